//! The world builder (Tab): paint the map with the mouse, with a tool and a brush picked in the
//! panel (or keys 1-9, `[` and `]` for the radius, F for flood fill); Ctrl+Z undoes, Ctrl+Y or
//! Ctrl+Shift+Z redoes, Ctrl+S saves the edits next to the map (`<map>.edited.map.ron`). Every
//! stroke is one `HexMapEdit` message: the plugin applies it on the task pool and rebuilds only
//! the chunks it changed.

use std::path::PathBuf;

use bevy::asset::io::file::FileAssetReader;
use bevy::prelude::*;
use bevy_hex_terrain::hex_terrain::{Brush, FeatureEdit, PropDensity, RuleId, Stroke, Tool};
use bevy_hex_terrain::prelude::*;
use bevy_hex_terrain::{HexMapHandle, HexMapSaved};

use crate::{DIGITS, Game};

/// The tools of the panel, in key order (1-9).
/// The fifth paints terrains (Shift: features) on a map with its own terrain ruleset.
const TOOLS: [&str; 9] = ["Raise", "Lower", "Smooth", "Type", "Biome", "River", "Lake", "Props", "Erase"];
/// The types the Type tool cycles through.
const KINDS: [TileKind; 3] = [TileKind::Sea, TileKind::Land, TileKind::Mountain];
/// The biomes the Biome tool cycles through (land biomes: water comes from height).
const BIOMES: [Biome; 8] = [
    Biome::Grassland,
    Biome::Plains,
    Biome::Forest,
    Biome::Rainforest,
    Biome::Desert,
    Biome::Tundra,
    Biome::Snow,
    Biome::Hills,
];
const DENSITIES: [PropDensity; 3] = [PropDensity::Dense, PropDensity::Sparse, PropDensity::None];
/// Largest brush radius of the panel.
const MAX_RADIUS: u32 = 5;

/// The editor's state: the tool, its value, the brush (whether it is open is `Game::editing`).
#[derive(Resource, Debug, Default)]
pub(crate) struct EditorMode {
    tool: usize,
    /// Which of the tool's values (type, biome, density) is picked.
    value: usize,
    radius: u32,
    flood: bool,
    /// The tile of the last stroke while the button is held (a drag paints each tile once).
    last: Option<Hex>,
    /// What the last save or refusal said.
    status: String,
}

impl EditorMode {
    /// The tool as the core takes it; Shift takes the other way (remove a river, drain a lake;
    /// hills rather than a type, on and off in turn; a feature rather than a terrain). On a map with its own terrain ruleset (`ruleset`) the
    /// fifth tool paints its terrains, or with Shift its features (and none), in turn.
    fn tool(&self, shift: bool, ruleset: Option<&TerrainRuleset>) -> Tool {
        match self.tool {
            0 => Tool::Raise(0.05),
            1 => Tool::Lower(0.05),
            2 => Tool::Smooth,
            3 if shift => Tool::SetHills(self.value.is_multiple_of(2)),
            3 => Tool::SetKind(KINDS[self.value % KINDS.len()]),
            4 => match ruleset {
                Some(ruleset) => {
                    let id = |s: &str| RuleId::new(s).expect("a validated ruleset's ids fit");
                    if shift {
                        match ruleset.features.get(self.value % (ruleset.features.len() + 1)) {
                            Some(f) => Tool::SetFeature(FeatureEdit::Grow(id(&f.id))),
                            None => Tool::SetFeature(FeatureEdit::Clear),
                        }
                    } else {
                        Tool::SetTerrain(id(&ruleset.terrains[self.value % ruleset.terrains.len()].id))
                    }
                }
                None => Tool::SetBiome(BIOMES[self.value % BIOMES.len()]),
            },
            5 if shift => Tool::RemoveRiver,
            5 => Tool::AddRiver,
            6 if shift => Tool::DrainLake,
            6 => Tool::FillLake,
            7 => Tool::SetProps(DENSITIES[self.value % DENSITIES.len()]),
            _ => Tool::Erase,
        }
    }

    fn brush(&self) -> Brush {
        match (self.flood, self.tool) {
            (true, 4) => Brush::FloodTerrain,
            (true, _) => Brush::Flood,
            (false, _) => Brush::Range(self.radius),
        }
    }

