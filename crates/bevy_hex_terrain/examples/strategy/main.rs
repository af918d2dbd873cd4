//! A small turn-based strategy game on streamed hex terrain: pan (WASD/arrows or the screen
//! edge), zoom (wheel), rotate (Q/E); hover a tile to see it; click a unit to select it and see
//! where it can go this turn; click a tile to walk there along the map's cheapest path (its
//! movement model: open land 1, hills and forests 2, a river tile 1 more; water, rock and snow
//! peaks cannot be entered); End Turn (button or Enter)
//! restores movement. G toggles tile outlines, L the movement-cost lens, T the territory tint,
//! V the fog of war, R regenerates with a new seed, 1-6 switch presets (6: Civ6 Standard,
//! wrapping; 7: a scenario made with the world builder; P pans east across its seam), F3 shows
//! chunk boundaries; M cycles the map types, U the World preset's terrain rulesets (its biomes,
//! Civilization V's terrain, The Shattered Realms); J, K, B, N, O, X switch shadows, distance
//! fog, props, water, ambient occlusion and the terrain textures (`look.rs`). Tab opens the world builder (`editor.rs`): paint with a tool and a
//! brush, Ctrl+Z / Ctrl+Y undo and redo, Ctrl+S saves the edits next to the map.
//!
//! Two players: yours (red) and a rival (blue), at the starts the map's game setup chose (the
//! World preset has one: regions of equal fertility, resources and wonders, shown as gems and
//! obelisks; F opens the fairness report and the map statistics), each with territory around its
//! units that grows at the end of each turn. Fog of war shows what your units see, by the map's
//! sight rule (higher tiles and mountains block the view, hills and forests see one tile farther,
//! mountains two); rival units out of sight are hidden. Every player's fog is kept, as a server
//! would keep it. All of it is per-tile state
//! ([`TileStates`]) the terrain shader draws: no mesh is rebuilt.
//!
//! `HEXTERRAIN_SCRIPT=1` plays a scripted turn (select, move, end turn), checks the game state,
//! fog and territory, and exits 0 (1 on a failed check); with `HEXTERRAIN_SCREENSHOT=out.png` it
//! saves a picture first. Without the script, `HEXTERRAIN_SCREENSHOT` takes a picture after some
//! frames.

#[path = "../support/mod.rs"]
mod support;

mod editor;
mod gizmos;
mod input;
mod look;
mod panel;
mod pieces;
mod rig;
mod script;
mod units;
mod vision;

use std::collections::HashSet;

use bevy::picking::events::{Move, Over};
use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;

use crate::gizmos::chunk_boundaries;
use crate::input::{hover, keys, leave};
use crate::panel::{EndTurnButton, Panel, ReportPanel, panel, report_panel};
use crate::rig::{Rig, camera_controls, follow_minimap};
use crate::units::{click, end_turn, follow_map, place_units, walk_ended};

pub(crate) const PRESETS: [&str; 7] = [
    "maps/world.map.ron",
    "maps/island.map.ron",
    "maps/mediterranean.map.ron",
    "maps/inland.map.ron",
    "maps/continent.map.ron",
    // Civilization's Standard size, wrapping east to west.
    "maps/civ6/standard.map.ron",
    // A scenario made with the world builder: the World map with a strait and a mountain pass.
    "maps/strait.map.ron",
];

/// The map types' presets (Civilization VI Standard, wrapping), in the order M cycles them.
pub(crate) const MAP_TYPES: [&str; 6] = [
    "maps/types/pangaea.map.ron",
    "maps/types/continents.map.ron",
    "maps/types/small_continents.map.ron",
    "maps/types/archipelago.map.ron",
    "maps/types/fractal.map.ron",
    "maps/types/inland_sea.map.ron",
];

/// The World preset under each shipped terrain ruleset, in the order U cycles them: its biomes,
/// Civilization V's terrain, The Shattered Realms.
pub(crate) const RULESETS: [&str; 3] = ["maps/world.map.ron", "maps/world_civ5.map.ron", "maps/world_fantasy.map.ron"];

