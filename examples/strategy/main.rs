//! A small turn-based strategy game on streamed hex terrain: pan (WASD/arrows or the screen
//! edge), zoom (wheel), rotate (Q/E); hover a tile to see it; click a unit to select it and see
//! where it can go this turn; click a tile to walk there along an A* path (land costs 1,
//! mountain 3, fording a river 1 more, sea and lakes are impassable); End Turn (button or Enter)
//! restores movement. G toggles tile outlines, L the movement-cost lens, T the territory tint,
//! V the fog of war, R regenerates with a new seed, 1-6 switch presets (6: Civ6 Standard,
//! wrapping; P pans east across its seam), F3 shows chunk boundaries; J, K, B, N, O switch
//! shadows, distance fog, props, water and ambient occlusion (`look.rs`).
//!
//! Two players: yours (red) and a rival (blue), at the starts the map's game setup chose (the
//! World preset has one: regions of equal fertility, resources and wonders, shown as gems and
//! obelisks; F opens the fairness report), each with territory around its units that grows
//! at the end of each turn. Fog of war shows what your units see (mountains block the view, hills
//! and mountains see farther); rival units out of sight are hidden. All of it is per-tile state
//! ([`TileStates`]) the terrain shader draws: no mesh is rebuilt.
//!
//! `HEXTERRAIN_SCRIPT=1` plays a scripted turn (select, move, end turn), checks the game state,
//! fog and territory, and exits 0 (1 on a failed check); with `HEXTERRAIN_SCREENSHOT=out.png` it
//! saves a picture first. Without the script, `HEXTERRAIN_SCREENSHOT` takes a picture after some
//! frames.

mod look;
mod script;
mod vision;

use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap, HashSet};

use bevy::input::mouse::AccumulatedMouseScroll;
use bevy::picking::PickingSystems;
use bevy::picking::backend::HitData;
use bevy::picking::events::{Click, Move, Out, Over, Pointer};
use bevy::picking::pointer::PointerButton;
use bevy::prelude::*;
use hex_terrain_game::prelude::*;
use hexx::algorithms::a_star;

/// Moves a unit has each turn.
pub(crate) const MOVES: u32 = 4;
/// Distance from the human player's units to the rival's.
const RIVAL_DISTANCE: u32 = 7;
const PRESETS: [&str; 6] = [
    "maps/world.map.ron",
    "maps/island.map.ron",
    "maps/mediterranean.map.ron",
    "maps/inland.map.ron",
    "maps/continent.map.ron",
    // Civilization's Standard size, wrapping east to west.
    "maps/civ6/standard.map.ron",
];

/// The camera's pivot on the ground; the streaming agent.
#[derive(Component)]
pub(crate) struct Rig {
    focus: Vec3,
    yaw: f32,
    distance: f32,
    pub(crate) target_focus: Vec3,
    target_yaw: f32,
    target_distance: f32,
}

#[derive(Component)]
pub(crate) struct Unit {
    /// [`vision::HUMAN`] or [`vision::RIVAL`].
    pub(crate) player: u8,
    pub(crate) tile: Hex,
    pub(crate) moves_left: u32,
    /// World positions still to walk through.
    pub(crate) path: Vec<Vec3>,
}

#[derive(Resource, Default)]
pub(crate) struct Game {
    pub(crate) turn: u32,
    pub(crate) selected: Option<Entity>,
    pub(crate) hovered: Option<Hex>,
    pub(crate) reachable: HashSet<Hex>,
    pub(crate) spawned: bool,
    show_chunks: bool,
    /// The camera pans east by itself (P): across the seam of a wrapping map, and on.
    auto_pan: bool,
}

#[derive(Component)]
struct Panel;

/// The fairness report of the map's game setup (F).
#[derive(Component)]
struct ReportPanel;

#[derive(Component)]
struct EndTurnButton;