    /// Picks tool `i`; picking the tool already picked cycles its value.
    fn pick(&mut self, i: usize) {
        if self.tool == i {
            self.value += 1;
        } else {
            self.tool = i;
            self.value = 0;
        }
    }

    fn describe(&self, ruleset: Option<&TerrainRuleset>) -> String {
        let tool = match self.tool(false, ruleset) {
            Tool::SetKind(k) => {
                let hills = if self.value.is_multiple_of(2) { "on hills" } else { "off hills" };
                format!("Type: {} (Shift: {hills})", k.name())
            }
            Tool::SetBiome(b) => format!("Biome: {}", b.name()),
            Tool::SetTerrain(t) => {
                let feature = match self.tool(true, ruleset) {
                    Tool::SetFeature(FeatureEdit::Grow(f)) => f.to_string(),
                    _ => "none".into(),
                };
                format!("Terrain: {t} (Shift: feature {feature})")
            }
            Tool::SetProps(d) => format!("Props: {d:?}"),
            Tool::AddRiver => "River (Shift: remove)".into(),
            Tool::FillLake => "Lake (Shift: drain)".into(),
            _ => TOOLS[self.tool].into(),
        };
        let brush = if self.flood { "flood fill".into() } else { format!("radius {}", self.radius) };
        format!("{tool}, {brush}")
    }
}

/// The editor's panel (shown while editing).
#[derive(Component)]
pub(crate) struct EditorPanel;

/// The panel's status line.
#[derive(Component)]
pub(crate) struct EditorStatus;

/// A button of the panel.
#[derive(Component, Clone, Copy)]
pub(crate) enum EditorButton {
    Tool(usize),
    Smaller,
    Larger,
    Flood,
    Undo,
    Redo,
    Save,
}

/// The panel: a column of tool buttons, the brush, undo, redo and save, and a status line.
pub(crate) fn spawn_panel(mut commands: Commands) {
    let button = |label: String, which: EditorButton| {
        (
            which,
            Button,
            Node { padding: UiRect::axes(px(8.0), px(3.0)), margin: UiRect::all(px(1.0)), ..default() },
            BackgroundColor(Color::srgb(0.15, 0.2, 0.3)),
            children![(Text::new(label), TextFont::from_font_size(13.0))],
        )
    };
    commands
        .spawn((
            EditorPanel,
            Visibility::Hidden,
            BackgroundColor(Color::srgba(0.05, 0.06, 0.09, 0.85)),
            Node {
                position_type: PositionType::Absolute,
                top: px(130.0),
                left: px(10.0),
                flex_direction: FlexDirection::Column,
                width: px(300.0),
                padding: UiRect::all(px(6.0)),
                ..default()
            },
        ))
        .with_children(|panel| {
            panel.spawn((Text::new("World builder (Tab)"), TextFont::from_font_size(14.0)));
            for (i, name) in TOOLS.iter().enumerate() {
                panel.spawn(button(format!("{} {name}", i + 1), EditorButton::Tool(i)));
            }
            panel.spawn(Node { flex_direction: FlexDirection::Row, ..default() }).with_children(|row| {
                row.spawn(button("[ smaller".into(), EditorButton::Smaller));
                row.spawn(button("] larger".into(), EditorButton::Larger));
                row.spawn(button("F flood".into(), EditorButton::Flood));
            });
            panel.spawn(Node { flex_direction: FlexDirection::Row, ..default() }).with_children(|row| {
                row.spawn(button("Undo".into(), EditorButton::Undo));
                row.spawn(button("Redo".into(), EditorButton::Redo));
                row.spawn(button("Save".into(), EditorButton::Save));
            });
            panel.spawn((EditorStatus, Text::new(""), TextFont::from_font_size(12.0)));
        });
}

/// Where Ctrl+S writes: beside the followed map file, as `<name>.edited.map.ron` (itself, when it
/// is already one), under the asset folder.
fn save_path(handle: &HexMapHandle) -> PathBuf {
    let asset = handle.handle().and_then(|h| h.path()).map(|p| p.path().to_path_buf());
    let asset = asset.unwrap_or_else(|| PathBuf::from("maps/untitled.map.ron"));
    let name = asset.file_name().and_then(|n| n.to_str()).unwrap_or("untitled.map.ron");
    let edited = if name.ends_with(".edited.map.ron") {
        name.to_owned()
    } else {
        format!("{}.edited.map.ron", name.trim_end_matches(".map.ron"))
    };
    FileAssetReader::get_base_path().join("assets").join(asset.with_file_name(edited))
}

