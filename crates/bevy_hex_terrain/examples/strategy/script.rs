//! The scripted turn (`HEXTERRAIN_SCRIPT=1`): select a unit, move it, end the turn, regenerate,
//! press on the minimap, checking the game state, the fog of war, the territory and the camera
//! on the way. With
//! `HEXTERRAIN_SCRIPT=seam`, on a wrapping map with the camera on its seam, the unit's reach
//! must cross the seam and the move goes to a tile on the other side, the short way.

use std::collections::HashSet;

use bevy::ecs::system::SystemParam;
use bevy::picking::pointer::{Location, PointerAction, PointerButton, PointerId, PointerInput};
use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy::ui::UiGlobalTransform;
use bevy_hex_terrain::prelude::*;

use crate::Game;
use crate::pieces::{LIFT, MOVES, Unit};
use crate::rig::Rig;
use crate::vision::{self, HUMAN, RIVAL};
use bevy_hex_terrain::{HexMinimap, MinimapPicture};

/// The mouse as the script moves it: to a tile's center on screen, then a press and a release,
/// one frame each, as `PointerInput` messages; the terrain picking backend turns them into the
/// `Pointer<Click>` the game observes.
#[derive(Resource, Default)]
pub struct ScriptedPointer {
    target: Option<PointAt>,
    phase: u8,
}

/// Where the scripted pointer goes.
#[derive(Clone, Copy)]
enum PointAt {
    /// A tile's center on the terrain.
    Tile(Hex),
    /// A position in the window (logical pixels).
    Screen(Vec2),
}

impl ScriptedPointer {
    /// Clicks a tile, starting next frame.
    fn click(&mut self, tile: Hex) {
        *self = Self { target: Some(PointAt::Tile(tile)), phase: 0 };
    }

    /// Clicks a position in the window, starting next frame.
    fn click_screen(&mut self, position: Vec2) {
        *self = Self { target: Some(PointAt::Screen(position)), phase: 0 };
    }
}

/// Moves the mouse pointer over the scripted tile and clicks it.
pub fn drive_pointer(
    mut pointer: ResMut<ScriptedPointer>,
    map: Res<HexMap>,
    cameras: Query<(&Camera, &GlobalTransform)>,
    windows: Query<Entity, With<bevy::window::PrimaryWindow>>,
    mut input: MessageWriter<PointerInput>,
) {
    let Some(point_at) = pointer.target else { return };
    let (Some((camera, at)), Ok(window)) = (cameras.iter().next(), windows.single()) else { return };
    let Some(target) = bevy::camera::RenderTarget::Window(bevy::window::WindowRef::Primary).normalize(Some(window))
    else {
        return;
    };
    let position = match point_at {
        // On a wrapping map, the copy of the tile on screen (the camera may look at the seam).
        PointAt::Tile(tile) => map
            .tile_center(tile)
            .map(|c| map.wrap_near(c, at.translation()))
            .and_then(|c| camera.world_to_viewport(at, c).ok()),
        PointAt::Screen(position) => Some(position),
    };
    let Some(position) = position else { return };
    let location = Location { target, position };
    let action = match pointer.phase {
        0 => PointerAction::Move { delta: Vec2::ZERO },
        1 => PointerAction::Press(PointerButton::Primary),
        _ => PointerAction::Release(PointerButton::Primary),
    };
    input.write(PointerInput::new(PointerId::Mouse, location, action));
    pointer.phase += 1;
    if pointer.phase == 3 {
        pointer.target = None;
    }
}

/// The minimap as the script sees it: its picture, its node on screen and the camera rig.
#[derive(SystemParam)]
pub struct MinimapProbe<'w, 's> {
    picture: Res<'w, MinimapPicture>,
    nodes: Query<'w, 's, (&'static ComputedNode, &'static UiGlobalTransform), With<HexMinimap>>,
    rigs: Query<'w, 's, &'static Rig>,
}