fn main() -> AppExit {
    let scripted = std::env::var_os("HEXTERRAIN_SCRIPT").is_some();
    // HEXTERRAIN_PRESET=1..6 starts on another preset (6: the wrapping Civ6 Standard map).
    let preset = std::env::var("HEXTERRAIN_PRESET").ok().and_then(|p| p.parse::<usize>().ok()).unwrap_or(1);
    let mut app = App::new();
    // HEXTERRAIN_FOG=off starts without the fog of war (V toggles it).
    let fog_of_war = std::env::var("HEXTERRAIN_FOG").map_or(true, |v| v != "off");
    // The minimap sits in the bottom right corner, above the help line.
    let minimap = MinimapSettings { margin: Vec2::new(12.0, 48.0), ..default() };
    app.add_plugins((
        DefaultPlugins,
        HexTerrainPlugin::from_asset(PRESETS[preset.clamp(1, PRESETS.len()) - 1]),
        HexMinimapPlugin { settings: minimap },
    ))
    .insert_resource(TerrainAppearance { outlines: true, outline_width: 0.04, fog_of_war, ..default() })
    .insert_resource(Game { turn: 1, ..default() })
    .add_systems(Startup, (setup, look::from_env))
    .add_systems(
        Update,
        (
            follow_minimap,
            camera_controls,
            place_units,
            (end_turn, keys),
            walk,
            (panel, report_panel),
            chunk_boundaries,
            look::keys,
        )
            .chain(),
    )
    .add_systems(
        Update,
        (vision::update_fog, vision::highlight, vision::paint_lens).after(HexTerrainSystems::Render).after(walk),
    )
    // The pointer through the terrain's picking backend: its events carry the tile.
    .add_observer(hover::<Over>)
    .add_observer(hover::<Move>)
    .add_observer(leave)
    .add_observer(click);
    if scripted {
        app.init_resource::<script::Script>()
            .init_resource::<script::ScriptedPointer>()
            .add_systems(PreUpdate, script::script.after(bevy::input::InputSystems))
            .add_systems(PreUpdate, script::drive_pointer.after(script::script).before(PickingSystems::ProcessInput));
    } else {
        app.add_plugins(hex_terrain_game::screenshot::ScreenshotModePlugin);
    }
    app.run()
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
    commands
        .spawn((
            Rig { focus, yaw: 0.0, distance: 18.0, target_focus: focus, target_yaw: 0.0, target_distance: 18.0 },
            HexTerrainAgent::default(),
            Transform::from_translation(focus),
            // The camera below inherits visibility from the rig.
            Visibility::default(),
        ))
        // The plugin lights what a HexTerrainCamera shows: sun, shadows, distance fog.
        .with_child((Camera3d::default(), HexTerrainCamera, Transform::default()));
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
             L lens, T tint, V fog, F fairness report, R new seed, 1-6 presets (6 wraps), P pan east, F3 chunks",
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

/// A press or drag on the minimap sends the camera there.
fn follow_minimap(mut go: MessageReader<MinimapNavigate>, mut rigs: Query<&mut Rig>) {
    for go in go.read() {
        for mut rig in &mut rigs {
            rig.target_focus = Vec3::new(go.world.x as f32, 0.0, go.world.y as f32);
        }
    }
}

fn camera_controls(
    time: Res<Time>,
    game: Res<Game>,
    keys: Res<ButtonInput<KeyCode>>,
    scroll: Res<AccumulatedMouseScroll>,
    windows: Query<&Window>,
    mut rigs: Query<(&mut Rig, &mut Transform, &Children)>,
    mut cameras: Query<&mut Transform, (With<Camera3d>, Without<Rig>)>,
) {
    let dt = time.delta_secs();
    for (mut rig, mut t, children) in &mut rigs {
        let mut pan = Vec2::ZERO;
        for (key, d) in [
            (KeyCode::KeyW, Vec2::NEG_Y),
            (KeyCode::ArrowUp, Vec2::NEG_Y),
            (KeyCode::KeyS, Vec2::Y),
            (KeyCode::ArrowDown, Vec2::Y),
            (KeyCode::KeyA, Vec2::NEG_X),
            (KeyCode::ArrowLeft, Vec2::NEG_X),
            (KeyCode::KeyD, Vec2::X),
            (KeyCode::ArrowRight, Vec2::X),
        ] {
            if keys.pressed(key) {
                pan += d;
            }
        }
        // Screen-edge panning.
        if let Some(cursor) = windows.iter().next().and_then(|w| w.cursor_position().map(|c| (c, w.size()))) {
            let (c, size) = cursor;
            let m = 8.0;
            if c.x < m {
                pan.x -= 1.0;
            } else if c.x > size.x - m {
                pan.x += 1.0;
            }
            if c.y < m {
                pan.y -= 1.0;
            } else if c.y > size.y - m {
                pan.y += 1.0;
            }
        }
        if game.auto_pan {
            pan.x += 1.0;
        }
        let speed = rig.target_distance * 0.9;
        let rotated = Vec2::from_angle(-rig.target_yaw).rotate(pan.normalize_or_zero());
        rig.target_focus += Vec3::new(rotated.x, 0.0, rotated.y) * speed * dt;
        if keys.pressed(KeyCode::KeyQ) {
            rig.target_yaw += 1.5 * dt;
        }
        if keys.pressed(KeyCode::KeyE) {
            rig.target_yaw -= 1.5 * dt;
        }
        rig.target_distance = (rig.target_distance * (1.0 - scroll.delta.y * 0.1)).clamp(8.0, 120.0);
        // Smooth: ease towards the targets.
        let k = 1.0 - (-10.0 * dt).exp();
        let (tf, ty, td) = (rig.target_focus, rig.target_yaw, rig.target_distance);
        rig.focus = rig.focus.lerp(tf, k);
        rig.yaw += (ty - rig.yaw) * k;
        rig.distance += (td - rig.distance) * k;
        t.translation = rig.focus;
        for child in children.iter() {
            if let Ok(mut cam) = cameras.get_mut(child) {
                let offset = Quat::from_rotation_y(rig.yaw) * Vec3::new(0.0, rig.distance, rig.distance * 0.8);
                *cam = Transform::from_translation(offset).looking_at(Vec3::ZERO, Vec3::Y);
            }
        }
    }
}

/// A pointer event that carries the terrain hit it is about.
trait TerrainHit {
    fn terrain_hit(&self) -> &HitData;
}

impl TerrainHit for Over {
    fn terrain_hit(&self) -> &HitData {
        &self.hit
    }
}

impl TerrainHit for Move {
    fn terrain_hit(&self) -> &HitData {
        &self.hit
    }
}

/// The hovered tile: the tile the terrain picking backend reports under the pointer.
fn hover<E: TerrainHit + std::fmt::Debug + Clone + Reflect>(
    pointer: On<Pointer<E>>,
    map: Res<HexMap>,
    mut game: ResMut<Game>,
) {
    // A hit on a prop bubbles up to its chunk: act on the first.
    if pointer.entity != pointer.original_event_target() {
        return;
    }
    if let Some(pick) = pointer.event.terrain_hit().extra_as::<HexPick>() {
        game.hovered = Some(pick.tile).filter(|&t| map.contains(t));
    }
}

/// The pointer left the terrain (a chunk it was over).
fn leave(pointer: On<Pointer<Out>>, mut game: ResMut<Game>) {
    if pointer.entity == pointer.original_event_target() && pointer.hit.extra_as::<HexPick>().is_some() {
        game.hovered = None;
    }
}

/// Movement cost of entering a tile: land 1, mountain 3; sea, lakes and outside the map
/// impassable.
pub(crate) fn cost(map: &HexMap, tile: Hex) -> Option<u32> {
    if !map.contains(tile) || map.lake(tile).is_some() {
        return None;
    }
    match map.tile_kind(tile)? {
        TileKind::Sea => None,
        TileKind::Land => Some(1),
        TileKind::Mountain => Some(3),
    }
}

/// Cost of the step from `a` to its neighbor `b`: entering `b`, plus 1 for fording a river, that
/// is entering a river tile from a tile its river does not come from or go to (walking along a
/// river costs nothing more).
pub(crate) fn step_cost(map: &HexMap, a: Hex, b: Hex) -> Option<u32> {
    let enter = cost(map, b)?;
    // Rivers name the map's own tiles; `a` may be a copy past a wrapping map's edge.
    let a = map.wrap_tile(a);
    let ford = map.river(b).is_some_and(|r| r.downstream != Some(a) && !r.upstream.contains(&a));
    Some(enter + u32::from(ford))
}

/// What a path costs, step by step.
pub(crate) fn path_cost(map: &HexMap, path: &[Hex]) -> u32 {
    path.windows(2).filter_map(|w| step_cost(map, w[0], w[1])).sum()
}

/// Every tile reachable from `start` with `budget` moves (Dijkstra over [`step_cost`]), tiles
/// in `blocked` excluded. The search runs on the plane, so on a wrapping map it crosses the
/// seam; the tiles returned are the map's own.
fn reachable(map: &HexMap, start: Hex, budget: u32, blocked: &HashSet<Hex>) -> HashSet<Hex> {
    let mut best: HashMap<Hex, u32> = HashMap::from([(start, 0)]);
    let mut queue = BinaryHeap::from([(Reverse(0), start.x, start.y)]);
    while let Some((Reverse(spent), x, y)) = queue.pop() {
        let here = Hex::new(x, y);
        if best.get(&here).is_some_and(|&b| b < spent) {
            continue;
        }
        for next in here.all_neighbors() {
            if blocked.contains(&map.wrap_tile(next)) {
                continue;
            }
            let Some(c) = step_cost(map, here, next) else { continue };
            let total = spent + c;
            if total <= budget && best.get(&next).is_none_or(|&b| total < b) {
                best.insert(next, total);
                queue.push((Reverse(total), next.x, next.y));
            }
        }
    }
    best.into_keys().map(|t| map.wrap_tile(t)).filter(|&t| t != start).collect()
}

/// Where units are placed (the map, its tile states) and the assets new ones are made of.
#[derive(bevy::ecs::system::SystemParam)]
struct UnitGround<'w> {
    map: Res<'w, HexMap>,
    states: ResMut<'w, TileStates>,
    meshes: ResMut<'w, Assets<Mesh>>,
    materials: ResMut<'w, Assets<StandardMaterial>>,
}

