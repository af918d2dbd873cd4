//! What the players see and own: every player's fog of war kept in one `FogOfWar` (the core's,
//! as a server would keep it) from their units' sight by the map's sight rule, the human's shown
//! through the terrain's per-tile state; territory around each player's units; the
//! movement-cost lens (L); and the highlights of the hovered tile, the selected unit and its
//! whole reachable set.

use std::collections::HashSet;

use bevy::prelude::*;
use bevy_hex_terrain::hex_terrain::FogOfWar;
use bevy_hex_terrain::prelude::*;

use crate::Game;
use crate::pieces::Unit;

/// The human player (the fog shows what this player's units see): player 0, on the setup's first
/// start, as the setup and the tile states number players.
pub const HUMAN: u32 = 0;
/// The other player.
pub const RIVAL: u32 = 1;
/// Sight radius on flat land.
pub const SIGHT: u32 = 4;
/// Territory radius claimed around a player's first unit.
pub const HOME_RADIUS: u32 = 3;

/// Tiles a unit on `from` sees: the map's sight rule (`HexMap::field_of_view`: higher tiles and
/// mountains block the view, hills and forests see one tile farther, mountains two) with
/// [`SIGHT`].
pub fn sight(map: &HexMap, from: Hex) -> HashSet<Hex> {
    // A reach of at most `SIGHT` plus the bonus of a mountain is within every map's limit.
    map.field_of_view(from, SIGHT).unwrap_or_default().into_iter().collect()
}

/// Every player's fog of war, for the map it was made for.
#[derive(Resource)]
pub struct Fogs {
    /// The map (`HexMap::map_id`).
    map_id: u64,
    /// The human's and the rival's fog.
    pub fog: FogOfWar,
}

/// Fog of war: whenever a unit enters another tile (also while walking) or the map changes,
/// each player's fog is updated from its units' sight (what was visible becomes explored, what
/// they see now visible), and the human's is shown. The plugin hides rival units (`OnTile`)
/// whose tile is not in sight.
pub fn update_fog(
    mut commands: Commands,
    map: Res<HexMap>,
    fogs: Option<ResMut<Fogs>>,
    mut states: ResMut<TileStates>,
    units: Query<(&Unit, &OnTile)>,
    mut seen_from: Local<Vec<(u32, Hex)>>,
) {
    let mut from: Vec<(u32, Hex)> = units.iter().map(|(u, on)| (u.player, on.tile)).collect();
    from.sort_unstable_by_key(|&(p, h)| (p, h.x, h.y));
    let new_map = fogs.as_ref().is_none_or(|f| f.map_id != map.map_id());
    if from == *seen_from && !map.is_changed() && !new_map {
        return;
    }
    seen_from.clone_from(&from);
    let terrain = map.terrain();
    let mut made = None;
    let fogs = match fogs {
        Some(fogs) if !new_map => fogs.into_inner(),
        _ => {
            let fog = FogOfWar::new(terrain, 2).expect("two players");
            made.insert(Fogs { map_id: map.map_id(), fog })
        }
    };
    for player in [HUMAN, RIVAL] {
        let sight = from.iter().filter(|(p, _)| *p == player).map(|&(_, tile)| (tile, SIGHT));
        // The fog is of this map, and both players are in it: nothing is refused.
        let _ = fogs.fog.update(terrain, player, sight);
    }
    let _ = states.show_fog(&fogs.fog, HUMAN);
    if let Some(fogs) = made {
        commands.insert_resource(fogs);
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

/// Territory grows at the end of each turn: each player, in turn, claims every tile nobody owns
/// next to its territory.
pub fn grow_territory(map: &HexMap, states: &mut TileStates) {
    for player in [HUMAN, RIVAL] {
        let border: Vec<Hex> = map
            .terrain()
            .tiles()
            .filter(|&t| states.owner(t).is_none())
            .filter(|&t| map.neighbors(t).into_iter().flatten().flatten().any(|n| states.owner(n) == Some(player)))
            .collect();
        for tile in border {
            let _ = states.set_owner(tile, Some(player));
        }
    }
}

/// The highlights: hovered tile, selected unit, its whole reachable set.
pub fn highlight(game: Res<Game>, units: Query<&OnTile, With<Unit>>, mut states: ResMut<TileStates>) {
    if !game.is_changed() {
        return;
    }
    states.replace_highlight(Highlight::Hovered, game.hovered);
    let selected = game.selected.and_then(|e| units.get(e).ok()).map(|on| on.tile);
    states.replace_highlight(Highlight::Selected, selected);
    states.replace_highlight(Highlight::Reachable, game.reachable.iter().copied());
}

/// The movement-cost lens colors, by the map's movement model: green for 1, yellow for 2,
/// orange for more; what cannot be entered (water, mountains) keeps its color.
pub fn lens_color(map: &HexMap, tile: Hex) -> Option<Color> {
    match map.move_cost(tile)? {
        1 => Some(Color::srgba(0.2, 0.9, 0.2, 0.55)),
        2 => Some(Color::srgba(0.95, 0.85, 0.1, 0.6)),
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