/// Keys and panel buttons: Tab, tools, brush, undo, redo, save.
pub(crate) fn editor_input(
    keys: Res<ButtonInput<KeyCode>>,
    buttons: Query<(&Interaction, &EditorButton), Changed<Interaction>>,
    handle: Res<HexMapHandle>,
    (mut game, mut mode): (ResMut<Game>, ResMut<EditorMode>),
    mut panel: Query<&mut Visibility, With<EditorPanel>>,
    mut edits: MessageWriter<HexMapEdit>,
) {
    if keys.just_pressed(KeyCode::Tab) {
        game.editing = !game.editing;
        for mut v in &mut panel {
            *v = if game.editing { Visibility::Inherited } else { Visibility::Hidden };
        }
    }
    if !game.editing {
        return;
    }
    let ctrl = keys.any_pressed([KeyCode::ControlLeft, KeyCode::ControlRight]);
    let shift = keys.any_pressed([KeyCode::ShiftLeft, KeyCode::ShiftRight]);
    let mut pressed: Vec<EditorButton> =
        buttons.iter().filter(|(i, _)| **i == Interaction::Pressed).map(|(_, b)| *b).collect();
    for (i, key) in DIGITS.into_iter().enumerate() {
        if keys.just_pressed(key) {
            pressed.push(EditorButton::Tool(i));
        }
    }
    for (key, button) in [
        (KeyCode::BracketLeft, EditorButton::Smaller),
        (KeyCode::BracketRight, EditorButton::Larger),
        (KeyCode::KeyF, EditorButton::Flood),
    ] {
        if keys.just_pressed(key) {
            pressed.push(button);
        }
    }
    if ctrl && keys.just_pressed(KeyCode::KeyZ) {
        pressed.push(if shift { EditorButton::Redo } else { EditorButton::Undo });
    }
    if ctrl && keys.just_pressed(KeyCode::KeyY) {
        pressed.push(EditorButton::Redo);
    }
    if ctrl && keys.just_pressed(KeyCode::KeyS) {
        pressed.push(EditorButton::Save);
    }
    for button in pressed {
        match button {
            EditorButton::Tool(i) => mode.pick(i),
            EditorButton::Smaller => mode.radius = mode.radius.saturating_sub(1),
            EditorButton::Larger => mode.radius = (mode.radius + 1).min(MAX_RADIUS),
            EditorButton::Flood => mode.flood = !mode.flood,
            EditorButton::Undo => {
                edits.write(HexMapEdit::Undo);
            }
            EditorButton::Redo => {
                edits.write(HexMapEdit::Redo);
            }
            EditorButton::Save => {
                edits.write(HexMapEdit::Save(save_path(&handle)));
            }
        }
    }
}

/// The left button paints on the terrain: a stroke on pressing, and one on each new tile while
/// held.
pub(crate) fn paint(
    mouse: Res<ButtonInput<MouseButton>>,
    keys: Res<ButtonInput<KeyCode>>,
    game: Res<Game>,
    map: Res<HexMap>,
    mut mode: ResMut<EditorMode>,
    mut edits: MessageWriter<HexMapEdit>,
) {
    if !game.editing || !mouse.pressed(MouseButton::Left) {
        mode.last = None;
        return;
    }
    let Some(tile) = game.hovered else { return };
    if mode.last == Some(tile) {
        return;
    }
    mode.last = Some(tile);
    let shift = keys.any_pressed([KeyCode::ShiftLeft, KeyCode::ShiftRight]);
    let ruleset = map.terrain().has_own_ruleset().then(|| map.terrain().ruleset());
    edits.write(HexMapEdit::Stroke(Stroke { tool: mode.tool(shift, ruleset), brush: mode.brush(), tile }));
}