/// Puts three units of yours and two rival units on the map's game setup starts (on a map
/// without one, near the camera and [`RIVAL_DISTANCE`] tiles away) once the terrain exists,
/// each player claiming territory around its units, the camera over yours; after a
/// regeneration, puts every unit back on land and claims again (another map starts with no
/// territory).
fn place_units(
    mut commands: Commands,
    mut ready: MessageReader<TerrainReady>,
    mut game: ResMut<Game>,
    mut rigs: Query<(&mut Rig, &mut Transform), Without<Unit>>,
    mut units: Query<(Entity, &mut Unit, &mut Transform)>,
    ground: UnitGround,
) {
    let UnitGround { map, mut states, mut meshes, mut materials } = ground;
    if ready.read().count() == 0 {
        return;
    }
    // A map with a game setup puts the players on its starts, the camera over yours.
    let starts = map.setup().map(|s| s.starts().to_vec()).filter(|s| s.len() >= 2);
    if !game.spawned
        && let Some(center) = starts.as_ref().and_then(|s| map.tile_center(s[0]))
    {
        for (mut rig, mut t) in &mut rigs {
            let focus = Vec3::new(center.x, 0.0, center.z);
            rig.focus = focus;
            rig.target_focus = focus;
            t.translation = focus;
        }
    }
    let focus = rigs.iter().next().map_or(Vec3::ZERO, |(r, _)| r.focus);
    let land_near = |from: Hex, taken: &[Hex]| {
        (0..40u32)
            .flat_map(|r| from.ring(r))
            .map(|t| map.wrap_tile(t))
            .find(|&t| cost(&map, t) == Some(1) && !taken.contains(&t))
    };
    let mut taken = Vec::new();
    if game.spawned {
        for (_, mut unit, mut t) in &mut units {
            let tile = if cost(&map, unit.tile).is_some() { Some(unit.tile) } else { land_near(unit.tile, &taken) };
            if let Some(tile) = tile
                && let Some(center) = map.tile_center(tile)
            {
                unit.tile = tile;
                unit.path.clear();
                taken.push(tile);
                t.translation = map.wrap_near(center, focus) + Vec3::Y * 0.6;
                vision::claim(&map, &mut states, unit.player, tile, vision::HOME_RADIUS - 1);
            }
        }
        // The selected unit's reach follows the new terrain.
        refresh_reachable(&map, &mut game, &units.transmute_lens::<(Entity, &Unit)>().query());
        return;
    }
    let mesh = meshes.add(Capsule3d::new(0.3, 0.6));
    let Some(home) = map.tile_at(focus) else { return };
    // Without a setup, the rival starts on the first land tile of the ring at RIVAL_DISTANCE,
    // searching from the east.
    let rival_home = match &starts {
        Some(s) => s[1],
        None => home.ring(RIVAL_DISTANCE).find(|&t| cost(&map, t) == Some(1)).unwrap_or(home),
    };
    let home = starts.as_ref().map_or(home, |s| s[0]);
    let human = [Color::srgb(0.85, 0.2, 0.15), Color::srgb(0.9, 0.75, 0.1), Color::srgb(0.95, 0.45, 0.1)];
    let rival = [Color::srgb(0.15, 0.35, 0.9), Color::srgb(0.2, 0.7, 0.85)];
    for (player, near, colors) in [(vision::HUMAN, home, &human[..]), (vision::RIVAL, rival_home, &rival[..])] {
        for (i, &color) in colors.iter().enumerate() {
            let Some(tile) = land_near(near, &taken) else { break };
            let Some(center) = map.tile_center(tile) else { break };
            taken.push(tile);
            let radius = if i == 0 { vision::HOME_RADIUS } else { vision::HOME_RADIUS - 1 };
            vision::claim(&map, &mut states, player, tile, radius);
            commands.spawn((
                Unit { player, tile, moves_left: MOVES, path: Vec::new() },
                Mesh3d(mesh.clone()),
                MeshMaterial3d(materials.add(color)),
                Transform::from_translation(map.wrap_near(center, focus) + Vec3::Y * 0.6),
            ));
        }
    }
    game.spawned = true;
}

