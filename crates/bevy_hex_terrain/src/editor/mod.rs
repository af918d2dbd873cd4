//! [`HexEditorPlugin`]: the world builder in Bevy. [`HexMapEdit`] messages (a stroke, undo,
//! redo, save) run in order on the core's [`Editor`], one at a time on the async compute pool;
//! each applied operation becomes a new [`HexMap`] generation in which only the chunks it changed
//! are out of date, so streaming rebuilds those (on the pool, the old meshes shown until the new
//! ones are in) and nothing else. Tile states (fog, owners) stay: an edit keeps the map's id.

mod session;

use std::path::PathBuf;

use bevy::prelude::*;
use hex_terrain::{Change, Editor, Stroke, TileEdit};

pub(crate) use session::{Edited, Report, Request, Session};

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
///
/// On a globe ([`HexGlobeEditorPlugin`](crate::HexGlobeEditorPlugin)) the strokes are
/// [`GlobeStroke`](hex_terrain::GlobeStroke)s: `HexMapEdit<GlobeStroke>`.
#[derive(Message, Debug, Clone, PartialEq, Reflect)]
pub enum HexMapEdit<S = Stroke> {
    /// Applies a stroke as one operation (what it cannot do is a [`HexMapError::Edit`]).
    Stroke(S),
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
/// of `change` are being rebuilt; every other chunk keeps its mesh. On a globe,
/// `HexMapEdited<GlobeChange>` and [`HexGlobe`](crate::HexGlobe).
#[derive(Message, Debug, Clone, PartialEq, Reflect)]
pub struct HexMapEdited<C = Change> {
    /// What was done.
    pub action: EditAction,
    /// The tiles and chunks it changed.
    pub change: C,
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
    /// The operations and the editor (not reflected: a task holds the editor while one runs).
    #[reflect(ignore)]
    session: Session<Editor>,
}

impl HexEditor {
    /// Operations [`HexMapEdit::Undo`] can take back.
    #[must_use]
    pub fn undo_len(&self) -> usize {
        self.session.counts.undo
    }

    /// Operations [`HexMapEdit::Redo`] can apply again.
    #[must_use]
    pub fn redo_len(&self) -> usize {
        self.session.counts.redo
    }

    /// Edited tiles of the map.
    #[must_use]
    pub fn edited_tiles(&self) -> usize {
        self.session.counts.edits
    }

    /// Whether an operation is running or waiting.
    #[must_use]
    pub fn is_busy(&self) -> bool {
        self.session.is_busy()
    }

    /// The edits as of the last finished operation (what a save writes); `None` while an
    /// operation runs.
    #[must_use]
    pub fn edits(&self) -> Option<Vec<TileEdit>> {
        self.session.edits()
    }
}

impl Edited<Editor> for HexMap {
    fn generation(&self) -> u64 {
        HexMap::generation(self)
    }
    fn is_waiting(&self) -> bool {
        self.is_waiting_for_asset()
    }
    fn new_editor(&self) -> Option<Editor> {
        Some(Editor::from_terrain((**self.terrain()).clone()))
    }
    fn take_edit(&mut self, editor: &Editor, change: &Change) {
        self.edit(editor.terrain().clone(), &change.chunks);
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

/// The messages [`run_edits`] writes (a globe's editor writes the same but its edits).
#[derive(bevy::ecs::system::SystemParam)]
pub(crate) struct EditReports<'w, M: Message> {
    edited: MessageWriter<'w, M>,
    unchanged: MessageWriter<'w, HexMapUnchanged>,
    saved: MessageWriter<'w, HexMapSaved>,
    errors: MessageWriter<'w, HexMapError>,
}

impl<M: Message> EditReports<'_, M> {
    /// Writes each report as its message, an edit as `edited` makes it.
    pub(crate) fn write<C>(&mut self, reports: Vec<Report<C>>, edited: impl Fn(EditAction, C, u64) -> M) {
        for report in reports {
            match report {
                Report::Edited { action, change, generation } => {
                    self.edited.write(edited(action, change, generation));
                }
                Report::Unchanged(action) => {
                    self.unchanged.write(HexMapUnchanged { action });
                }
                Report::Saved(saved) => {
                    self.saved.write(saved);
                }
                Report::Error(error) => {
                    self.errors.write(error);
                }
            }
        }
    }
}

impl<S> From<HexMapEdit<S>> for Request<S> {
    fn from(edit: HexMapEdit<S>) -> Self {
        match edit {
            HexMapEdit::Stroke(stroke) => Request::Stroke(stroke),
            HexMapEdit::Undo => Request::Undo,
            HexMapEdit::Redo => Request::Redo,
            HexMapEdit::Save(path) => Request::Save(path),
        }
    }
}

/// Runs the world builder's operations on the map (see [`Session::run`]).
fn run_edits(
    mut state: ResMut<HexEditor>,
    mut map: ResMut<HexMap>,
    handle: Res<HexMapHandle>,
    mut requests: MessageReader<HexMapEdit>,
    mut reports: EditReports<HexMapEdited>,
) {
    let name = handle.handle().and_then(|h| h.path()).map_or_else(|| "map".to_owned(), |p| format!("map {p}"));
    // Read without marking it changed; changed when an edit is shown.
    let done = state.session.run(map.bypass_change_detection(), requests.read().cloned().map(Request::from), &name);
    if done.iter().any(Report::is_edit) {
        map.set_changed();
    }
    reports.write(done, |action, change, generation| HexMapEdited { action, change, generation });
}
