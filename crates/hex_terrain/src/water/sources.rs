//! Where the rivers of an edge river network rise Civilization V's way
//! ([`RiverSources::Relief`](crate::RiverSources::Relief)), on the corners' drainage
//! ([`super::descent`]): a river is the way down from its source to the sea or a lake, merging
//! into the rivers it meets.
//!
//! The sources are taken in passes, each over the corners that drain to water, those with the
//! longest way down first (so rivers are long, and the first rivers of a region its main ones):
//! first among hills and mountains at least `sea_distance` tiles from the sea and
//! [`RIVER_SPACING`]`[0]` from every river and lake; then, on each landmass of at least
//! [`RIVER_MIN_LANDMASS`] tiles with fewer river edges than its share (one for every
//! `tiles_per_edge` land tiles, and one more), among its
//! hills and mountains half as far from the sea and [`RIVER_SPACING`]`[1]` from rivers and
//! lakes; then within two tiles of hills or mountains; then anywhere on such a landmass at those
//! distances. Once a landmass has a river, the passes add rivers of at least [`MIN_RIVER_EDGES`]
//! edges to it, so its rivers are not a fringe of short streams. Sources set by hand rise first,
//! wherever they lie. Every step is a pure function of the network, so the choice is the same
//! on every thread.

use std::collections::VecDeque;

use super::descent::NONE;
use crate::config::{RIVER_MIN_LANDMASS, RIVER_SPACING};

/// What the choice reads.
pub(super) struct SourceInput<'a> {
    /// Each corner's downstream corner ([`NONE`] for outlets and unused corners).
    pub down: &'a [u32],
    /// The outlets and the corners that drain, each after the corner it drains into.
    pub order: &'a [u32],
    /// Each corner's map tiles ([`NONE`] past the map).
    pub corner_tiles: &'a [[u32; 3]],
    /// Each map tile's six neighbors (the tile itself past the map).
    pub links: &'a [[u32; 6]],
    /// Whether each map tile is sea.
    pub sea: &'a [bool],
    /// Whether each map tile is a lake tile.
    pub lake: &'a [bool],
    /// Whether each map tile is hills or a mountain.
    pub relief: &'a [bool],
    /// Whether each corner is kept dry by hand.
    pub dry: &'a [bool],
    /// Whether each corner is a source set by hand.
    pub by_hand: &'a [bool],
}

/// The fewest edges of a landmass' rivers after its first.
const MIN_RIVER_EDGES: u32 = 6;

/// How near (in tiles) hills or mountains the third pass looks for sources.
const NEAR_RELIEF: u32 = 2;