/// A click on the terrain: select the human unit on the tile, or move the selected unit there.
fn click(pointer: On<Pointer<Click>>, map: Res<HexMap>, mut game: ResMut<Game>, mut units: Query<(Entity, &mut Unit)>) {
    // A click on a prop bubbles up to its chunk: act on the first.
    if pointer.button != PointerButton::Primary || pointer.entity != pointer.original_event_target() {
        return;
    }
    let Some(tile) = pointer.hit.extra_as::<HexPick>().map(|p| p.tile).filter(|&t| map.contains(t)) else { return };
    game.hovered = Some(tile);
    let occupied: HashSet<Hex> = units.iter().map(|(_, u)| u.tile).collect();
    if let Some((e, _)) = units.iter().find(|(_, u)| u.tile == tile && u.player == vision::HUMAN) {
        game.selected = Some(e);
    } else if let Some(e) = game.selected
        && let Ok((_, mut unit)) = units.get_mut(e)
        && game.reachable.contains(&tile)
    {
        // Other units block the way; the mover's own tile (hexx asks for the start's cost) does not.
        // On a wrapping map the goal is the copy of the tile nearest the unit: A* runs on the
        // plane and takes the short way, across the seam when that is shorter.
        let from = unit.tile;
        let goal = map.tile_near(tile, from);
        let step = |a: Hex, b: Hex| {
            let taken = occupied.contains(&map.wrap_tile(b)) && b != from;
            if taken { None } else { step_cost(&map, a, b) }
        };
        if let Some(path) = a_star(from, goal, step) {
            let spent = path_cost(&map, &path);
            if spent <= unit.moves_left {
                unit.moves_left -= spent;
                unit.path =
                    path.iter().skip(1).filter_map(|&t| map.tile_center(t)).map(|c| c + Vec3::Y * 0.6).collect();
                unit.tile = map.wrap_tile(goal);
            }
        }
    }
    refresh_reachable(&map, &mut game, &units.transmute_lens::<(Entity, &Unit)>().query());
}

