//! The rules' view of each tile of a bounded map: what entering it costs, which of its edges a
//! step crosses a river on, and how tall it stands for sight, computed once on the first rules query (paths, reach, sight, fog) and shared by
//! every clone of the [`Terrain`]. A table of the answers [`Terrain::move_cost`] and
//! [`Terrain::sight_height`] give tile by tile, so the searches read an array instead of
//! evaluating the surface; an unbounded world, which has no end to tabulate, evaluates them
//! each time. The same answers either way (tested in `tests/paths.rs`).

use hexx::Hex;

use super::Terrain;
use crate::chunk::TileRect;
use crate::ruleset::Landform;
use crate::vocab::TileKind;

/// Each tile's rules, row by row over a bounded map.
#[derive(Debug)]
pub(crate) struct RuleTable {
    rect: TileRect,
    /// Cost of entering, 0 for a tile that cannot be entered (costs are at most twice
    /// `MAX_MOVE_COST`, so a byte holds them).
    cost: Vec<u8>,
    /// Sight height: 0, 1 (tall) or 2 (mountain).
    sight: Vec<u8>,
    /// Which edges carry a river (bit `d`: toward `all_neighbors()[d]`).
    crossing: Vec<u8>,
    /// The movement model's cost of crossing a river on an edge.
    river: u32,
}

impl RuleTable {
    /// Evaluates every tile of `rect`.
    pub(crate) fn new(terrain: &Terrain, rect: TileRect) -> Self {
        let tiles: Vec<Hex> = rect.iter().map(|oc| terrain.tile_from_offset(oc)).collect();
        let (cost, sight) = tiles
            .iter()
            .map(|&tile| {
                let cost = evaluate_cost(terrain, tile).map_or(0, |c| u8::try_from(c).expect("costs fit a byte"));
                (cost, evaluate_sight(terrain, tile).unwrap_or(0))
            })
            .unzip();
        let crossing = match terrain.pipeline.table() {
            Some(table) => tiles.iter().map(|&t| table.river_edge_mask(terrain.geometry(), t)).collect(),
            None => vec![0; tiles.len()],
        };
        Self { rect, cost, sight, crossing, river: terrain.config().movement.river }
    }

    /// What crossing the edge of the tile at `index` toward its neighbor `d` adds to a step.
    #[inline]
    pub(crate) fn crossing(&self, index: usize, d: usize) -> u32 {
        if self.crossing[index] & (1 << d) != 0 { self.river } else { 0 }
    }

    /// Row-major index of a map tile's offset coordinate.
    #[inline]
    pub(crate) fn index(&self, [c, r]: [i32; 2]) -> Option<usize> {
        self.rect.index([c, r])
    }

    /// Number of tiles.
    pub(crate) fn len(&self) -> usize {
        self.cost.len()
    }

    /// The cost of entering the tile at `index`.
    #[inline]
    pub(crate) fn cost(&self, index: usize) -> Option<u32> {
        let c = self.cost[index];
        (c > 0).then_some(u32::from(c))
    }

    /// The sight height of the tile at `index`.
    #[inline]
    pub(crate) fn sight(&self, index: usize) -> u8 {
        self.sight[index]
    }
}

/// The movement model's cost of entering a tile of the map, from the surface.
/// On a map with its own terrain ruleset, the tile's traits (its terrain's and feature's), on
/// the sea or not.
pub(crate) fn evaluate_cost(terrain: &Terrain, tile: Hex) -> Option<u32> {
    let tile = terrain.wrap_tile(tile)?;
    let info = terrain.tile_info(tile)?;
    let movement = &terrain.config().movement;
    if terrain.has_own_ruleset() {
        let t = terrain.tile_terrain(tile)?;
        let sea = matches!(t.landform, Landform::OpenSea | Landform::Shore);
        return movement.enter_with(t.traits.movement, sea, info.river_flow > 0.0);
    }
    movement.enter(info.biome, info.river_flow > 0.0)
}

/// The sight rule's height of a tile of the map, from the surface: 2 on a mountain, 1 on a tall
/// biome (on a map with its own terrain ruleset, where the tile's traits stand tall).
pub(crate) fn evaluate_sight(terrain: &Terrain, tile: Hex) -> Option<u8> {
    let tile = terrain.wrap_tile(tile)?;
    let info = terrain.tile_info(tile)?;
    Some(if info.kind == TileKind::Mountain && info.lake.is_none() {
        2
    } else if terrain.has_own_ruleset() {
        u8::from(terrain.tile_terrain(tile)?.traits.tall)
    } else {
        u8::from(terrain.config().sight.tall.contains(&info.biome))
    })
}
