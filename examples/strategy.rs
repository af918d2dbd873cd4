//! A small turn-based strategy game on streamed hex terrain: pan (WASD/arrows or the screen
//! edge), zoom (wheel), rotate (Q/E); hover a tile to see it; click a unit to select it and see
//! where it can go this turn; click a tile to walk there along an A* path (land costs 1,
//! mountain 3, fording a river 1 more, sea and lakes are impassable); End Turn (button or Enter)
//! restores movement. G toggles tile outlines, R regenerates with a new seed, 1-5 switch presets,
//! F3 shows chunk boundaries.
//!
//! `HEXTERRAIN_SCRIPT=1` plays a scripted turn (select, move, end turn), checks the game state
//! and exits 0 (1 on a failed check); with `HEXTERRAIN_SCREENSHOT=out.png` it saves a picture
//! first. Without the script, `HEXTERRAIN_SCREENSHOT` takes a picture after some frames.

use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap, HashSet};

use bevy::input::mouse::AccumulatedMouseScroll;
use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use hex_terrain_game::prelude::*;
use hexx::algorithms::a_star;

const MOVES: u32 = 4;
const PRESETS: [&str; 5] = [
    "maps/world.map.ron",
    "maps/island.map.ron",
    "maps/mediterranean.map.ron",
    "maps/inland.map.ron",
    "maps/continent.map.ron",
];

/// The camera's pivot on the ground; the streaming agent.
#[derive(Component)]
struct Rig {
    focus: Vec3,
    yaw: f32,
    distance: f32,
    target_focus: Vec3,
    target_yaw: f32,
    target_distance: f32,
}

#[derive(Component)]
struct Unit {
    tile: Hex,
    moves_left: u32,
    /// World positions still to walk through.
    path: Vec<Vec3>,
}

#[derive(Resource, Default)]
struct Game {
    turn: u32,
    selected: Option<Entity>,
    hovered: Option<Hex>,
    reachable: HashSet<Hex>,
    spawned: bool,
    show_chunks: bool,
}

#[derive(Component)]
struct Panel;

#[derive(Component)]
struct EndTurnButton;

fn main() -> AppExit {
    let scripted = std::env::var_os("HEXTERRAIN_SCRIPT").is_some();
    let mut app = App::new();
    app.add_plugins((DefaultPlugins, HexTerrainPlugin::from_asset(PRESETS[0])))
        .insert_resource(TerrainAppearance { outlines: true, outline_width: 0.04, ..default() })
        .insert_resource(Game { turn: 1, ..default() })
        .add_systems(Startup, setup)
        .add_systems(
            Update,
            (
                camera_controls,
                hover,
                place_units,
                (click, end_turn, keys).after(hover),
                walk,
                highlight,
                panel,
                chunk_boundaries,
            ),
        );
    if scripted {
        app.init_resource::<Script>().add_systems(PreUpdate, script.after(bevy::input::InputSystems));
    } else {
        app.add_plugins(hex_terrain_game::screenshot::ScreenshotModePlugin);
    }
    app.run()
}

