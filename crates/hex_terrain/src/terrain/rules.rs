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
use crate::vocab::{Biome, TileKind};

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

/// The movement model's cost of entering a tile of the map, from the surface: its terrain's
/// traits ([`TileInfo::terrain`](crate::TileInfo::terrain); under the default ruleset, its
/// biome's cost by the config), embarking on the sea, fording a river.
pub(crate) fn evaluate_cost(terrain: &Terrain, tile: Hex) -> Option<u32> {
    let info = terrain.tile_info(terrain.wrap_tile(tile)?)?;
    let t = info.terrain;
    // Under the default ruleset the sea is its biomes' (a sea biome painted on land embarks).
    let sea = match terrain.has_own_ruleset() {
        true => matches!(t.landform, Landform::OpenSea | Landform::Shore),
        false => matches!(terrain.ruleset().biome(t.terrain), Some(Biome::Ocean | Biome::Coast)),
    };
    terrain.config().movement.enter_with(t.traits.movement, sea, info.river_flow > 0.0)
}

/// The sight rule's height of a tile of the map, from the surface: 2 on a mountain, 1 where its
/// terrain's traits stand tall (under the default ruleset, a tall biome by the config).
pub(crate) fn evaluate_sight(terrain: &Terrain, tile: Hex) -> Option<u8> {
    let info = terrain.tile_info(terrain.wrap_tile(tile)?)?;
    Some(if info.kind == TileKind::Mountain && info.lake.is_none() { 2 } else { u8::from(info.terrain.traits.tall) })
}
