//! [`HexEditorPlugin`]: the world builder in Bevy. [`HexMapEdit`] messages (a stroke, undo,
//! redo, save) run in order on the core's [`Editor`], one at a time on the async compute pool;
//! each applied operation becomes a new [`HexMap`] generation in which only the chunks it changed
//! are out of date, so streaming rebuilds those (on the pool, the old meshes shown until the new
//! ones are in) and nothing else. Tile states (fog, owners) stay: an edit keeps the map's id.

use std::collections::VecDeque;
use std::path::{Path, PathBuf};

use bevy::prelude::*;
use bevy::tasks::futures::check_ready;
use bevy::tasks::{AsyncComputeTaskPool, IoTaskPool, Task};
use hex_terrain::{Change, EditError, Editor, MapConfig, Stroke, TileEdit};

use crate::HexTerrainSystems;
use crate::map::{HexMap, HexMapError, HexMapHandle};

/// Asks the world builder to change the map: each message is one operation, run in the order
/// sent (a save writes the edits as they are after the messages before it).
///
/// ```no_run
/// use bevy::prelude::*;
/// use bevy_hex_terrain::prelude::*;
/// use bevy_hex_terrain::hex_terrain::{Brush, Stroke, Tool};
///
/// fn raise_under_cursor(tile: Hex, mut edits: MessageWriter<HexMapEdit>) {
///     edits.write(HexMapEdit::Stroke(Stroke { tool: Tool::Raise(0.05), brush: Brush::Range(2), tile }));
/// }
/// ```
#[derive(Message, Debug, Clone, PartialEq, Reflect)]
pub enum HexMapEdit {
    /// Applies a stroke as one operation (what it cannot do is a [`HexMapError::Edit`]).
    Stroke(Stroke),
    /// Takes the last operation back (nothing when there is none).
    Undo,
    /// Applies the last undone operation again (nothing when there is none).
    Redo,
    /// Writes the edited map's file (the seed's config plus its `edits`, a delta a person can
    /// read) to a path of the file system, replacing it whole or not at all; then
    /// [`HexMapSaved`], or [`HexMapError::Unwritable`] with the edits kept in memory.
    Save(PathBuf),
}

/// Which operation a [`HexMapEdited`] reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Reflect)]
pub enum EditAction {
    /// A stroke was applied.
    Stroke,
    /// An operation was taken back.
    Undo,
    /// An undone operation was applied again.
    Redo,
}

/// The map was edited: [`HexMap`] holds the new terrain (generation `generation`) and the chunks
/// of `change` are being rebuilt; every other chunk keeps its mesh.
#[derive(Message, Debug, Clone, PartialEq, Reflect)]
pub struct HexMapEdited {
    /// What was done.
    pub action: EditAction,
    /// The tiles and chunks it changed.
    pub change: Change,
    /// The [`HexMap::generation`] it made.
    pub generation: u64,
}

/// An operation ran and changed nothing: a stroke that sets what its tiles already have, or an
/// undo or redo with nothing to take back or apply again. [`HexMap`] is as it was (no new
/// generation); every [`HexMapEdit`] other than a save is answered by exactly one of
/// [`HexMapEdited`], this, or [`HexMapError`].
#[derive(Message, Debug, Clone, Copy, PartialEq, Eq, Reflect)]
pub struct HexMapUnchanged {
    /// What was asked.
    pub action: EditAction,
}

/// The edited map's file was written.
#[derive(Message, Debug, Clone, PartialEq, Eq, Reflect)]
pub struct HexMapSaved {
    /// Where.
    pub path: PathBuf,
    /// How many edited tiles it lists.
    pub edits: usize,
}

/// The world builder's state: the core [`Editor`] following [`HexMap`], the operations waiting
/// and the one running. Read it for the undo and redo counts and the edits; change the map with
/// [`HexMapEdit`] messages.
#[derive(Resource, Default, Reflect)]
#[reflect(Resource, Default)]
pub struct HexEditor {
    /// The editor, when no task holds it.
    #[reflect(ignore)]
    editor: Option<Editor>,
    /// The [`HexMap::generation`] the editor's terrain is.
    follows: Option<u64>,
    /// Operations waiting for the running one.
    queue: VecDeque<HexMapEdit>,
    /// The operation running: the editor, what it did, the generation it started from.
    #[reflect(ignore)]
    running: Option<Task<Outcome>>,
    /// Files being written.
    #[reflect(ignore)]
    saving: Vec<Task<Result<HexMapSaved, (PathBuf, String)>>>,
    /// Figures of the editor as of the last operation.
    counts: Counts,
}