impl MinimapProbe<'_, '_> {
    /// The window position (logical pixels) of a pixel showing `tile` on the minimap.
    fn screen_of(&self, tile: Hex) -> Option<Vec2> {
        let minimap = self.picture.minimap()?;
        let pixels = minimap.pixels_of(tile);
        let i = *pixels.get(pixels.len() / 2)?;
        let [w, h] = minimap.size();
        let (node, transform) = self.nodes.single().ok()?;
        let scale = node.inverse_scale_factor();
        let on_node = Vec2::new(((i % w) as f32 + 0.5) / w as f32, ((i / w) as f32 + 0.5) / h as f32) - 0.5;
        Some(transform.translation * scale + on_node * node.size() * scale)
    }

    /// Where the camera is going.
    fn camera_target(&self) -> Option<Vec3> {
        self.rigs.iter().next().map(|r| r.target_focus)
    }
}

/// A scripted turn for tests: select a unit, move it, end the turn, check the state.
#[derive(Resource, Default)]
pub struct Script {
    frame: u32,
    step: u32,
    generation: u64,
    target: Option<Hex>,
    start: Option<Hex>,
    expected_cost: u32,
    /// Tiles visible before the move.
    seen: HashSet<Hex>,
    /// Tiles the human player owned before the turn ended.
    owned: usize,
    /// The tile pressed on the minimap, and the selection then (the press must not reach the
    /// terrain behind the minimap).
    minimap: Option<(Hex, Option<Entity>)>,
}

/// Whether the script crosses a wrapping map's seam (`HEXTERRAIN_SCRIPT=seam`).
fn across_the_seam() -> bool {
    std::env::var("HEXTERRAIN_SCRIPT").is_ok_and(|v| v == "seam")
}

/// Which half of the map a tile's column is in.
fn east_half(map: &HexMap, tile: Hex) -> bool {
    let columns = map.terrain().bounds().map_or(1, |b| b.max[0]);
    map.wrap_tile(tile).is_some_and(|own| map.terrain().offset_of(own)[0] >= columns / 2)
}

/// Checks the fog against what the units see, and with `owned` that every unit stands in its
/// player's territory (at the start, and after the end of a turn); the first mismatch.
fn check_vision(map: &HexMap, states: &TileStates, units: &Query<Seen>, owned: bool) -> Result<(), String> {
    let mut sight = HashSet::new();
    for (_, _, on, ..) in units.iter().filter(|(_, u, ..)| u.player == HUMAN) {
        sight.extend(vision::sight(map, on.tile));
        if owned && states.owner(on.tile) != Some(HUMAN) {
            return Err(format!("the human unit's tile {:?} belongs to nobody", on.tile));
        }
    }
    if let Some(t) = sight.iter().find(|&&t| states.visibility(t) != FogState::Visible) {
        return Err(format!("tile {t:?} is in sight but drawn {:?}", states.visibility(*t)));
    }
    let far =
        sight.iter().map(|&t| t + Hex::new(30, 0)).find(|&t| map.wrap_tile(t).is_some_and(|own| !sight.contains(&own)));
    if let Some(t) = far.filter(|&t| states.visibility(t) == FogState::Visible) {
        return Err(format!("tile {t:?}, far from every unit, is visible"));
    }
    for (_, _, on, _, visibility, _) in units.iter().filter(|(_, u, ..)| u.player == RIVAL) {
        if owned && states.owner(on.tile) != Some(RIVAL) {
            return Err(format!("the rival unit's tile {:?} is owned by {:?}", on.tile, states.owner(on.tile)));
        }
        let in_sight = sight.contains(&on.tile);
        if in_sight != (*visibility != Visibility::Hidden) {
            return Err(format!("rival unit on {:?}: in sight {in_sight}, shown {:?}", on.tile, visibility));
        }
    }
    Ok(())
}

/// Plays the scripted turn (`HEXTERRAIN_SCRIPT`): its state, the pointer it drives, its systems
/// before the game's input is read.
pub struct ScriptPlugin;

impl Plugin for ScriptPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<Script>()
            .init_resource::<ScriptedPointer>()
            .add_systems(PreUpdate, script.after(bevy::input::InputSystems))
            .add_systems(PreUpdate, drive_pointer.after(script).before(bevy::picking::PickingSystems::ProcessInput));
    }
}