/// Which corners' downstream edges carry a river.
pub(super) fn relief_sources(input: &SourceInput<'_>, tiles_per_edge: f32, sea_distance: u32) -> Vec<bool> {
    let n = input.down.len();
    let tiles = input.links.len();
    let wet = |i: u32| input.sea[i as usize] || input.lake[i as usize];
    // How many edges each corner lies from its outlet, and whether that outlet is water (not
    // the map's edge).
    let mut steps = vec![0u32; n];
    let mut to_water = vec![false; n];
    for &c in input.order {
        let c = c as usize;
        match input.down[c] {
            NONE => to_water[c] = input.corner_tiles[c].iter().any(|&i| i != NONE && wet(i)),
            d => {
                steps[c] = steps[d as usize] + 1;
                to_water[c] = to_water[d as usize];
            }
        }
    }
    let (landmass, sizes) = landmasses(input.links, |i| !wet(i as u32));
    let from_sea = distances(input.links, (0..tiles).filter(|&i| input.sea[i]), u32::MAX);
    let reach = RIVER_SPACING[0];
    let mut near_river = distances(input.links, (0..tiles).filter(|&i| input.lake[i]), reach);
    let mut edges = vec![0u32; sizes.len()];
    let mut river = vec![false; n];
    let run = |c: usize, river: &mut Vec<bool>, near_river: &mut Vec<u32>, edges: &mut Vec<u32>| {
        let mut touched = Vec::new();
        let mut at = c;
        while input.down[at] != NONE && !river[at] {
            river[at] = true;
            let ts = input.corner_tiles[at];
            edges[landmass[ts[0] as usize] as usize] += 1;
            touched.extend(ts.iter().filter(|&&i| i != NONE).map(|&i| i as usize));
            at = input.down[at] as usize;
        }
        spread(near_river, input.links, touched, reach);
    };
    for c in (0..n).filter(|&c| input.by_hand[c] && !input.dry[c]) {
        run(c, &mut river, &mut near_river, &mut edges);
    }
    let mut candidates: Vec<usize> =
        (0..n).filter(|&c| input.down[c] != NONE && to_water[c] && !input.dry[c]).collect();
    candidates.sort_by_key(|&c| (std::cmp::Reverse(steps[c]), c));
    let short = sea_distance.div_ceil(2);
    // Each tile's steps from hills or mountains, up to NEAR_RELIEF + 1.
    let from_relief = distances(input.links, (0..tiles).filter(|&i| input.relief[i]), NEAR_RELIEF + 1);
    // (steps from relief at most, the landmass' share, tiles from the sea, tiles from rivers
    // and lakes)
    let passes = [
        (0, false, sea_distance, RIVER_SPACING[0]),
        (0, true, short, RIVER_SPACING[1]),
        (NEAR_RELIEF, true, short, RIVER_SPACING[1]),
        (u32::MAX, true, short, RIVER_SPACING[1]),
    ];
    for (relief, share, sea, spacing) in passes {
        for &c in &candidates {
            let ts = input.corner_tiles[c];
            let land = landmass[ts[0] as usize] as usize;
            // A landmass' rivers after its first (which may be shorter) are at least
            // MIN_RIVER_EDGES long.
            let wanted = (edges[land] == 0 || steps[c] >= MIN_RIVER_EDGES)
                && (!share
                    || (sizes[land] >= RIVER_MIN_LANDMASS
                        && (edges[land] as f32) < sizes[land] as f32 / tiles_per_edge + 1.0));
            let fits = !river[c]
                && wanted
                && (relief == u32::MAX || ts.iter().any(|&i| from_relief[i as usize] <= relief))
                && ts.iter().all(|&i| from_sea[i as usize] >= sea && near_river[i as usize] >= spacing);
            if fits {
                run(c, &mut river, &mut near_river, &mut edges);
            }
        }
    }
    river
}

/// Each tile's landmass (`u32::MAX` off land) and each landmass' tiles, by flood fill over the
/// tiles `on_land` says are land.
fn landmasses(links: &[[u32; 6]], on_land: impl Fn(usize) -> bool) -> (Vec<u32>, Vec<u32>) {
    let mut id = vec![u32::MAX; links.len()];
    let mut sizes = Vec::new();
    let mut stack = Vec::new();
    for start in 0..links.len() {
        if id[start] != u32::MAX || !on_land(start) {
            continue;
        }
        let label = sizes.len() as u32;
        let mut size = 0;
        id[start] = label;
        stack.push(start);
        while let Some(i) = stack.pop() {
            size += 1;
            for &j in &links[i] {
                let j = j as usize;
                if id[j] == u32::MAX && on_land(j) {
                    id[j] = label;
                    stack.push(j);
                }
            }
        }
        sizes.push(size);
    }
    (id, sizes)
}

/// Each tile's steps from the nearest of `from`, counted up to `reach` (`reach` for the tiles
/// farther).
pub(super) fn distances(links: &[[u32; 6]], from: impl Iterator<Item = usize>, reach: u32) -> Vec<u32> {
    let mut d = vec![reach; links.len()];
    spread(&mut d, links, from.collect(), reach);
    d
}

/// Lowers `d` to each tile's steps from the nearest of `from`, where fewer than `reach`.
fn spread(d: &mut [u32], links: &[[u32; 6]], from: Vec<usize>, reach: u32) {
    let mut queue = VecDeque::with_capacity(from.len());
    // A tile already at 0 has spread before.
    for i in from {
        if d[i] > 0 {
            d[i] = 0;
            queue.push_back(i);
        }
    }
    while let Some(i) = queue.pop_front() {
        let next = d[i] + 1;
        if next >= reach {
            continue;
        }
        for &j in &links[i] {
            let j = j as usize;
            if d[j] > next {
                d[j] = next;
                queue.push_back(j);
            }
        }
    }
}