/// What a finished operation hands back.
struct Outcome {
    editor: Editor,
    action: EditAction,
    result: Result<Option<Change>, EditError>,
    from: u64,
}

/// Undo and redo depths and the edited tiles, kept for reading while a task holds the editor.
#[derive(Debug, Clone, Copy, Default, Reflect)]
struct Counts {
    undo: usize,
    redo: usize,
    edits: usize,
}

impl HexEditor {
    /// Operations [`HexMapEdit::Undo`] can take back.
    #[must_use]
    pub fn undo_len(&self) -> usize {
        self.counts.undo
    }

    /// Operations [`HexMapEdit::Redo`] can apply again.
    #[must_use]
    pub fn redo_len(&self) -> usize {
        self.counts.redo
    }

    /// Edited tiles of the map.
    #[must_use]
    pub fn edited_tiles(&self) -> usize {
        self.counts.edits
    }

    /// Whether an operation is running or waiting.
    #[must_use]
    pub fn is_busy(&self) -> bool {
        self.running.is_some() || !self.queue.is_empty()
    }

    /// The edits as of the last finished operation (what a save writes); `None` while an
    /// operation runs.
    #[must_use]
    pub fn edits(&self) -> Option<Vec<TileEdit>> {
        self.editor.as_ref().map(Editor::edits)
    }

    /// The editor following the map: the one held, or a new one when the map is another
    /// generation than the editor's (a reload or another map: its undo history starts anew).
    fn take_editor(&mut self, map: &HexMap) -> Editor {
        match self.editor.take() {
            Some(editor) if self.follows == Some(map.generation()) => editor,
            _ => {
                self.follows = Some(map.generation());
                Editor::from_terrain((**map.terrain()).clone())
            }
        }
    }

    fn count(&mut self, editor: &Editor) {
        self.counts = Counts { undo: editor.undo_len(), redo: editor.redo_len(), edits: editor.edited_tiles() };
    }
}

/// The world builder: [`HexEditor`], [`HexMapEdit`] in, [`HexMapEdited`] (or
/// [`HexMapUnchanged`]) and [`HexMapSaved`] out, refusals as [`HexMapError`]; its system runs in [`HexTerrainSystems::Map`], after the map
/// assets. Needs [`HexMapPlugin`](crate::HexMapPlugin).
///
/// A hot reload of the map file (or another map) replaces the terrain and starts a new undo
/// history: the file wins over unsaved edits, so save first. Saving over the followed map file
/// reloads nothing (the file holds the map already shown).
#[derive(Debug, Clone, Copy, Default)]
pub struct HexEditorPlugin;

impl Plugin for HexEditorPlugin {
    fn build(&self, app: &mut App) {
        if !app.is_plugin_added::<crate::HexMapPlugin>() {
            panic!("HexEditorPlugin needs HexMapPlugin: add HexTerrainPlugins (or HexMapPlugin before it)");
        }
        app.init_resource::<HexEditor>()
            .register_type::<HexEditor>()
            .add_message::<HexMapEdit>()
            .add_message::<HexMapEdited>()
            .add_message::<HexMapUnchanged>()
            .add_message::<HexMapSaved>()
            .register_type::<HexMapEdit>()
            .register_type::<HexMapEdited>()
            .register_type::<HexMapUnchanged>()
            .register_type::<HexMapSaved>()
            .add_systems(Update, run_edits.after(crate::map::MapAssets).in_set(HexTerrainSystems::Map));
    }
}

/// The messages [`run_edits`] writes.
#[derive(bevy::ecs::system::SystemParam)]
struct EditReports<'w> {
    edited: MessageWriter<'w, HexMapEdited>,
    unchanged: MessageWriter<'w, HexMapUnchanged>,
    saved: MessageWriter<'w, HexMapSaved>,
    errors: MessageWriter<'w, HexMapError>,
}

