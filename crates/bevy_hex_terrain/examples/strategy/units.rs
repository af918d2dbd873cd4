//! Units and turns: the players' units placed on the setup's starts, selecting and moving them
//! with the pointer by the map's rules (`HexMap::path_avoiding`, `reachable_avoiding`: the map
//! file's movement model, which the fairness report measures too), and ending the turn. Units
//! are `OnTile` entities: the plugin keeps them on the surface, walks their `TileWalk`s and
//! hides the rival's under the fog.

use std::collections::HashSet;

use bevy::picking::events::{Click, Pointer};
use bevy::picking::pointer::PointerButton;
use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;

use crate::Game;
use crate::panel::EndTurnButton;
use crate::pieces::{LIFT, MOVES, Unit};
use crate::rig::Rig;
use crate::vision;

/// World units a second a unit walks.
const SPEED: f32 = 6.0;

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
/// each player claiming territory around its units, the camera over yours.
pub(crate) fn place_units(
    mut commands: Commands,
    mut ready: MessageReader<TerrainReady>,
    mut game: ResMut<Game>,
    mut rigs: Query<(&mut Rig, &mut Transform)>,
    ground: UnitGround,
) {
    let UnitGround { map, mut states, mut meshes, mut materials } = ground;
    if ready.read().count() == 0 || game.spawned {
        return;
    }
    // A map with a game setup puts the players on its starts, the camera over yours.
    let starts = map.setup().map(|s| s.starts().to_vec()).filter(|s| s.len() >= 2);
    if let Some(center) = starts.as_ref().and_then(|s| map.tile_center(s[0])) {
        for (mut rig, mut t) in &mut rigs {
            let focus = Vec3::new(center.x, 0.0, center.z);
            rig.focus = focus;
            rig.target_focus = focus;
            t.translation = focus;
        }
    }
    let focus = rigs.iter().next().map_or(Vec3::ZERO, |(r, _)| r.focus);
    let mut taken = Vec::new();
    let mesh = meshes.add(Capsule3d::new(0.3, 0.6));
    let Some(home) = map.tile_at(focus) else { return };
    // Without a setup, the rival starts on the first land tile of the ring at RIVAL_DISTANCE,
    // searching from the east.
    let rival_home = match &starts {
        Some(s) => s[1],
        None => home.ring(RIVAL_DISTANCE).find(|&t| map.move_cost(t) == Some(1)).unwrap_or(home),
    };
    let home = starts.as_ref().map_or(home, |s| s[0]);
    let human = [Color::srgb(0.85, 0.2, 0.15), Color::srgb(0.9, 0.75, 0.1), Color::srgb(0.95, 0.45, 0.1)];
    let rival = [Color::srgb(0.15, 0.35, 0.9), Color::srgb(0.2, 0.7, 0.85)];
    for (player, near, colors) in [(vision::HUMAN, home, &human[..]), (vision::RIVAL, rival_home, &rival[..])] {
        for (i, &color) in colors.iter().enumerate() {
            let Some(tile) = land_near(&map, near, &taken) else { break };
            taken.push(tile);
            let radius = if i == 0 { vision::HOME_RADIUS } else { vision::HOME_RADIUS - 1 };
            vision::claim(&map, &mut states, player, tile, radius);
            commands.spawn((
                Unit { player, moves_left: MOVES },
                OnTile { lift: LIFT, ..OnTile::new(tile) },
                Mesh3d(mesh.clone()),
                MeshMaterial3d(materials.add(color)),
            ));
        }
    }
    game.spawned = true;
    game.map_id = map.map_id();
}

/// The open land tile (cost 1) nearest `from`, not in `taken`.
fn land_near(map: &HexMap, from: Hex, taken: &[Hex]) -> Option<Hex> {
    (0..40u32)
        .flat_map(|r| from.ring(r))
        .filter_map(|t| map.wrap_tile(t))
        .find(|&t| map.move_cost(t) == Some(1) && !taken.contains(&t))
}