/// The digit keys 1-9, in order: presets in the game, tools in the world builder.
pub(crate) const DIGITS: [KeyCode; 9] = [
    KeyCode::Digit1,
    KeyCode::Digit2,
    KeyCode::Digit3,
    KeyCode::Digit4,
    KeyCode::Digit5,
    KeyCode::Digit6,
    KeyCode::Digit7,
    KeyCode::Digit8,
    KeyCode::Digit9,
];

#[derive(Resource, Default)]
pub(crate) struct Game {
    pub(crate) turn: u32,
    pub(crate) selected: Option<Entity>,
    pub(crate) hovered: Option<Hex>,
    pub(crate) reachable: HashSet<Hex>,
    pub(crate) spawned: bool,
    /// The map the units were placed on (`HexMap::map_id`).
    pub(crate) map_id: u64,
    pub(crate) show_chunks: bool,
    /// The camera pans east by itself (P): across the seam of a wrapping map, and on.
    pub(crate) auto_pan: bool,
    /// The world builder is open (Tab): clicks paint, the digits pick tools.
    pub(crate) editing: bool,
    /// How many times M was pressed: the next map type is `MAP_TYPES[map_types % 6]`.
    pub(crate) map_types: usize,
    /// How many times U was pressed: the next ruleset is `RULESETS[(rulesets + 1) % 3]`.
    pub(crate) rulesets: usize,
}

fn main() -> AppExit {
    let scripted = std::env::var_os("HEXTERRAIN_SCRIPT").is_some();
    // HEXTERRAIN_PRESET=1..7 starts on another preset (6: the wrapping Civ6 Standard map).
    let preset = std::env::var("HEXTERRAIN_PRESET").ok().and_then(|p| p.parse::<usize>().ok()).unwrap_or(1);
    // HEXTERRAIN_MAP=maps/civ6/huge.map.ron starts on any map file of the assets instead.
    let map = std::env::var("HEXTERRAIN_MAP").unwrap_or_else(|_| PRESETS[preset.clamp(1, PRESETS.len()) - 1].into());
    // HEXTERRAIN_SETTLE=1 spawns every prop at once (for figures of a settled view).
    let settle = std::env::var_os("HEXTERRAIN_SETTLE").is_some();
    // HEXTERRAIN_LOD=off draws every chunk at full detail (levels of detail compared).
    let streaming = support::streaming_from_env();
    support::require_asset(&map);
    let mut app = App::new();
    // HEXTERRAIN_FOG=off starts without the fog of war (V toggles it).
    let fog_of_war = std::env::var("HEXTERRAIN_FOG").map_or(true, |v| v != "off");
    // The minimap sits in the bottom right corner, above the help line.
    let minimap = HexMinimapSettings { margin: Vec2::new(12.0, 48.0), ..default() };
    app.add_plugins((DefaultPlugins, HexTerrainPlugins::from_asset(map), HexMinimapPlugin))
        .insert_resource(streaming)
        .insert_resource(minimap)
        .insert_resource(HexTerrainMaterialSettings { outlines: true, outline_width: 0.04, ..default() })
        .insert_resource(HexTileStateStyle { fog_of_war, ..default() })
        .insert_resource(HexPropSettings { max_spawns_per_frame: if settle { usize::MAX } else { 64 }, ..default() })
        .insert_resource(Game { turn: 1, ..default() })
        .init_resource::<editor::EditorMode>()
        .add_systems(Startup, (setup, look::from_env, editor::spawn_panel))
        .add_systems(
            Update,
            (
                follow_minimap,
                camera_controls,
                place_units,
                (end_turn, keys),
                (panel, report_panel),
                chunk_boundaries,
                look::keys,
            )
                .chain(),
        )
        .add_systems(
            Update,
            (editor::from_env, editor::editor_input, editor::paint, editor::brush_outline, editor::editor_panel)
                .chain()
                .before(HexTerrainSystems::Map)
                .after(keys),
        )
        .add_systems(
            Update,
            (follow_map, vision::update_fog, vision::highlight, vision::paint_lens)
                .chain()
                .after(HexTerrainSystems::Render),
        )
        // The pointer through the terrain's picking backend: its events carry the tile.
        .add_observer(hover::<Over>)
        .add_observer(hover::<Move>)
        .add_observer(leave)
        .add_observer(click)
        .add_observer(walk_ended);
    // The scripted turn for the tests is a plugin of its own: the game's systems carry no test
    // branches.
    if scripted {
        app.add_plugins(script::ScriptPlugin);
    } else {
        app.add_plugins(HexScreenshotPlugin::default());
        // In screenshot mode, what each frame draws is printed (the README's figures).
        if std::env::var_os("HEXTERRAIN_SCREENSHOT").is_some() {
            app.add_plugins(support::render_figures::RenderFiguresPlugin).add_systems(Last, print_figures);
        }
    }
    app.run()
}

