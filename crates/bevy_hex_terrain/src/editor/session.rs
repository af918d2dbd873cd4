//! The world builder's running of operations, for a flat map's editor and a globe's alike: the
//! messages wait in order, one operation at a time runs on the async compute pool holding the
//! core editor, saves are written on the I/O pool, and a finished operation is handed to the
//! map or globe it was made for (or dropped when that changed while it ran).

use std::collections::VecDeque;
use std::path::{Path, PathBuf};

use bevy::prelude::*;
use bevy::tasks::futures::check_ready;
use bevy::tasks::{AsyncComputeTaskPool, IoTaskPool, Task};
use hex_terrain::{Change, EditError, Editor, GlobeChange, GlobeEditor, GlobeStroke, MapConfig, Stroke, TileEdit};

use super::{EditAction, HexMapSaved};
use crate::map::HexMapError;

/// What one message asks of an editor.
#[derive(Debug, Clone)]
pub(crate) enum Request<S> {
    Stroke(S),
    Undo,
    Redo,
    Save(PathBuf),
}

/// A core editor: a flat map's [`Editor`] or a globe's [`GlobeEditor`].
pub(crate) trait CoreEditor: Send + Sized + 'static {
    type Stroke: Send + 'static;
    type Change: Send + 'static;
    fn apply(&mut self, stroke: Self::Stroke) -> Result<Self::Change, EditError>;
    fn undo(&mut self) -> Option<Self::Change>;
    fn redo(&mut self) -> Option<Self::Change>;
    fn changes_nothing(change: &Self::Change) -> bool;
    fn config(&self) -> MapConfig;
    fn edits(&self) -> Vec<TileEdit>;
    fn counts(&self) -> Counts;
}

impl CoreEditor for Editor {
    type Stroke = Stroke;
    type Change = Change;
    fn apply(&mut self, stroke: Stroke) -> Result<Change, EditError> {
        Editor::apply(self, stroke)
    }
    fn undo(&mut self) -> Option<Change> {
        Editor::undo(self)
    }
    fn redo(&mut self) -> Option<Change> {
        Editor::redo(self)
    }
    fn changes_nothing(change: &Change) -> bool {
        change.is_empty()
    }
    fn config(&self) -> MapConfig {
        Editor::config(self)
    }
    fn edits(&self) -> Vec<TileEdit> {
        Editor::edits(self)
    }
    fn counts(&self) -> Counts {
        Counts { undo: self.undo_len(), redo: self.redo_len(), edits: self.edited_tiles() }
    }
}

impl CoreEditor for GlobeEditor {
    type Stroke = GlobeStroke;
    type Change = GlobeChange;
    fn apply(&mut self, stroke: GlobeStroke) -> Result<GlobeChange, EditError> {
        GlobeEditor::apply(self, stroke)
    }
    fn undo(&mut self) -> Option<GlobeChange> {
        GlobeEditor::undo(self)
    }
    fn redo(&mut self) -> Option<GlobeChange> {
        GlobeEditor::redo(self)
    }
    fn changes_nothing(change: &GlobeChange) -> bool {
        change.is_empty()
    }
    fn config(&self) -> MapConfig {
        GlobeEditor::config(self)
    }
    fn edits(&self) -> Vec<TileEdit> {
        GlobeEditor::edits(self)
    }
    fn counts(&self) -> Counts {
        Counts { undo: self.undo_len(), redo: self.redo_len(), edits: self.edited_tiles() }
    }
}

/// What an editor edits: the map or the globe shown.
pub(crate) trait Edited<E: CoreEditor> {
    /// Grows with each config applied and each edit.
    fn generation(&self) -> u64;
    /// Whether its file is still loading (operations wait).
    fn is_waiting(&self) -> bool;
    /// A new editor of what is shown; `None` while nothing is.
    fn new_editor(&self) -> Option<E>;
    /// Shows the editor's terrain, a new generation in which `change`'s chunks are out of date.
    fn take_edit(&mut self, editor: &E, change: &E::Change);
}

/// Undo and redo depths and the edited tiles, kept for reading while a task holds the editor.
#[derive(Debug, Clone, Copy, Default, Reflect)]
pub(crate) struct Counts {
    pub undo: usize,
    pub redo: usize,
    pub edits: usize,
}

/// What a finished operation hands back.
struct Outcome<E: CoreEditor> {
    editor: E,
    action: EditAction,
    result: Result<Option<E::Change>, EditError>,
    from: u64,
}

/// What [`Session::run`] has to say: each becomes a message.
pub(crate) enum Report<C> {
    Edited { action: EditAction, change: C, generation: u64 },
    Unchanged(EditAction),
    Saved(HexMapSaved),
    Error(HexMapError),
}

impl<C> Report<C> {
    /// Whether it reports an edit shown.
    pub fn is_edit(&self) -> bool {
        matches!(self, Report::Edited { .. })
    }
}

