//! The world builder on a globe: [`HexGlobeEditorPlugin`] runs `HexMapEdit<GlobeStroke>`
//! messages on the core's [`GlobeEditor`], one operation at a time on the async compute pool, as
//! the flat map's editor does; each applied operation becomes a new [`HexGlobe`] generation in
//! which only the chunks it changed are out of date, so streaming builds those again (the old
//! meshes shown until the new ones are in) and nothing else. The tile states stay (an edit keeps
//! the globe's tiles), and units standing on tiles are put back on the edited surface.

use bevy::prelude::*;
use hex_terrain::{GlobeChange, GlobeEditor, GlobeStroke, TileEdit};

use super::HexGlobe;
use crate::HexTerrainSystems;
use crate::editor::{EditReports, Edited, Report, Request, Session};
use crate::{HexMapEdit, HexMapEdited, HexMapSaved, HexMapUnchanged};

/// The globe's world builder: the core [`GlobeEditor`] following [`HexGlobe`], the operations
/// waiting and the one running. Read it for the undo and redo counts and the edits; change the
/// globe with `HexMapEdit<GlobeStroke>` messages.
#[derive(Resource, Default, Reflect)]
#[reflect(Resource, Default)]
pub struct HexGlobeEditor {
    /// The operations and the editor (not reflected: a task holds the editor while one runs).
    #[reflect(ignore)]
    session: Session<GlobeEditor>,
}

impl HexGlobeEditor {
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

    /// Edited tiles of the globe.
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
    /// operation runs or before the first.
    #[must_use]
    pub fn edits(&self) -> Option<Vec<TileEdit>> {
        self.session.edits()
    }
}

impl Edited<GlobeEditor> for HexGlobe {
    fn generation(&self) -> u64 {
        HexGlobe::generation(self)
    }
    fn is_waiting(&self) -> bool {
        self.globe.is_none()
    }
    fn new_editor(&self) -> Option<GlobeEditor> {
        self.globe.as_ref().map(|g| GlobeEditor::from_globe((**g).clone()))
    }
    fn take_edit(&mut self, editor: &GlobeEditor, change: &GlobeChange) {
        self.edit(editor.globe().clone(), &change.chunks);
    }
}

/// The world builder on a globe: [`HexGlobeEditor`], `HexMapEdit<GlobeStroke>` in,
/// `HexMapEdited<GlobeChange>` (or [`HexMapUnchanged`]) and [`HexMapSaved`] out, refusals as
/// [`HexMapError`](crate::HexMapError) (a tool globes do not have, a tile not on the globe, a brush too wide); its
/// system runs in [`HexTerrainSystems::Map`], after the globe's file is applied. Needs
/// [`HexGlobePlugin`](super::HexGlobePlugin).
///
/// A hot reload of the globe's file replaces the globe and starts a new undo history: the file
/// wins over unsaved edits, so save first.
///
/// ```no_run
/// use bevy::prelude::*;
/// use bevy_hex_terrain::prelude::*;
/// use bevy_hex_terrain::HoveredGlobeTile;
/// use bevy_hex_terrain::hex_terrain::GlobeStroke;
///
/// fn raise_hovered(hovered: Res<HoveredGlobeTile>, mut edits: MessageWriter<HexMapEdit<GlobeStroke>>) {
///     if let Some(tile) = hovered.tile() {
///         edits.write(HexMapEdit::Stroke(GlobeStroke { tool: Tool::Raise(0.05), brush: Brush::Range(1), tile }));
///     }
/// }
///
/// App::new()
///     .add_plugins((
///         DefaultPlugins,
///         HexGlobePlugin::from_asset("maps/globe/continents.map.ron"),
///         HexGlobeEditorPlugin,
///     ))
///     .add_systems(Update, raise_hovered);
/// ```
#[derive(Debug, Clone, Copy, Default)]
pub struct HexGlobeEditorPlugin;

impl Plugin for HexGlobeEditorPlugin {
    fn build(&self, app: &mut App) {
        if !app.is_plugin_added::<super::HexGlobePlugin>() {
            panic!("HexGlobeEditorPlugin needs HexGlobePlugin: add it before");
        }
        app.init_resource::<HexGlobeEditor>()
            .register_type::<HexGlobeEditor>()
            .add_message::<HexMapEdit<GlobeStroke>>()
            .add_message::<HexMapEdited<GlobeChange>>()
            .add_message::<HexMapUnchanged>()
            .add_message::<HexMapSaved>()
            .register_type::<HexMapEdit<GlobeStroke>>()
            .register_type::<HexMapEdited<GlobeChange>>()
            .register_type::<HexMapUnchanged>()
            .register_type::<HexMapSaved>()
            .add_systems(Update, run_edits.after(super::apply_asset).in_set(HexTerrainSystems::Map));
    }
}

/// Runs the world builder's operations on the globe.
fn run_edits(
    mut state: ResMut<HexGlobeEditor>,
    mut globe: ResMut<HexGlobe>,
    mut requests: MessageReader<HexMapEdit<GlobeStroke>>,
    mut reports: EditReports<HexMapEdited<GlobeChange>>,
) {
    let name =
        globe.handle.as_ref().and_then(|h| h.path()).map_or_else(|| "globe".to_owned(), |p| format!("globe {p}"));
    // Read without marking it changed; changed when an edit is shown.
    let done = state.session.run(globe.bypass_change_detection(), requests.read().cloned().map(Request::from), &name);
    if done.iter().any(Report::is_edit) {
        globe.set_changed();
    }
    reports.write(done, |action, change, generation| HexMapEdited { action, change, generation });
}
