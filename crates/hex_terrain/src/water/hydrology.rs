//! The water network, built with the per-map tile table: rivers and lakes of a bounded map,
//! at the tile level, from the tiles' center heights.
//!
//! Priority-flood (Barnes, Lehman and Mulla, 2014): the sea and the map's edge tiles are the
//! outlets; tiles are taken lowest water level first, and each tile reached from one already
//! taken gets the water level `max(own height, that tile's level)` and drains into it. That
//! fills every depression up to its spill height and gives every tile one downstream
//! neighbor with a level at or below its own, on a path that ends at an outlet: no cycles, never
//! uphill. A tile whose level lies above its center by more than the minimum depth is a lake
//! tile (water above sea level). Each land or mountain tile collects its rain (its moisture, more on
//! higher ground, so rivers rise on high, wet tiles), adds it
//! to its downstream neighbor's, in reverse order of the flood; a tile whose flow reaches the
//! threshold carries a river, which ends in the sea, a lake or at the map edge. Rivers merge
//! where they meet and their flow grows downstream.
//!
//! Rivers run through tile centers (as in Endless Legend and Catlike Coding's Hex Map): a river
//! tile's channel runs from its center to the middle of each edge it crosses, upstream and
//! downstream, so a river is read as a tile property (a unit stands on it) and the channel uses
//! the lattice's own points from center to edge.

use hexx::Hex;
use serde::{Deserialize, Serialize};

use super::corners::{CornerGrid, Stencils};
use super::descent::{Drainage, LevelQueue, NONE, Role, drain};
use crate::chunk::TileRect;
use crate::config::{RiverConfig, RiverEdit};
use crate::geometry::Geometry;
use crate::vocab::TileKind;

/// The channels of a tile without a river.
const NO_CHANNELS: [f32; 6] = [0.0; 6];

/// No downstream tile: the tile is sea (an outlet).
const OUTLET: u8 = 6;

/// The water network of a bounded map, row by row over its tiles.
#[derive(Debug, Clone)]
pub struct Hydrology {
    /// Water level (normalised height of the filled surface) of each tile.
    level: Vec<f32>,
    /// Direction (index into `Hex::all_neighbors`) of the downstream tile; for an edge tile
    /// draining off the map, the direction of a neighbor outside it; [`OUTLET`] for sea.
    down: Vec<u8>,
    /// Water collected by each tile from itself and upstream.
    flow: Vec<f32>,
    /// Lake id + 1 of each tile, 0 when not a lake.
    lake: Vec<u32>,
    /// Spill height of each lake.
    spill: Vec<f32>,
    /// Channel half-width in lattice steps towards each of the six neighbors (0: no channel);
    /// empty when no tile carries a river.
    channels: Vec<[f32; 6]>,
    threshold: f32,
}

/// A river on one tile.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct RiverTile {
    /// The tile.
    pub hex: Hex,
    /// Water it carries (rain collected from itself and upstream).
    pub flow: f32,
    /// Water surface level (normalised height); never rises downstream.
    pub level: f32,
    /// Where it flows: the next tile (a river, lake or sea tile), or `None` off the map's edge.
    pub downstream: Option<Hex>,
    /// The neighbors whose river flows into it.
    pub upstream: Vec<Hex>,
}

/// Each map tile's six neighbors (row-major indices, in `Hex::all_neighbors` order; the tile
/// itself past the map's edge) of the map's rectangle `rect`: what the tiles' floods read.
pub(crate) fn tile_links(geometry: &Geometry, rect: TileRect) -> Vec<[u32; 6]> {
    let grid = CornerGrid::new(rect, geometry.wrap().is_some());
    let stencils = Stencils::new(geometry);
    (0..rect.len())
        .map(|i| {
            let [c, r] = grid.tile_offset(i);
            stencils.neighbors([c, r]).map(|[dc, dr]| grid.tile([c + dc, r + dr]).map_or(i as u32, |j| j as u32))
        })
        .collect()
}