/// Prints what the frame drew and the chunks at each level.
fn print_figures(frame: Res<support::render_figures::RenderFigures>, props: Query<(), With<HexProp>>) {
    println!("frame: {}; {} props", *frame, props.iter().count());
}

fn setup(mut commands: Commands) {
    // HEXTERRAIN_FOCUS=x,z starts the camera elsewhere (the README's seam picture).
    let focus = std::env::var("HEXTERRAIN_FOCUS")
        .ok()
        .and_then(|f| {
            let (x, z) = f.split_once(',')?;
            Some(Vec3::new(x.trim().parse().ok()?, 0.0, z.trim().parse().ok()?))
        })
        // The opening view: a coast with an inland sea, forest, hills and mountains close by.
        .unwrap_or(Vec3::new(52.0, 0.0, 52.0));
    // HEXTERRAIN_ZOOM=d starts the camera d units from its focus (8 to 120, 18 by default).
    let zoom =
        std::env::var("HEXTERRAIN_ZOOM").ok().and_then(|z| z.parse::<f32>().ok()).map_or(18.0, |z| z.clamp(8.0, 120.0));
    commands
        .spawn((
            Rig { focus, yaw: 0.0, distance: zoom, target_focus: focus, target_yaw: 0.0, target_distance: zoom },
            HexTerrainAgent::default(),
            Transform::from_translation(focus),
            // The camera below inherits visibility from the rig.
            Visibility::default(),
        ))
        // The plugin lights what a HexTerrainCamera shows: sun, shadows, distance fog (the
        // camera's `DistanceFog` and `AmbientLight` come with it).
        .with_child((HexTerrainCamera, Transform::default()));
    commands.spawn((
        Panel,
        Text::new(""),
        TextFont::from_font_size(16.0),
        Node { position_type: PositionType::Absolute, top: px(10.0), left: px(10.0), ..default() },
    ));
    // HEXTERRAIN_REPORT=1 starts with the fairness report open (F toggles it).
    let report =
        if std::env::var_os("HEXTERRAIN_REPORT").is_some() { Visibility::Inherited } else { Visibility::Hidden };
    commands.spawn((
        ReportPanel,
        Text::new(""),
        TextFont::from_font_size(12.0),
        report,
        BackgroundColor(Color::srgba(0.05, 0.06, 0.09, 0.85)),
        Node {
            position_type: PositionType::Absolute,
            top: px(56.0),
            right: px(10.0),
            padding: UiRect::all(px(8.0)),
            ..default()
        },
    ));
    commands.spawn((
        Text::new(
            "WASD/arrows/edge pan, wheel zoom, Q/E rotate, click unit then tile, Enter end turn, G outlines, \
             L lens, T tint, V fog, F map report, R new seed, 1-7 presets (6 wraps, 7 edited), M map types, U rulesets, X textures, \
             P pan east, F3 chunks, \
             Tab world builder",
        ),
        TextFont::from_font_size(13.0),
        Node { position_type: PositionType::Absolute, bottom: px(8.0), left: px(10.0), ..default() },
    ));
    commands
        .spawn((
            EndTurnButton,
            Button,
            Node {
                position_type: PositionType::Absolute,
                top: px(10.0),
                right: px(10.0),
                padding: UiRect::all(px(8.0)),
                ..default()
            },
            BackgroundColor(Color::srgb(0.15, 0.2, 0.3)),
        ))
        .with_child((Text::new("End Turn"), TextFont::from_font_size(16.0)));
}
