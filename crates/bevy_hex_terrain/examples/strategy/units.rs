//! Units and turns: the players' units placed on the setup's starts, selecting and moving them
//! with the pointer, and ending the turn.

use std::collections::HashSet;

use bevy::picking::events::{Click, Pointer};
use bevy::picking::pointer::PointerButton;
use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;
use hexx::algorithms::a_star;

use crate::Game;
use crate::movement::{MOVES, cost, path_cost, reachable, step_cost};
use crate::panel::EndTurnButton;
use crate::rig::Rig;
use crate::vision;

#[derive(Component)]
pub(crate) struct Unit {
    /// [`vision::HUMAN`] or [`vision::RIVAL`].
    pub(crate) player: u32,
    pub(crate) tile: Hex,
    pub(crate) moves_left: u32,
    /// World positions still to walk through.
    pub(crate) path: Vec<Vec3>,
}

/// Distance from the human player's units to the rival's.
const RIVAL_DISTANCE: u32 = 7;

/// Where units are placed (the map, its tile states) and the assets new ones are made of.
#[derive(bevy::ecs::system::SystemParam)]
pub(crate) struct UnitGround<'w> {
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
pub(crate) fn place_units(
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
            .filter_map(|t| map.wrap_tile(t))
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
pub(crate) fn click(
    pointer: On<Pointer<Click>>,
    map: Res<HexMap>,
    mut game: ResMut<Game>,
    mut units: Query<(Entity, &mut Unit)>,
) {
    // A click on a prop bubbles up to its chunk: act on the first. In the world builder a click
    // paints instead.
    if game.editing || pointer.button != PointerButton::Primary || pointer.entity != pointer.original_event_target() {
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
            let taken = map.wrap_tile(b).is_some_and(|own| occupied.contains(&own)) && b != from;
            if taken { None } else { step_cost(&map, a, b) }
        };
        if let Some(path) = a_star(from, goal, step) {
            let spent = path_cost(&map, &path);
            if spent <= unit.moves_left {
                unit.moves_left -= spent;
                unit.path =
                    path.iter().skip(1).filter_map(|&t| map.tile_center(t)).map(|c| c + Vec3::Y * 0.6).collect();
                unit.tile = map.wrap_tile(goal).unwrap_or(tile);
            }
        }
    }
    refresh_reachable(&map, &mut game, &units.transmute_lens::<(Entity, &Unit)>().query());
}

pub(crate) fn refresh_reachable(map: &HexMap, game: &mut Game, units: &Query<(Entity, &Unit)>) {
    game.reachable.clear();
    let Some(e) = game.selected else { return };
    let Ok((_, unit)) = units.get(e) else { return };
    let occupied: HashSet<Hex> = units.iter().filter(|(o, _)| *o != e).map(|(_, u)| u.tile).collect();
    // hexx's field of movement charges per tile entered; fording a river depends on the step,
    // so the reach is a small Dijkstra over the same step costs as the A* path.
    game.reachable = reachable(map, unit.tile, unit.moves_left, &occupied);
}

pub(crate) fn end_turn(
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