fn refresh_reachable(map: &HexMap, game: &mut Game, units: &Query<(Entity, &Unit)>) {
    game.reachable.clear();
    let Some(e) = game.selected else { return };
    let Ok((_, unit)) = units.get(e) else { return };
    let occupied: HashSet<Hex> = units.iter().filter(|(o, _)| *o != e).map(|(_, u)| u.tile).collect();
    // hexx's field of movement charges per tile entered; fording a river depends on the step,
    // so the reach is a small Dijkstra over the same step costs as the A* path.
    game.reachable = reachable(map, unit.tile, unit.moves_left, &occupied);
}

fn end_turn(
    keys: Res<ButtonInput<KeyCode>>,
    buttons: Query<&Interaction, (Changed<Interaction>, With<EndTurnButton>)>,
    map: Res<HexMap>,
    mut game: ResMut<Game>,
    mut states: ResMut<TileStates>,
    mut units: Query<(Entity, &mut Unit)>,
) {
    let pressed = buttons.iter().any(|i| *i == Interaction::Pressed);
    if !(keys.just_pressed(KeyCode::Enter) || pressed) {
        return;
    }
    game.turn += 1;
    vision::grow_territory(&map, &mut states, &units);
    for (_, mut unit) in &mut units {
        unit.moves_left = MOVES;
    }
    refresh_reachable(&map, &mut game, &units.transmute_lens::<(Entity, &Unit)>().query());
}