/// The brush's outline under the cursor: the outline of every tile it covers (the hovered tile
/// alone for a flood fill).
pub(crate) fn brush_outline(mode: Res<EditorMode>, game: Res<Game>, map: Res<HexMap>, mut gizmos: Gizmos) {
    let (true, Some(tile)) = (game.editing, game.hovered) else { return };
    let terrain = map.terrain();
    let brush = if mode.flood { Brush::Range(0) } else { mode.brush() };
    let corners = terrain.layout().center_aligned_hex_corners();
    let sea = terrain.sea_level();
    let color = if mode.flood { Color::srgb(0.3, 0.8, 1.0) } else { Color::srgb(1.0, 0.95, 0.4) };
    for t in brush.tiles(terrain, tile) {
        // The copy of the tile nearest the cursor, on a wrapping map.
        let t = map.tile_near(t, tile);
        let Some([x, y, z]) = terrain.tile_center(t) else { continue };
        let y = (y as f32).max(sea) + 0.08;
        let points = corners.map(|c| Vec3::new(x as f32 + c.x, y, z as f32 + c.y));
        for k in 0..6 {
            gizmos.line(points[k], points[(k + 1) % 6], color);
        }
    }
}

/// The panel: which tool is picked, the brush, undo and redo depths, the last save or refusal.
pub(crate) fn editor_panel(
    (game, map): (Res<Game>, Res<HexMap>),
    mut mode: ResMut<EditorMode>,
    editor: Res<HexEditor>,
    mut saved: MessageReader<HexMapSaved>,
    mut errors: MessageReader<HexMapError>,
    mut status: Query<&mut Text, With<EditorStatus>>,
    mut buttons: Query<(&EditorButton, &mut BackgroundColor)>,
) {
    for s in saved.read() {
        mode.status = format!("Saved {} edited tiles to {}", s.edits, s.path.display());
    }
    for e in errors.read() {
        mode.status = e.to_string();
    }
    if !game.editing {
        return;
    }
    let text = format!(
        "{}\n{} edited tiles, {} to undo, {} to redo{}\n{}",
        mode.describe(map.terrain().has_own_ruleset().then(|| map.terrain().ruleset())),
        editor.edited_tiles(),
        editor.undo_len(),
        editor.redo_len(),
        if editor.is_busy() { " (working)" } else { "" },
        mode.status
    );
    for mut t in &mut status {
        if t.0 != text {
            t.0.clone_from(&text);
        }
    }
    for (button, mut color) in &mut buttons {
        let on = match button {
            EditorButton::Tool(i) => *i == mode.tool,
            EditorButton::Flood => mode.flood,
            _ => false,
        };
        let want = if on { Color::srgb(0.55, 0.4, 0.1) } else { Color::srgb(0.15, 0.2, 0.3) };
        if color.0 != want {
            color.0 = want;
        }
    }
}

/// `HEXTERRAIN_EDITOR=1` starts in the editor; `HEXTERRAIN_EDIT=col,row` also paints a scripted
/// stroke set there once the map is in (for the README's pictures): mountains around the tile,
/// a lake dug to their north-west, a wood to their south and a river rising beside them.
pub(crate) fn from_env(
    map: Res<HexMap>,
    (mut game, mut mode): (ResMut<Game>, ResMut<EditorMode>),
    mut panel: Query<&mut Visibility, With<EditorPanel>>,
    mut edits: MessageWriter<HexMapEdit>,
    mut done: Local<bool>,
) {
    if *done || map.is_waiting_for_asset() {
        return;
    }
    *done = true;
    if std::env::var_os("HEXTERRAIN_EDITOR").is_some() {
        game.editing = true;
        for mut v in &mut panel {
            *v = Visibility::Inherited;
        }
    }
    let Some((col, row)) = std::env::var("HEXTERRAIN_EDIT").ok().and_then(|s| {
        let (c, r) = s.split_once(',')?;
        Some((c.trim().parse::<i32>().ok()?, r.trim().parse::<i32>().ok()?))
    }) else {
        return;
    };
    let at = |dc: i32, dr: i32| map.terrain().tile_from_offset([col + dc, row + dr]);
    for (tool, brush, tile) in [
        (Tool::SetKind(TileKind::Mountain), Brush::Range(1), at(0, 0)),
        (Tool::FillLake, Brush::Range(1), at(-3, -2)),
        (Tool::SetProps(PropDensity::Dense), Brush::Range(1), at(0, 4)),
        (Tool::AddRiver, Brush::Range(0), at(-2, 0)),
    ] {
        edits.write(HexMapEdit::Stroke(Stroke { tool, brush, tile }));
    }
    mode.tool = 0;
    mode.radius = 2;
}