/// Takes a finished operation's result into [`HexMap`], queues new messages, starts the next
/// operation, and reports finished saves. Never blocks on a task.
fn run_edits(
    mut state: ResMut<HexEditor>,
    mut map: ResMut<HexMap>,
    handle: Res<HexMapHandle>,
    mut requests: MessageReader<HexMapEdit>,
    mut reports: EditReports,
) {
    let state = &mut *state;
    if let Some(outcome) = state.running.as_mut().and_then(check_ready) {
        state.running = None;
        let name = handle.handle().and_then(|h| h.path()).map_or_else(|| "map".to_owned(), |p| format!("map {p}"));
        finish(state, &mut map, outcome, &name, &mut reports);
    }
    state.queue.extend(requests.read().cloned());
    state.saving.retain_mut(|task| match check_ready(task) {
        Some(Ok(saved)) => {
            info!("hex terrain: {} edited tiles saved to {}", saved.edits, saved.path.display());
            reports.saved.write(saved);
            false
        }
        Some(Err((path, message))) => {
            let error = HexMapError::Unwritable { path: path.display().to_string(), message };
            error!("{error}");
            reports.errors.write(error);
            false
        }
        None => true,
    });
    if state.running.is_some() || map.is_waiting_for_asset() {
        return;
    }
    while let Some(request) = state.queue.pop_front() {
        let mut editor = state.take_editor(&map);
        let (stroke, action) = match request {
            HexMapEdit::Save(path) => {
                let config = editor.config();
                state.editor = Some(editor);
                let edits = config.edits.len();
                state.saving.push(IoTaskPool::get().spawn(async move { save(&path, &config, edits) }));
                continue;
            }
            HexMapEdit::Stroke(stroke) => (Some(stroke), EditAction::Stroke),
            HexMapEdit::Undo => (None, EditAction::Undo),
            HexMapEdit::Redo => (None, EditAction::Redo),
        };
        let generation = map.generation();
        state.running = Some(AsyncComputeTaskPool::get().spawn(async move {
            let result = match (stroke, action) {
                (Some(stroke), _) => editor.apply(stroke).map(Some),
                (None, EditAction::Undo) => Ok(editor.undo()),
                (None, _) => Ok(editor.redo()),
            };
            Outcome { editor, action, result, from: generation }
        }));
        break;
    }
}

/// Applies a finished operation to the map, or reports why it was not.
fn finish(state: &mut HexEditor, map: &mut HexMap, outcome: Outcome, name: &str, reports: &mut EditReports) {
    let Outcome { editor, action, result, from } = outcome;
    if map.generation() != from {
        // The map was reloaded or switched while the operation ran: the new map wins.
        state.editor = None;
        let message = format!("{action:?} dropped: the map changed while it ran");
        let error = HexMapError::Edit { map: name.to_owned(), message };
        warn!("{error}");
        reports.errors.write(error);
        return;
    }
    state.count(&editor);
    match result {
        Ok(Some(change)) if !change.is_empty() => {
            map.edit(editor.terrain().clone(), &change.chunks);
            state.follows = Some(map.generation());
            reports.edited.write(HexMapEdited { action, change, generation: map.generation() });
        }
        Ok(_) => {
            reports.unchanged.write(HexMapUnchanged { action });
        }
        Err(e) => {
            let error = HexMapError::Edit { map: name.to_owned(), message: e.to_string() };
            warn!("{error}");
            reports.errors.write(error);
        }
    }
    state.editor = Some(editor);
}

/// Writes a map file whole or not at all: to a file beside it, then renamed over it.
fn save(path: &Path, config: &MapConfig, edits: usize) -> Result<HexMapSaved, (PathBuf, String)> {
    let fail = |e: std::io::Error| (path.to_path_buf(), e.to_string());
    let mut part = path.as_os_str().to_owned();
    part.push(".part");
    let part = PathBuf::from(part);
    std::fs::write(&part, config.to_ron()).map_err(fail)?;
    std::fs::rename(&part, path).map_err(|e| {
        let _ = std::fs::remove_file(&part);
        fail(e)
    })?;
    Ok(HexMapSaved { path: path.to_path_buf(), edits })
}