fn keys(
    keys: Res<ButtonInput<KeyCode>>,
    mut appearance: ResMut<TerrainAppearance>,
    map: Res<HexMap>,
    mut load: MessageWriter<LoadHexMap>,
    mut game: ResMut<Game>,
    mut report: Query<&mut Visibility, With<ReportPanel>>,
) {
    if keys.just_pressed(KeyCode::KeyG) {
        appearance.outlines = !appearance.outlines;
    }
    if keys.just_pressed(KeyCode::KeyL) {
        appearance.lens = !appearance.lens;
    }
    if keys.just_pressed(KeyCode::KeyT) {
        appearance.territory_tint = !appearance.territory_tint;
    }
    if keys.just_pressed(KeyCode::KeyV) {
        appearance.fog_of_war = !appearance.fog_of_war;
    }
    if keys.just_pressed(KeyCode::F3) {
        game.show_chunks = !game.show_chunks;
    }
    if keys.just_pressed(KeyCode::KeyF) {
        for mut v in &mut report {
            v.toggle_inherited_hidden();
        }
    }
    if keys.just_pressed(KeyCode::KeyP) {
        game.auto_pan = !game.auto_pan;
    }
    if keys.just_pressed(KeyCode::KeyR) {
        let mut config = map.config().clone();
        config.seed = config.seed.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
        load.write(LoadHexMap(config.into()));
    }
    let digits = [KeyCode::Digit1, KeyCode::Digit2, KeyCode::Digit3, KeyCode::Digit4, KeyCode::Digit5, KeyCode::Digit6];
    for (i, key) in digits.into_iter().enumerate() {
        if keys.just_pressed(key) {
            load.write(LoadHexMap(PRESETS[i].into()));
        }
    }
}

/// Moves units along their paths, on the surface. On a wrapping map a unit is drawn at its copy
/// nearest the camera, and walks the short way to the next point of its path, whichever copy of
/// it that is.
fn walk(time: Res<Time>, map: Res<HexMap>, rigs: Query<&Rig>, mut units: Query<(&mut Unit, &mut Transform)>) {
    let focus = rigs.iter().next().map_or(Vec3::ZERO, |r| r.focus);
    for (mut unit, mut t) in &mut units {
        t.translation = map.wrap_near(t.translation, focus);
        let Some(&next) = unit.path.first() else { continue };
        let next = map.wrap_near(next, t.translation);
        let to = next - t.translation;
        let step = 6.0 * time.delta_secs();
        if to.length() <= step {
            t.translation = next;
            unit.path.remove(0);
        } else {
            t.translation += to.normalize() * step;
            if let Some(y) = map.surface_height(t.translation) {
                t.translation.y = y + 0.6;
            }
        }
    }
}