/// What the script looks at: the game, the map, the tile states, the look and the units.
#[derive(bevy::ecs::system::SystemParam)]
pub struct Observed<'w, 's> {
    material: Res<'w, HexTerrainMaterialSettings>,
    style: Res<'w, HexTileStateStyle>,
    game: Res<'w, Game>,
    map: Res<'w, HexMap>,
    states: Res<'w, TileStates>,
    units: Query<'w, 's, Seen>,
    chunks: Query<'w, 's, &'static HexChunk>,
}

/// A unit as the script sees it: its player and moves, its tile, where it is drawn, whether it
/// is shown, and whether it is walking.
type Seen = (Entity, &'static Unit, &'static OnTile, &'static Transform, &'static Visibility, Has<TileWalk>);

/// Plays the scripted turn, a step once the previous one shows its effect.
pub fn script(
    mut commands: Commands,
    mut s: ResMut<Script>,
    observed: Observed,
    mut pointer: ResMut<ScriptedPointer>,
    minimap: MinimapProbe,
    mut keys: ResMut<ButtonInput<KeyCode>>,
    mut exit: MessageWriter<AppExit>,
) {
    let Observed { material, style, game, map, states, units, chunks } = observed;
    s.frame += 1;
    for key in [KeyCode::Enter, KeyCode::KeyG, KeyCode::KeyR, KeyCode::KeyL, KeyCode::KeyM, KeyCode::KeyU] {
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
        0 if game.spawned && units.iter().count() == 5 && s.frame.is_multiple_of(5) => {
            if let Err(e) = check_vision(&map, &states, &units, true) {
                fail(format!("before the move: {e}"), &mut exit);
                return;
            }
            s.seen = units
                .iter()
                .filter(|(_, u, ..)| u.player == HUMAN)
                .flat_map(|(_, _, on, ..)| vision::sight(&map, on.tile))
                .collect();
            let Some((_, _, on, ..)) = units.iter().find(|(_, u, ..)| u.player == HUMAN) else { return };
            s.start = Some(on.tile);
            pointer.click(on.tile);
            s.step = 1;
        }
        // Selected: pick the reachable tile farthest along (cost > 1 if any) and click it.
        1 if game.selected.is_some() => {
            if game.reachable.is_empty() {
                fail("the selected unit can go nowhere".into(), &mut exit);
                return;
            }
            if states.highlighted(Highlight::Reachable).count() != game.reachable.len() {
                fail(
                    format!(
                        "{} reachable tiles, {} highlighted",
                        game.reachable.len(),
                        states.highlighted(Highlight::Reachable).count()
                    ),
                    &mut exit,
                );
                return;
            }
            let start = s.start.unwrap_or_default();
            let mut options: Vec<Hex> = game.reachable.iter().copied().collect();
            if across_the_seam() {
                // The reach crosses the seam: go to a tile on the other side of it.
                let side = east_half(&map, start);
                options.retain(|&t| east_half(&map, t) != side && map.distance(t, start).is_some_and(|d| d <= MOVES));
                if options.is_empty() || map.terrain().wrap().is_none() {
                    fail(format!("the reach of the unit on {start:?} does not cross the seam"), &mut exit);
                    return;
                }
            }
            options.sort_unstable_by_key(|&h| (std::cmp::Reverse(map.distance(h, start)), h.x, h.y));
            let target = options[0];
            // The map's cheapest path around the other units (the short way round, across the
            // seam when cheaper).
            let others: HashSet<Hex> = units.iter().map(|(_, _, on, ..)| on.tile).filter(|&t| t != start).collect();
            let Some(path) = map.path_avoiding(start, target, |t| others.contains(&t)) else {
                fail(format!("no path to the reachable {target:?}"), &mut exit);
                return;
            };
            if path.tiles.len() as u32 > MOVES + 1 {
                fail(format!("the path to {target:?} takes {} steps", path.tiles.len() - 1), &mut exit);
                return;
            }
            s.expected_cost = path.cost;
            s.target = Some(target);
            pointer.click(target);
            s.step = 2;
        }
        // Wait for the walk to end, check, then end the turn.
        2 => {
            let Some((_, unit, _, t, _, walking)) = units.iter().find(|(_, _, on, ..)| Some(on.tile) == s.target)
            else {
                return;
            };
            if walking {
                return;
            }
            let Some(target) = s.target else { return };
            if unit.moves_left != MOVES - s.expected_cost {
                fail(format!("moves left {} after spending {}", unit.moves_left, s.expected_cost), &mut exit);
                return;
            }
            let Some(ground) = map.tile_center(target).map(|c| c.y + LIFT) else { return };
            if (t.translation.y - ground).abs() > 0.05 {
                fail(format!("unit at height {} instead of {ground}", t.translation.y), &mut exit);
                return;
            }
            if let Err(e) = check_vision(&map, &states, &units, false) {
                fail(format!("after the move: {e}"), &mut exit);
                return;
            }
            if let Some(t) = s.seen.iter().find(|&&t| states.visibility(t) == FogState::Unexplored) {
                fail(format!("tile {t:?} was seen and is unexplored again"), &mut exit);
                return;
            }
            s.owned = owned(&map, &states, HUMAN);
            keys.press(KeyCode::Enter);
            s.step = 3;
        }
        3 if game.turn == 2 => {
            if units.iter().any(|(_, u, ..)| u.moves_left != MOVES) {
                fail("movement points were not restored".into(), &mut exit);
                return;
            }
            let now = owned(&map, &states, HUMAN);
            if now <= s.owned {
                fail(
                    format!("the territory did not grow at the end of the turn ({} tiles, then {now})", s.owned),
                    &mut exit,
                );
                return;
            }
            println!("SCRIPT: territory {} -> {now} tiles", s.owned);
            keys.press(KeyCode::KeyL);
            // Outlines off, and a new seed.
            s.generation = map.generation();
            keys.press(KeyCode::KeyG);
            keys.press(KeyCode::KeyR);
            s.step = 4;
        }
        // After the regeneration every unit stands on land, on the new surface.
        4 if map.generation() > s.generation && s.frame.is_multiple_of(10) => {
            if material.outlines || !style.lens {
                fail("G did not toggle the outlines or L the lens".into(), &mut exit);
                return;
            }
            // The chunk under each unit shows the new map (so its lens colors are painted: the
            // game paints a chunk's tiles when it arrives, in the frame before this one).
            let terrain = map.terrain();
            let shown = |tile: Hex| {
                let Some(mine) = terrain.chunk_of(tile).map(|c| terrain.wrap_chunk(c).0) else { return false };
                chunks.iter().any(|c| terrain.wrap_chunk(c.coord).0 == mine && c.generation == Some(map.generation()))
            };
            let settled = units.iter().all(|(_, _, on, t, ..)| {
                map.move_cost(on.tile).is_some()
                    && map.tile_center(on.tile).is_some_and(|c| (t.translation.y - (c.y + LIFT)).abs() < 0.05)
                    && shown(on.tile)
            });
            if !settled {
                return;
            }
            if let Some(&t) = game.reachable.iter().find(|&&t| map.move_cost(t).is_none()) {
                fail(format!("tile {t:?} is shown reachable but impassable on the new map"), &mut exit);
                return;
            }
            // Another map: territory starts again around the units, and the fog from what they see.
            if let Err(e) = check_vision(&map, &states, &units, true) {
                fail(format!("after the regeneration: {e}"), &mut exit);
                return;
            }
            let Some((_, _, on, ..)) = units.iter().next() else { return };
            // Overlays are stored in 8 bits a channel.
            let bytes = |c: Option<Color>| c.map(|c| c.to_srgba().to_u8_array());
            if bytes(states.overlay(on.tile)) != bytes(vision::lens_color(&map, on.tile)) {
                fail(
                    format!("the lens color of a unit's tile {:?} is {:?}", on.tile, states.overlay(on.tile)),
                    &mut exit,
                );
                return;
            }
            s.step = 5;
        }
        // A press on the minimap, on a tile across the map from the camera, sends it there.
        5 if minimap.picture.minimap().is_some() && !minimap.picture.is_building() => {
            let (Some(bounds), Some(focus)) = (map.terrain().bounds(), minimap.camera_target()) else { return };
            let here = map.tile_at(focus).unwrap_or_default();
            let row = bounds.max[1] / 2;
            let far = [bounds.max[0] / 4, 3 * bounds.max[0] / 4]
                .map(|col| map.terrain().tile_from_offset([col, row]))
                .into_iter()
                .max_by_key(|&t| map.distance(t, here))
                .unwrap_or_default();
            let Some(position) = minimap.screen_of(far) else {
                fail(format!("tile {far:?} is not on the minimap"), &mut exit);
                return;
            };
            s.minimap = Some((far, game.selected));
            pointer.click_screen(position);
            s.step = 6;
        }
        6 => {
            let (Some((tile, selected)), Some(target)) = (s.minimap, minimap.camera_target()) else { return };
            if map.tile_at(target) != Some(tile) {
                return;
            }
            if game.selected != selected {
                fail("the press on the minimap reached the terrain behind it".into(), &mut exit);
                return;
            }
            println!("SCRIPT: a press on the minimap sent the camera to {tile:?}");
            // M: the first map type, Pangaea.
            s.generation = map.generation();
            keys.press(KeyCode::KeyM);
            s.step = 7;
        }
        // The Pangaea preset, its targets met, every unit on its land.
        7 if map.generation() > s.generation && s.frame.is_multiple_of(10) => {
            let Some(report) = map.terrain().map_type() else {
                fail("M did not load a map type".into(), &mut exit);
                return;
            };
            if report.kind != MapType::Pangaea || !report.met() {
                fail(format!("M loaded {report}"), &mut exit);
                return;
            }
            if !units.iter().all(|(_, _, on, ..)| map.move_cost(on.tile).is_some()) {
                return;
            }
            println!("SCRIPT: M loaded the Pangaea map type, every target met, the units on its land");
            // U: the World preset under the first other terrain ruleset, Civilization V's.
            s.generation = map.generation();
            keys.press(KeyCode::KeyU);
            s.step = 8;
        }
        // Civilization V's terrain: every tile a terrain of the ruleset, the units on its land.
        8 if map.generation() > s.generation && s.frame.is_multiple_of(10) => {
            let ruleset = map.terrain().ruleset();
            if ruleset.name != "Civilization V" || !map.terrain().has_own_ruleset() {
                fail(format!("U loaded the ruleset {:?}", ruleset.name), &mut exit);
                return;
            }
            let forests = map.terrain().tiles().filter(|&t| {
                map.tile_info(t).and_then(|i| i.terrain.feature).is_some_and(|f| ruleset.feature(f).id == "forest")
            });
            if forests.count() == 0 {
                fail("no forest under Civilization V's terrain".into(), &mut exit);
                return;
            }
            if !units.iter().all(|(_, _, on, ..)| map.move_cost(on.tile).is_some()) {
                return;
            }
            println!(
                "SCRIPT: U loaded the World preset under Civilization V's terrain, forests on it, the units on its land"
            );
            s.step = 9;
        }
        9 if s.frame.is_multiple_of(5) => {
            println!(
                "SCRIPT OK: unit moved {:?} -> {:?} for {} moves{}; turn {}; fog and territory checked; outlines \
                 off; lens on; regenerated, units on land; the minimap moved the camera; M loaded a map type; U a ruleset",
                s.start,
                s.target,
                s.expected_cost,
                if across_the_seam() { " across the seam" } else { "" },
                game.turn
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
                    s.step = 9;
                }
                None => {
                    exit.write(AppExit::Success);
                    s.step = 9;
                }
            }
        }
        _ => {}
    }
}

/// Tiles of the map's chunks owned by `player` (the whole map: every preset the script plays is
/// bounded).
fn owned(map: &HexMap, states: &TileStates, player: u32) -> usize {
    map.terrain().tiles().filter(|&t| states.owner(t) == Some(player)).count()
}