/// An editor's queue, its running operation and its saves.
pub(crate) struct Session<E: CoreEditor> {
    /// The editor, when no task holds it.
    editor: Option<E>,
    /// The generation the editor's terrain is.
    follows: Option<u64>,
    queue: VecDeque<Request<E::Stroke>>,
    running: Option<Task<Outcome<E>>>,
    saving: Vec<Task<Result<HexMapSaved, (PathBuf, String)>>>,
    pub counts: Counts,
}

impl<E: CoreEditor> Default for Session<E> {
    fn default() -> Self {
        Self {
            editor: None,
            follows: None,
            queue: VecDeque::new(),
            running: None,
            saving: Vec::new(),
            counts: Counts::default(),
        }
    }
}

impl<E: CoreEditor> Session<E> {
    /// Whether an operation is running or waiting.
    pub fn is_busy(&self) -> bool {
        self.running.is_some() || !self.queue.is_empty()
    }

    /// The edits as of the last finished operation; `None` while one runs (or before the
    /// first).
    pub fn edits(&self) -> Option<Vec<TileEdit>> {
        self.editor.as_ref().map(E::edits)
    }

    /// Takes a finished operation's result into `target`, queues `requests`, starts the next
    /// operation, and reports finished saves. Never blocks on a task. `name` names the map or
    /// globe in errors.
    pub fn run(
        &mut self,
        target: &mut impl Edited<E>,
        requests: impl IntoIterator<Item = Request<E::Stroke>>,
        name: &str,
    ) -> Vec<Report<E::Change>> {
        let mut reports = Vec::new();
        if let Some(outcome) = self.running.as_mut().and_then(check_ready) {
            self.running = None;
            reports.extend(self.finish(target, outcome, name));
        }
        self.queue.extend(requests);
        self.saving.retain_mut(|task| match check_ready(task) {
            Some(Ok(saved)) => {
                info!("hex terrain: {} edited tiles saved to {}", saved.edits, saved.path.display());
                reports.push(Report::Saved(saved));
                false
            }
            Some(Err((path, message))) => {
                let error = HexMapError::Unwritable { path: path.display().to_string(), message };
                error!("{error}");
                reports.push(Report::Error(error));
                false
            }
            None => true,
        });
        if self.running.is_some() || target.is_waiting() {
            return reports;
        }
        while let Some(request) = self.queue.pop_front() {
            let Some(mut editor) = self.take_editor(target) else {
                self.queue.push_front(request);
                break;
            };
            let (stroke, action) = match request {
                Request::Save(path) => {
                    let config = editor.config();
                    self.editor = Some(editor);
                    let edits = config.edits.len();
                    self.saving.push(IoTaskPool::get().spawn(async move { save(&path, &config, edits) }));
                    continue;
                }
                Request::Stroke(stroke) => (Some(stroke), EditAction::Stroke),
                Request::Undo => (None, EditAction::Undo),
                Request::Redo => (None, EditAction::Redo),
            };
            let from = target.generation();
            self.running = Some(AsyncComputeTaskPool::get().spawn(async move {
                let result = match (stroke, action) {
                    (Some(stroke), _) => editor.apply(stroke).map(Some),
                    (None, EditAction::Undo) => Ok(editor.undo()),
                    (None, _) => Ok(editor.redo()),
                };
                Outcome { editor, action, result, from }
            }));
            break;
        }
        reports
    }

    /// The editor following `target`: the one held, or a new one when `target` is another
    /// generation than the editor's (a reload or another map: its undo history starts anew).
    fn take_editor(&mut self, target: &impl Edited<E>) -> Option<E> {
        match self.editor.take() {
            Some(editor) if self.follows == Some(target.generation()) => Some(editor),
            _ => {
                self.follows = Some(target.generation());
                target.new_editor()
            }
        }
    }

    /// Applies a finished operation to `target`, or says why it was not.
    fn finish(&mut self, target: &mut impl Edited<E>, outcome: Outcome<E>, name: &str) -> Option<Report<E::Change>> {
        let Outcome { editor, action, result, from } = outcome;
        if target.generation() != from {
            // The map was reloaded or switched while the operation ran: the new map wins.
            self.editor = None;
            let message = format!("{action:?} dropped: the map changed while it ran");
            let error = HexMapError::Edit { map: name.to_owned(), message };
            warn!("{error}");
            return Some(Report::Error(error));
        }
        self.counts = editor.counts();
        let report = match result {
            Ok(Some(change)) if !E::changes_nothing(&change) => {
                target.take_edit(&editor, &change);
                self.follows = Some(target.generation());
                Report::Edited { action, change, generation: target.generation() }
            }
            Ok(_) => Report::Unchanged(action),
            Err(e) => {
                let error = HexMapError::Edit { map: name.to_owned(), message: e.to_string() };
                warn!("{error}");
                Report::Error(error)
            }
        };
        self.editor = Some(editor);
        Some(report)
    }
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