/// When the map changes (an edit, a regeneration, another preset): every unit back on a tile
/// it can enter, territory claimed again around the units on another map (which starts with
/// none), and the selected unit's reach on the new terrain. The terrain's queries answer at
/// once, before its chunks are streamed.
pub(crate) fn follow_map(
    mut commands: Commands,
    map: Res<HexMap>,
    mut game: ResMut<Game>,
    mut states: ResMut<TileStates>,
    mut units: Query<(Entity, &Unit, &mut OnTile)>,
) {
    if !map.is_changed() || !game.spawned {
        return;
    }
    let another = std::mem::replace(&mut game.map_id, map.map_id()) != map.map_id();
    let mut taken = Vec::new();
    for (entity, unit, mut on) in &mut units {
        let tile = if map.move_cost(on.tile).is_some() { Some(on.tile) } else { land_near(&map, on.tile, &taken) };
        if let Some(tile) = tile {
            on.set_if_neq(OnTile { tile, ..*on });
            taken.push(tile);
            if another {
                commands.entity(entity).remove::<TileWalk>();
                vision::claim(&map, &mut states, unit.player, tile, vision::HOME_RADIUS - 1);
            }
        }
    }
    refresh_reachable(&map, &mut game, &units.transmute_lens::<(Entity, &Unit, &OnTile)>().query());
}

/// A click on the terrain: select the human unit on the tile, or move the selected unit there.
pub(crate) fn click(
    pointer: On<Pointer<Click>>,
    mut commands: Commands,
    map: Res<HexMap>,
    mut game: ResMut<Game>,
    mut units: Query<(Entity, &mut Unit, &OnTile)>,
) {
    // A click on a prop bubbles up to its chunk: act on the first. In the world builder a click
    // paints instead.
    if game.editing || pointer.button != PointerButton::Primary || pointer.entity != pointer.original_event_target() {
        return;
    }
    let Some(tile) = pointer.hit.extra_as::<HexPick>().map(|p| p.tile).filter(|&t| map.contains(t)) else { return };
    game.hovered = Some(tile);
    let occupied: HashSet<Hex> = units.iter().map(|(_, _, on)| on.tile).collect();
    if let Some((e, ..)) = units.iter().find(|(_, u, on)| on.tile == tile && u.player == vision::HUMAN) {
        game.selected = Some(e);
    } else if let Some(e) = game.selected
        && let Ok((_, mut unit, on)) = units.get_mut(e)
        && game.reachable.contains(&tile)
    {
        // The map's rules: other units block the way; on a wrapping map the path takes the short
        // way, across the seam when that is cheaper, and the walk follows it.
        if let Some(path) = map.path_avoiding(on.tile, tile, |t| occupied.contains(&t))
            && path.cost <= unit.moves_left
        {
            unit.moves_left -= path.cost;
            commands.entity(e).insert(TileWalk::new(path.tiles, SPEED));
        }
    }
    refresh_reachable(&map, &mut game, &units.transmute_lens::<(Entity, &Unit, &OnTile)>().query());
}

/// Where the selected unit can go with the moves it has left, by the map's rules, around the
/// other units (before it walks: it is reckoned from where the walk ends).
pub(crate) fn refresh_reachable(map: &HexMap, game: &mut Game, units: &Query<(Entity, &Unit, &OnTile)>) {
    game.reachable.clear();
    let Some(e) = game.selected else { return };
    let Ok((_, unit, on)) = units.get(e) else { return };
    let occupied: HashSet<Hex> = units.iter().filter(|(o, ..)| *o != e).map(|(_, _, on)| on.tile).collect();
    game.reachable = map
        .reachable_avoiding(on.tile, unit.moves_left, |t| occupied.contains(&t))
        .into_iter()
        .map(|(tile, _)| tile)
        .filter(|&tile| tile != on.tile)
        .collect();
}

/// The selected unit's reach again when a walk ends (it was reckoned from where it started).
pub(crate) fn walk_ended(
    _ended: On<WalkEnded>,
    map: Res<HexMap>,
    mut game: ResMut<Game>,
    units: Query<(Entity, &Unit, &OnTile)>,
) {
    refresh_reachable(&map, &mut game, &units);
}

pub(crate) fn end_turn(
    keys: Res<ButtonInput<KeyCode>>,
    buttons: Query<&Interaction, (Changed<Interaction>, With<EndTurnButton>)>,
    map: Res<HexMap>,
    mut game: ResMut<Game>,
    mut states: ResMut<TileStates>,
    mut units: Query<(Entity, &mut Unit, &OnTile)>,
) {
    let pressed = buttons.iter().any(|i| *i == Interaction::Pressed);
    if !(keys.just_pressed(KeyCode::Enter) || pressed) {
        return;
    }
    game.turn += 1;
    vision::grow_territory(&map, &mut states);
    for (_, mut unit, _) in &mut units {
        unit.moves_left = MOVES;
    }
    refresh_reachable(&map, &mut game, &units.transmute_lens::<(Entity, &Unit, &OnTile)>().query());
}