impl Hydrology {
    /// Builds the network of a map's tiles (indices `0..raw.len()`) from their center heights
    /// `raw`, their kinds, each tile's rain, the rivers set by hand (`rivers[i]`; an empty slice
    /// when none is), and `neighbor(i, d)`: the tile in direction `d` (`Hex::all_neighbors`
    /// order) of tile `i`, `None` off the map.
    ///
    /// A source set by hand on a land tile collects at least the threshold as rain, so a river
    /// rises there and runs down like any other; a dry tile and every tile draining through it
    /// collect nothing.
    pub(crate) fn build(
        config: &RiverConfig,
        raw: &[f32],
        kinds: &[TileKind],
        rain: &[f32],
        rivers: &[Option<RiverEdit>],
        neighbor: impl Fn(usize, usize) -> Option<usize>,
    ) -> Self {
        let neighbor = &neighbor;
        let count = raw.len();
        let mut level = raw.to_vec();
        let mut down = vec![OUTLET; count];
        let mut taken = vec![false; count];
        // Lowest level first, then first pushed: the queue's ties go by the order pushed, and
        // `pushed` names the tile of each push.
        let (low, high) = raw.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &l| (lo.min(l), hi.max(l)));
        let mut queue = LevelQueue::new(count / 4, low, high.max(low));
        let mut pushed: Vec<u32> = Vec::with_capacity(count);
        for i in 0..count {
            let off_map = (0..6).find(|&d| neighbor(i, d).is_none());
            if kinds[i] == TileKind::Sea || off_map.is_some() {
                if kinds[i] != TileKind::Sea {
                    down[i] = off_map.unwrap_or(0) as u8;
                }
                taken[i] = true;
                queue.push(level[i], pushed.len() as u32);
                pushed.push(i as u32);
            }
        }
        let mut order = Vec::with_capacity(count);
        while let Some(k) = queue.pop() {
            let i = pushed[k as usize] as usize;
            let l = level[i];
            order.push(i);
            for d in 0..6 {
                if let Some(j) = neighbor(i, d)
                    && !taken[j]
                {
                    taken[j] = true;
                    level[j] = level[j].max(l);
                    down[j] = ((d + 3) % 6) as u8;
                    queue.push(level[j], pushed.len() as u32);
                    pushed.push(j as u32);
                }
            }
        }
        let downstream =
            |i: usize, down: &[u8]| (down[i] < OUTLET).then(|| neighbor(i, usize::from(down[i]))).flatten();
        let mut flow: Vec<f32> = rain.to_vec();
        if !rivers.is_empty() {
            // Downstream first: a tile is dry when it or the tile it drains into is.
            let mut dry = vec![false; count];
            for &i in &order {
                dry[i] = rivers[i] == Some(RiverEdit::Dry) || downstream(i, &down).is_some_and(|j| dry[j]);
                if dry[i] {
                    flow[i] = 0.0;
                } else if rivers[i] == Some(RiverEdit::Source) && kinds[i] != TileKind::Sea {
                    flow[i] = flow[i].max(config.threshold);
                }
            }
        }
        for &i in order.iter().rev() {
            if let Some(j) = downstream(i, &down) {
                flow[j] += flow[i];
            }
        }
        let (lake, spill) = Self::lakes(config.lakes, config.min_lake_depth, raw, &level, kinds, &order, |i| {
            (0..6).filter_map(move |d| neighbor(i, d))
        });
        let mut hydrology = Self { level, down, flow, lake, spill, channels: Vec::new(), threshold: config.threshold };
        let width = |flow: f32| config.width * (flow / config.threshold).sqrt().clamp(1.0, 2.0);
        for i in 0..count {
            if !hydrology.river_at(i) {
                continue;
            }
            if hydrology.channels.is_empty() {
                hydrology.channels = vec![NO_CHANNELS; count];
            }
            let d = usize::from(hydrology.down[i]);
            hydrology.channels[i][d] = width(hydrology.flow[i]);
            if let Some(j) = downstream(i, &hydrology.down)
                && hydrology.river_at(j)
            {
                hydrology.channels[j][(d + 3) % 6] = width(hydrology.flow[i]);
            }
        }
        hydrology
    }

    /// The network of a map whose rivers run on the tiles' edges: its water levels and lakes,
    /// no tile carrying a river. A tile drains down the steepest slope, and out of a depression
    /// by a flood from the tiles round it ([`super::descent`], as the edge network's corners do);
    /// the water levels are the filled heights, which do not depend on the order tiles are taken
    /// in, so the lakes are the tiles and spill heights [`Hydrology::build`] finds, at a fraction
    /// of its cost (lake ids count the lakes in this order instead).
    pub(crate) fn lakes_only(
        config: &RiverConfig,
        links: &[[u32; 6]],
        (raw, kinds, rain): (&[f32], &[TileKind], &[f32]),
    ) -> Self {
        let count = raw.len();
        // The sea and the map's edge tiles are the outlets, as in `build`.
        let roles: Vec<Role> =
            (0..count)
                .map(|i| {
                    if kinds[i] == TileKind::Sea || links[i].contains(&(i as u32)) {
                        Role::Outlet
                    } else {
                        Role::Drains
                    }
                })
                .collect();
        let mut level = raw.to_vec();
        let Drainage { down: to, order } = drain(&roles, &mut level, links);
        let down: Vec<u8> = (0..count)
            .map(|i| {
                let toward = |t: u32| links[i].iter().position(|&j| j == t).map_or(OUTLET, |d| d as u8);
                match (kinds[i], to[i]) {
                    (TileKind::Sea, _) => OUTLET,
                    // A land tile on the map's edge drains off it, toward its first missing neighbor.
                    (_, NONE) => toward(i as u32),
                    (_, t) => toward(t),
                }
            })
            .collect();
        let mut flow = rain.to_vec();
        for &i in order.iter().rev() {
            if let Some(&t) = to.get(i as usize).filter(|&&t| t != NONE) {
                flow[t as usize] += flow[i as usize];
            }
        }
        let order: Vec<usize> = order.iter().map(|&i| i as usize).collect();
        let (lake, spill) = Self::lakes(config.lakes, config.min_lake_depth, raw, &level, kinds, &order, |i| {
            links[i].into_iter().filter(move |&j| j as usize != i).map(|j| j as usize)
        });
        Self { level, down, flow, lake, spill, channels: Vec::new(), threshold: f32::INFINITY }
    }

    /// Lake ids (connected tiles filled above their center by more than `min_depth`) and each
    /// lake's spill height; adjacent filled tiles always share one level.
    fn lakes<I: Iterator<Item = usize>>(
        enabled: bool,
        min_depth: f32,
        raw: &[f32],
        level: &[f32],
        kinds: &[TileKind],
        order: &[usize],
        neighbors: impl Fn(usize) -> I,
    ) -> (Vec<u32>, Vec<f32>) {
        let mut lake = vec![0_u32; raw.len()];
        let mut spill = Vec::new();
        if !enabled {
            return (lake, spill);
        }
        let filled = |i: usize| kinds[i] != TileKind::Sea && level[i] - raw[i] > min_depth;
        for &start in order {
            if lake[start] != 0 || !filled(start) {
                continue;
            }
            spill.push(level[start]);
            let id = spill.len() as u32;
            let mut stack = vec![start];
            lake[start] = id;
            while let Some(i) = stack.pop() {
                for j in neighbors(i) {
                    if lake[j] == 0 && filled(j) && level[j] == level[start] {
                        lake[j] = id;
                        stack.push(j);
                    }
                }
            }
        }
        (lake, spill)
    }

    /// Whether tile `i` carries the same water in `self` and `other` (level, flow, where it
    /// drains, lake or not, channels); lake ids are not compared (they count lakes in flood
    /// order, so a new lake renumbers the lakes after it without changing them).
    pub(crate) fn same_tile(&self, other: &Self, i: usize) -> bool {
        self.level[i].to_bits() == other.level[i].to_bits()
            && self.flow[i].to_bits() == other.flow[i].to_bits()
            && self.down[i] == other.down[i]
            && (self.lake[i] == 0) == (other.lake[i] == 0)
            && self.channels(i).map(f32::to_bits) == other.channels(i).map(f32::to_bits)
    }

    /// Lake id of tile `i` (row-major index in the map), if it is a lake tile.
    pub(crate) fn lake_of(&self, i: usize) -> Option<u32> {
        self.lake[i].checked_sub(1)
    }

    /// Spill height (normalised) of a lake.
    #[must_use]
    pub fn spill_height(&self, lake: u32) -> Option<f32> {
        self.spill.get(lake as usize).copied()
    }

    /// Number of lakes.
    #[must_use]
    pub fn lake_count(&self) -> usize {
        self.spill.len()
    }

    /// Channel half-widths of tile `i` towards its six neighbors (0: none).
    #[inline]
    pub(crate) fn channels(&self, i: usize) -> &[f32; 6] {
        self.channels.get(i).unwrap_or(&NO_CHANNELS)
    }

    /// Water level of tile `i`.
    pub(crate) fn level(&self, i: usize) -> f32 {
        self.level[i]
    }

    /// Flow of tile `i`.
    pub(crate) fn flow(&self, i: usize) -> f32 {
        self.flow[i]
    }

    /// Whether tile `i` carries a river (the flow threshold reached, not sea, not lake).
    pub(crate) fn river_at(&self, i: usize) -> bool {
        self.flow[i] >= self.threshold && self.lake[i] == 0 && self.down[i] < OUTLET
    }

    /// Downstream direction of tile `i` (`None` for sea).
    pub(crate) fn down(&self, i: usize) -> Option<usize> {
        (self.down[i] < OUTLET).then_some(usize::from(self.down[i]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On random heights over maps of both layouts, wrapping or not (a third of them with only a
    /// few distinct heights, so flats and ties abound), the lakes-only network has the water
    /// levels of `build`'s flood bit for bit, the same lake tiles grouped into the same lakes
    /// with the same spill heights, and every tile draining toward a neighbor no higher.
    #[test]
    fn lakes_only_finds_the_lakes_and_levels_of_the_full_flood() {
        let mut seed = 2024_u64;
        let mut next = move || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 33) as u32
        };
        for round in 0..120 {
            let (x, z) = (4 + next() % 30, 1 + next() % 24);
            let wrap = next() % 2 == 0;
            let mut config =
                crate::MapConfig { size: crate::MapSize::Bounded { x: x + x % 2, z }, wrap, ..Default::default() };
            config.layout.orientation =
                if next() % 2 == 0 { crate::Orientation::Pointy } else { crate::Orientation::Flat };
            config.rivers.min_lake_depth = [0.0, 0.01][round % 2];
            let geometry = Geometry::new(&config);
            let rect = geometry.bounds().unwrap();
            let tiles: Vec<hexx::Hex> = rect.iter().map(|oc| geometry.tile_from_offset(oc)).collect();
            let levels = if round % 3 == 0 { 4 } else { 1000 };
            let raw: Vec<f32> = tiles.iter().map(|_| (next() % levels) as f32 / levels as f32).collect();
            let kinds: Vec<TileKind> = raw
                .iter()
                .map(|&h| {
                    if h < 0.3 {
                        TileKind::Sea
                    } else if h > 0.8 {
                        TileKind::Mountain
                    } else {
                        TileKind::Land
                    }
                })
                .collect();
            let rain: Vec<f32> = tiles.iter().map(|_| (next() % 100) as f32 / 50.0).collect();
            let index = |t: hexx::Hex| {
                let [c, r] = geometry.offset_of(geometry.wrap_tile(t));
                rect.contains([c, r])
                    .then(|| ((r - rect.min[1]) * (rect.max[0] - rect.min[0]) + c - rect.min[0]) as usize)
            };
            let neighbor = |i: usize, d: usize| index(tiles[i].all_neighbors()[d]);
            let lakes_config = RiverConfig { threshold: f32::INFINITY, ..config.rivers.clone() };
            let full = Hydrology::build(&lakes_config, &raw, &kinds, &rain, &[], neighbor);
            let links = tile_links(&geometry, rect);
            for (i, l) in links.iter().enumerate() {
                for (d, &j) in l.iter().enumerate() {
                    let by_link = (j as usize != i).then_some(j as usize);
                    assert_eq!(by_link, neighbor(i, d), "round {round}: tile {i}'s link {d}");
                }
            }
            let fast = Hydrology::lakes_only(&config.rivers, &links, (&raw, &kinds, &rain));
            let mut pairs = std::collections::HashMap::new();
            for i in 0..tiles.len() {
                assert_eq!(fast.level(i).to_bits(), full.level(i).to_bits(), "round {round}: tile {i}'s level");
                match (full.lake_of(i), fast.lake_of(i)) {
                    (None, None) => {}
                    (Some(a), Some(b)) => {
                        assert_eq!(*pairs.entry(a).or_insert(b), b, "round {round}: lake {a} split");
                        assert_eq!(full.spill_height(a), fast.spill_height(b), "round {round}: lake {a}'s spill");
                    }
                    other => panic!("round {round}: tile {i} is a lake in one network only: {other:?}"),
                }
                if let Some(d) = fast.down(i)
                    && let Some(j) = neighbor(i, d)
                {
                    assert!(fast.level(j) <= fast.level(i), "round {round}: tile {i} drains uphill");
                }
                assert!(!fast.river_at(i));
            }
            assert_eq!(full.lake_count(), fast.lake_count(), "round {round}");
        }
    }
}