fn setup(mut commands: Commands) {
    let focus = Vec3::new(48.0, 0.0, 40.0);
    commands
        .spawn((
            Rig { focus, yaw: 0.0, distance: 30.0, target_focus: focus, target_yaw: 0.0, target_distance: 30.0 },
            HexTerrainAgent::default(),
            Transform::from_translation(focus),
            // The camera below inherits visibility from the rig.
            Visibility::default(),
        ))
        .with_child((Camera3d::default(), Transform::default()));
    commands.spawn((
        DirectionalLight { illuminance: 9000.0, ..default() },
        Transform::from_xyz(4.0, 10.0, 2.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.spawn((
        Panel,
        Text::new(""),
        TextFont::from_font_size(16.0),
        Node { position_type: PositionType::Absolute, top: px(10.0), left: px(10.0), ..default() },
    ));
    commands.spawn((
        Text::new("WASD/arrows/edge pan, wheel zoom, Q/E rotate, click unit then tile, Enter end turn, G outlines, R new seed, 1-5 presets, F3 chunks"),
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

fn camera_controls(
    time: Res<Time>,
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

fn hover(
    windows: Query<&Window>,
    cameras: Query<(&Camera, &GlobalTransform)>,
    map: Res<HexMap>,
    mut game: ResMut<Game>,
    script: Option<Res<Script>>,
) {
    // A scripted run points at tiles itself.
    if script.is_some() {
        return;
    }
    let Some(cursor) = windows.iter().next().and_then(Window::cursor_position) else { return };
    let Some((camera, at)) = cameras.iter().next() else { return };
    let Ok(ray) = camera.viewport_to_world(at, cursor) else { return };
    game.hovered = map.raycast(ray, 2000.0).map(|hit| hit.tile).filter(|&t| map.contains(t));
}

/// Movement cost of entering a tile: land 1, mountain 3; sea, lakes and outside the map
/// impassable.
fn cost(map: &HexMap, tile: Hex) -> Option<u32> {
    if !map.contains(tile) || map.lake(tile).is_some() {
        return None;
    }
    match map.tile_kind(tile) {
        TileKind::Sea => None,
        TileKind::Land => Some(1),
        TileKind::Mountain => Some(3),
    }
}

/// Cost of the step from `a` to its neighbor `b`: entering `b`, plus 1 for fording a river, that
/// is entering a river tile from a tile its river does not come from or go to (walking along a
/// river costs nothing more).
fn step_cost(map: &HexMap, a: Hex, b: Hex) -> Option<u32> {
    let enter = cost(map, b)?;
    let ford = map.river(b).is_some_and(|r| r.downstream != Some(a) && !r.upstream.contains(&a));
    Some(enter + u32::from(ford))
}

/// What a path costs, step by step.
fn path_cost(map: &HexMap, path: &[Hex]) -> u32 {
    path.windows(2).filter_map(|w| step_cost(map, w[0], w[1])).sum()
}

/// Every tile reachable from `start` with `budget` moves (Dijkstra over [`step_cost`]), tiles
/// in `blocked` excluded.
fn reachable(map: &HexMap, start: Hex, budget: u32, blocked: &HashSet<Hex>) -> HashSet<Hex> {
    let mut best: HashMap<Hex, u32> = HashMap::from([(start, 0)]);
    let mut queue = BinaryHeap::from([(Reverse(0), start.x, start.y)]);
    while let Some((Reverse(spent), x, y)) = queue.pop() {
        let here = Hex::new(x, y);
        if best.get(&here).is_some_and(|&b| b < spent) {
            continue;
        }
        for next in here.all_neighbors() {
            if blocked.contains(&next) {
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
    best.into_keys().filter(|&t| t != start).collect()
}

/// Puts three units on land near the camera once the terrain exists, and back on the surface
/// (on land) after a regeneration.
#[expect(clippy::too_many_arguments, reason = "a system's parameters")]
fn place_units(
    mut commands: Commands,
    mut ready: MessageReader<TerrainReady>,
    map: Res<HexMap>,
    mut game: ResMut<Game>,
    rigs: Query<&Rig>,
    mut units: Query<(Entity, &mut Unit, &mut Transform)>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    if ready.read().count() == 0 {
        return;
    }
    let focus = rigs.iter().next().map_or(Vec3::ZERO, |r| r.focus);
    let land_near = |from: Hex, taken: &[Hex]| {
        (0..40u32).flat_map(|r| from.ring(r)).find(|&t| cost(&map, t) == Some(1) && !taken.contains(&t))
    };
    let mut taken = Vec::new();
    if game.spawned {
        for (_, mut unit, mut t) in &mut units {
            let tile = if cost(&map, unit.tile).is_some() { Some(unit.tile) } else { land_near(unit.tile, &taken) };
            if let Some(tile) = tile {
                unit.tile = tile;
                unit.path.clear();
                taken.push(tile);
                t.translation = map.tile_center(tile) + Vec3::Y * 0.6;
            }
        }
        // The selected unit's reach follows the new terrain.
        refresh_reachable(&map, &mut game, &units.transmute_lens::<(Entity, &Unit)>().query());
        return;
    }
    let mesh = meshes.add(Capsule3d::new(0.3, 0.6));
    let colors = [Color::srgb(0.85, 0.2, 0.15), Color::srgb(0.9, 0.75, 0.1), Color::srgb(0.6, 0.2, 0.8)];
    for color in colors {
        let Some(tile) = land_near(map.tile_at(focus), &taken) else { break };
        taken.push(tile);
        commands.spawn((
            Unit { tile, moves_left: MOVES, path: Vec::new() },
            Mesh3d(mesh.clone()),
            MeshMaterial3d(materials.add(color)),
            Transform::from_translation(map.tile_center(tile) + Vec3::Y * 0.6),
        ));
    }
    game.spawned = true;
}

fn click(
    mouse: Res<ButtonInput<MouseButton>>,
    map: Res<HexMap>,
    mut game: ResMut<Game>,
    mut units: Query<(Entity, &mut Unit)>,
) {
    if !mouse.just_pressed(MouseButton::Left) {
        return;
    }
    let Some(tile) = game.hovered else { return };
    let occupied: HashSet<Hex> = units.iter().map(|(_, u)| u.tile).collect();
    if let Some((e, _)) = units.iter().find(|(_, u)| u.tile == tile) {
        game.selected = Some(e);
    } else if let Some(e) = game.selected
        && let Ok((_, mut unit)) = units.get_mut(e)
        && game.reachable.contains(&tile)
    {
        // Other units block the way; the mover's own tile (hexx asks for the start's cost) does not.
        let from = unit.tile;
        let step = |a: Hex, b: Hex| if occupied.contains(&b) && b != from { None } else { step_cost(&map, a, b) };
        if let Some(path) = a_star(unit.tile, tile, step) {
            let spent = path_cost(&map, &path);
            if spent <= unit.moves_left {
                unit.moves_left -= spent;
                unit.path = path.iter().skip(1).map(|&t| map.tile_center(t) + Vec3::Y * 0.6).collect();
                unit.tile = tile;
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
    mut units: Query<(Entity, &mut Unit)>,
) {
    let pressed = buttons.iter().any(|i| *i == Interaction::Pressed);
    if !(keys.just_pressed(KeyCode::Enter) || pressed) {
        return;
    }
    game.turn += 1;
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
) {
    if keys.just_pressed(KeyCode::KeyG) {
        appearance.outlines = !appearance.outlines;
    }
    if keys.just_pressed(KeyCode::F3) {
        game.show_chunks = !game.show_chunks;
    }
    if keys.just_pressed(KeyCode::KeyR) {
        let mut config = map.config().clone();
        config.seed = config.seed.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
        load.write(LoadHexMap(config.into()));
    }
    let digits = [KeyCode::Digit1, KeyCode::Digit2, KeyCode::Digit3, KeyCode::Digit4, KeyCode::Digit5];
    for (i, key) in digits.into_iter().enumerate() {
        if keys.just_pressed(key) {
            load.write(LoadHexMap(PRESETS[i].into()));
        }
    }
}

/// Moves units along their paths, on the surface.
fn walk(time: Res<Time>, map: Res<HexMap>, mut units: Query<(&mut Unit, &mut Transform)>) {
    for (mut unit, mut t) in &mut units {
        let Some(&next) = unit.path.first() else { continue };
        let to = next - t.translation;
        let step = 6.0 * time.delta_secs();
        if to.length() <= step {
            t.translation = next;
            unit.path.remove(0);
        } else {
            t.translation += to.normalize() * step;
            t.translation.y = map.surface_height(t.translation) + 0.6;
        }
    }
}

fn highlight(game: Res<Game>, mut highlights: ResMut<TileHighlights>) {
    if !game.is_changed() {
        return;
    }
    highlights.hovered = game.hovered;
    let mut tiles: Vec<Hex> = game.reachable.iter().copied().collect();
    tiles.sort_unstable_by_key(|h| (h.x, h.y));
    highlights.selected = tiles;
}

fn panel(game: Res<Game>, map: Res<HexMap>, units: Query<&Unit>, mut text: Query<&mut Text, With<Panel>>) {
    let mut s = format!("Turn {}", game.turn);
    if let Some(tile) = game.hovered {
        let info = map.tile_info(tile);
        s += &format!(
            "\nTile ({}, {})  {} ({})  elevation {:.2}",
            tile.x,
            tile.y,
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
    }
    if let Some(unit) = game.selected.and_then(|e| units.get(e).ok()) {
        s += &format!("\nSelected unit: {} of {MOVES} moves left", unit.moves_left);
    }
    for mut t in &mut text {
        t.0.clone_from(&s);
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
        let corners = [
            rect.min,
            [rect.max[0] - 1, rect.min[1]],
            [rect.max[0] - 1, rect.max[1] - 1],
            [rect.min[0], rect.max[1] - 1],
        ]
        .map(|oc| {
            let [x, _, z] = terrain.tile_center(terrain.tile_from_offset(oc));
            Vec3::new(x, top, z)
        });
        for k in 0..4 {
            gizmos.line(corners[k], corners[(k + 1) % 4], Color::srgb(1.0, 0.3, 0.1));
        }
    }
}

/// A scripted turn for tests: select a unit, move it, end the turn, check the state.
#[derive(Resource, Default)]
struct Script {
    frame: u32,
    step: u32,
    generation: u64,
    target: Option<Hex>,
    start: Option<Hex>,
    expected_cost: u32,
}

#[expect(clippy::too_many_arguments, reason = "a system's parameters")]
fn script(
    mut commands: Commands,
    mut s: ResMut<Script>,
    appearance: Res<TerrainAppearance>,
    mut game: ResMut<Game>,
    map: Res<HexMap>,
    units: Query<(Entity, &Unit, &Transform)>,
    mut mouse: ResMut<ButtonInput<MouseButton>>,
    mut keys: ResMut<ButtonInput<KeyCode>>,
    mut exit: MessageWriter<AppExit>,
) {
    s.frame += 1;
    mouse.release(MouseButton::Left);
    for key in [KeyCode::Enter, KeyCode::KeyG, KeyCode::KeyR] {
        keys.release(key);
    }
    let fail = |msg: String, exit: &mut MessageWriter<AppExit>| {
        eprintln!("SCRIPT FAILED: {msg}");
        exit.write(AppExit::error());
    };
    if s.frame > 6000 {
        fail(format!("stuck at step {}", s.step), &mut exit);
        return;
    }
    match s.step {
        // Wait for the units, then click the first one.
        0 if game.spawned && units.iter().count() == 3 => {
            let Some((_, unit, _)) = units.iter().next() else { return };
            s.start = Some(unit.tile);
            game.hovered = Some(unit.tile);
            mouse.press(MouseButton::Left);
            s.step = 1;
        }
        // Selected: pick the reachable tile farthest along (cost > 1 if any) and click it.
        1 if game.selected.is_some() => {
            if game.reachable.is_empty() {
                fail("the selected unit can go nowhere".into(), &mut exit);
                return;
            }
            let start = s.start.unwrap_or_default();
            let mut options: Vec<Hex> = game.reachable.iter().copied().collect();
            options.sort_unstable_by_key(|h| (std::cmp::Reverse(h.unsigned_distance_to(start)), h.x, h.y));
            let target = options[0];
            let path = a_star(start, target, |a, b| step_cost(&map, a, b)).unwrap_or_default();
            s.expected_cost = path_cost(&map, &path);
            s.target = Some(target);
            game.hovered = Some(target);
            mouse.press(MouseButton::Left);
            s.step = 2;
        }
        // Wait for the walk to end, check, then end the turn.
        2 => {
            let Some((_, unit, t)) = units.iter().find(|(_, u, _)| Some(u.tile) == s.target) else { return };
            if !unit.path.is_empty() {
                return;
            }
            let Some(target) = s.target else { return };
            if unit.moves_left != MOVES - s.expected_cost {
                fail(format!("moves left {} after spending {}", unit.moves_left, s.expected_cost), &mut exit);
                return;
            }
            let ground = map.tile_center(target).y + 0.6;
            if (t.translation.y - ground).abs() > 0.05 {
                fail(format!("unit at height {} instead of {ground}", t.translation.y), &mut exit);
                return;
            }
            keys.press(KeyCode::Enter);
            s.step = 3;
        }
        3 if game.turn == 2 => {
            if units.iter().any(|(_, u, _)| u.moves_left != MOVES) {
                fail("movement points were not restored".into(), &mut exit);
                return;
            }
            // Outlines off, and a new seed.
            s.generation = map.generation();
            keys.press(KeyCode::KeyG);
            keys.press(KeyCode::KeyR);
            s.step = 4;
        }
        // After the regeneration every unit stands on land, on the new surface.
        4 if map.generation() > s.generation && s.frame.is_multiple_of(10) => {
            if appearance.outlines {
                fail("G did not toggle the outlines".into(), &mut exit);
                return;
            }
            let settled = units.iter().all(|(_, u, t)| {
                cost(&map, u.tile).is_some() && (t.translation.y - (map.tile_center(u.tile).y + 0.6)).abs() < 0.05
            });
            if !settled {
                return;
            }
            if let Some(&t) = game.reachable.iter().find(|&&t| cost(&map, t).is_none()) {
                fail(format!("tile {t:?} is shown reachable but impassable on the new map"), &mut exit);
                return;
            }
            s.step = 5;
        }
        5 => {
            println!(
                "SCRIPT OK: unit moved {:?} -> {:?} for {} moves; turn {}; outlines off; regenerated, units on land",
                s.start, s.target, s.expected_cost, game.turn
            );
            match std::env::var_os("HEXTERRAIN_SCREENSHOT") {
                Some(path) => {
                    commands.spawn(Screenshot::primary_window()).observe(
                        move |shot: On<ScreenshotCaptured>, mut exit: MessageWriter<AppExit>| {
                            if let Ok(img) = shot.image.clone().try_into_dynamic() {
                                let _ = img.to_rgb8().save(&path);
                            }
                            exit.write(AppExit::Success);
                        },
                    );
                    s.step = 6;
                }
                None => {
                    exit.write(AppExit::Success);
                    s.step = 6;
                }
            }
        }
        _ => {}
    }
}
