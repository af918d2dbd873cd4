//! What the player sees and owns, written into the terrain's per-tile state: fog of war from
//! the units' sight (mountains block it, hills and mountains see farther), territory around each
//! player's units, the movement-cost lens (L), and the highlights of the hovered tile, the
//! selected unit and its whole reachable set.

use std::collections::HashSet;

use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;
use hexx::algorithms::range_fov;

use crate::Game;
use crate::movement::cost;
use crate::units::Unit;

/// The human player (the fog shows what this player's units see): player 0, on the setup's first
/// start, as the setup and the tile states number players.
pub const HUMAN: u32 = 0;
/// The other player.
pub const RIVAL: u32 = 1;
/// Sight radius on flat land.
pub const SIGHT: u32 = 4;
/// Territory radius claimed around a player's first unit.
pub const HOME_RADIUS: u32 = 3;

/// Tiles a unit on `from` sees: [`SIGHT`], one more from hills, two more from a mountain;
/// mountains block the view behind them (the mountain itself is seen).
pub fn sight(map: &HexMap, from: Hex) -> HashSet<Hex> {
    let bonus = match (map.tile_kind(from), map.biome(from)) {
        (Some(TileKind::Mountain), _) => 2,
        (_, Some(Biome::Hills)) => 1,
        _ => 0,
    };
    let range = SIGHT + bonus;
    let blocks = |h: Hex| h != from && map.tile_kind(h) == Some(TileKind::Mountain);
    let mut seen: HashSet<Hex> = range_fov(from, range, blocks).into_iter().collect();
    let faces: Vec<Hex> = seen
        .iter()
        .flat_map(|h| h.all_neighbors())
        .filter(|&n| blocks(n) && n.unsigned_distance_to(from) <= range)
        .collect();
    seen.extend(faces);
    seen.insert(from);
    // The map's own tiles (the view may reach across a wrapping map's seam).
    seen.into_iter().filter_map(|h| map.wrap_tile(h)).collect()
}

/// Fog of war: whenever a human unit enters another tile (also while walking) or the map
/// changes, what was visible becomes explored and what the human units see now becomes
/// visible; rival units out of sight are hidden.
pub fn update_fog(
    map: Res<HexMap>,
    mut states: ResMut<TileStates>,
    mut units: Query<(&Unit, &Transform, &mut Visibility)>,
    mut seen_from: Local<Vec<Hex>>,
) {
    let mut from: Vec<Hex> =
        units.iter().filter(|(u, ..)| u.player == HUMAN).filter_map(|(_, t, _)| map.tile_at(t.translation)).collect();
    from.sort_unstable_by_key(|h| (h.x, h.y));
    if from != *seen_from || map.is_changed() {
        seen_from.clone_from(&from);
        states.hide_visible();
        for &unit in &from {
            for tile in sight(&map, unit) {
                // `sight` keeps to the map: no write is refused.
                let _ = states.set_visibility(tile, FogState::Visible);
            }
        }
    }
    for (unit, t, mut visibility) in &mut units {
        let shown = unit.player == HUMAN
            || map.tile_at(t.translation).is_some_and(|tile| states.visibility(tile) == FogState::Visible);
        visibility.set_if_neq(if shown { Visibility::Inherited } else { Visibility::Hidden });
    }
}

/// Claims for `player` the tiles within `radius` of `center` that nobody owns.
pub fn claim(map: &HexMap, states: &mut TileStates, player: u32, center: Hex, radius: u32) {
    for tile in center.range(radius) {
        if map.contains(tile) && states.owner(tile).is_none() {
            let _ = states.set_owner(tile, Some(player));
        }
    }
}

/// Territory grows at the end of each turn: one ring around every unit.
pub fn grow_territory(map: &HexMap, states: &mut TileStates, units: &Query<(Entity, &mut Unit)>) {
    for (_, unit) in units.iter() {
        claim(map, states, unit.player, unit.tile, 1);
    }
}

/// The highlights: hovered tile, selected unit, its whole reachable set.
pub fn highlight(game: Res<Game>, units: Query<&Unit>, mut states: ResMut<TileStates>) {
    if !game.is_changed() {
        return;
    }
    states.replace_highlight(Highlight::Hovered, game.hovered);
    let selected = game.selected.and_then(|e| units.get(e).ok()).map(|u| u.tile);
    states.replace_highlight(Highlight::Selected, selected);
    states.replace_highlight(Highlight::Reachable, game.reachable.iter().copied());
}

/// The movement-cost lens colors: green for 1, orange for 3; water (impassable) keeps its
/// color.
pub fn lens_color(map: &HexMap, tile: Hex) -> Option<Color> {
    match cost(map, tile)? {
        1 => Some(Color::srgba(0.2, 0.9, 0.2, 0.55)),
        _ => Some(Color::srgba(1.0, 0.5, 0.05, 0.65)),
    }
}

/// Writes the lens colors of every tile of the chunks that arrive (all of a bounded map), once a
/// map generation; L toggles the lens itself.
pub fn paint_lens(
    map: Res<HexMap>,
    mut spawned: MessageReader<ChunkSpawned>,
    mut states: ResMut<TileStates>,
    mut painted: Local<(u64, HashSet<ChunkCoord>)>,
) {
    if painted.0 != map.generation() {
        *painted = (map.generation(), HashSet::new());
    }
    let terrain = map.terrain();
    for chunk in spawned.read() {
        if !painted.1.insert(chunk.coord) {
            continue;
        }
        let Some(rect) = terrain.chunk_rect(chunk.coord) else { continue };
        for oc in rect.iter() {
            let tile = terrain.tile_from_offset(oc);
            let _ = states.set_overlay(tile, lens_color(&map, tile));
        }
    }
}