fn panel(
    game: Res<Game>,
    map: Res<HexMap>,
    states: Res<TileStates>,
    appearance: Res<TerrainAppearance>,
    units: Query<&Unit>,
    mut text: Query<&mut Text, With<Panel>>,
) {
    let mut s = format!("Turn {}", game.turn);
    if appearance.lens {
        s += "   Lens: movement cost (green 1, orange 3; water impassable)";
    }
    if let Some(tile) = game.hovered.filter(|&t| !appearance.fog_of_war || states.visibility(t) != FogState::Unexplored)
    {
        let owner = match states.owner(tile) {
            Some(vision::HUMAN) => "yours",
            Some(_) => "rival's",
            None => "nobody's",
        };
        s += &format!("\nTerritory: {owner}");
        let Some(info) = map.tile_info(tile) else { return };
        // Offset coordinates (column, row), as the fairness report gives them.
        let [col, row] = map.terrain().offset_of(tile);
        s += &format!(
            "\nTile ({col}, {row})  {} ({})  elevation {:.2}",
            info.biome.name(),
            info.kind.name(),
            info.elevation
        );
        if let Some(river) = map.river(tile) {
            s += &format!("\nRiver: flow {:.1} (fording costs 1 more)", river.flow);
        }
        if let Some(lake) = info.lake {
            s += &format!("\nLake {lake} (impassable)");
        }
        if let Some(r) = map.resource(tile) {
            s += &format!("\nResource: {} ({})", r.name, r.class.name());
        }
        if let Some(w) = map.wonder(tile) {
            s += &format!("\nNatural wonder: {}", w.name);
        }
        if let Some(p) = map.start(tile) {
            s += &format!("\nStart of player {}", p + 1);
        }
    }
    if let Some(unit) = game.selected.and_then(|e| units.get(e).ok()) {
        s += &format!("\nSelected unit: {} of {MOVES} moves left", unit.moves_left);
    }
    for mut t in &mut text {
        t.0.clone_from(&s);
    }
}

/// Writes the setup's fairness report into its panel when the map changes.
fn report_panel(map: Res<HexMap>, mut text: Query<&mut Text, With<ReportPanel>>) {
    if !map.is_changed() {
        return;
    }
    let report = match map.setup() {
        Some(setup) => format!("Fairness report ({} players)\n{}", setup.starts().len(), setup.report()),
        None => "This map has no game setup (the World preset has one).".to_owned(),
    };
    for mut t in &mut text {
        t.0.clone_from(&report);
    }
}

/// F3: outlines of the loaded chunks.
fn chunk_boundaries(game: Res<Game>, map: Res<HexMap>, streamer: Res<ChunkStreamer>, mut gizmos: Gizmos) {
    if !game.show_chunks {
        return;
    }
    let terrain = map.terrain();
    let top = map.config().terrain.max_elevation + 0.2;
    for chunk in streamer.loaded_chunks() {
        let Some(rect) = terrain.chunk_rect(chunk) else { continue };
        // A chunk past a wrapping map's edge shows its map chunk's tiles, whole map widths on.
        let shift = terrain.wrap().map_or(0.0, |w| w.width * f64::from(terrain.wrap_chunk(chunk).1));
        let corners = [
            rect.min,
            [rect.max[0] - 1, rect.min[1]],
            [rect.max[0] - 1, rect.max[1] - 1],
            [rect.min[0], rect.max[1] - 1],
        ]
        .map(|oc| {
            let [x, _, z] = terrain.tile_center(terrain.tile_from_offset(oc)).unwrap_or_default();
            Vec3::new((x + shift) as f32, top, z as f32)
        });
        for k in 0..4 {
            gizmos.line(corners[k], corners[(k + 1) % 4], Color::srgb(1.0, 0.3, 0.1));
        }
    }
}
