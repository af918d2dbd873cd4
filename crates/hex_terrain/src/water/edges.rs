//! Rivers on the edges between tiles (`rivers.model: Edges`), built with the per-map tile table
//! of a bounded map: the network of corners (the points where three tiles meet) and the edges
//! between them, from the tiles' center heights, kinds, lakes and rain.
//!
//! A corner's height is the mean of its tiles' in the map; a corner touching the sea, a lake or
//! the map's edge is an outlet. A priority flood from the outlets (lowest water level first,
//! ties in the order pushed) gives every other corner a downstream corner, one of its three
//! neighbors, and a water level (its height, or the level of the corner it drains into when
//! that is higher, so a depression fills to its spill height): every path downstream ends at an
//! outlet, never rises in level and never loops. Each land tile's rain goes a sixth to each of
//! its corners and flows downstream, added up in reverse order of the flood. An edge carries a
//! river where the flow of its upstream corner reaches `rivers.threshold`, unless every source
//! of that river rises nearer the sea than `rivers.sea_distance` tiles. A non-outlet corner's
//! tiles are all land in the map, so every river edge lies between two land tiles of the map.

use std::cmp::Ordering;
use std::collections::{BinaryHeap, VecDeque};

use hexx::{EdgeDirection, GridEdge, GridVertex, Hex};
use serde::{Deserialize, Serialize};

use crate::chunk::TileRect;
use crate::config::RiverConfig;
use crate::geometry::Geometry;
use crate::vocab::TileKind;

/// No corner: an outlet's downstream, an empty slot.
const NONE: u32 = u32::MAX;

/// A river edge of a tile.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct RiverEdge {
    /// The edge, from the tile asked about toward the neighbor across the river.
    pub edge: GridEdge,
    /// Water the river carries along it.
    pub flow: f32,
    /// The corner it flows toward, one of the edge's two (as seen from the tile asked about).
    pub downstream: GridVertex,
    /// Water level (normalised height) at the corner it flows from; a river's level never rises
    /// downstream.
    pub level: f32,
}

/// The edge river network of a bounded map.
#[derive(Debug, Clone)]
pub struct EdgeRivers {
    grid: CornerGrid,
    /// Downstream corner of each corner; [`NONE`] for outlets and unused corners.
    down: Vec<u32>,
    /// Water level of each corner.
    level: Vec<f32>,
    /// Water each corner collects from itself and upstream.
    flow: Vec<f32>,
    /// Whether the edge from each corner to its downstream corner carries a river.
    river: Vec<bool>,
    /// The vertex each corner is known by (its owner tile as first met, its direction 0 or 1).
    vertex: Vec<GridVertex>,
    /// Per map tile, row-major: bit `d` set when its edge toward `all_neighbors()[d]` carries a
    /// river.
    edges: Vec<u8>,
}

/// Where corners are kept: two a tile (its vertices 0 and 1), over the map's tiles with a row
/// more above and below and, on a map that does not wrap, a column more either side.
#[derive(Debug, Clone, Copy)]
struct CornerGrid {
    rect: TileRect,
    wraps: bool,
    width: usize,
    height: usize,
}

impl CornerGrid {
    fn new(rect: TileRect, wraps: bool) -> Self {
        let cols = (rect.max[0] - rect.min[0]) as usize;
        let rows = (rect.max[1] - rect.min[1]) as usize;
        Self { rect, wraps, width: if wraps { cols } else { cols + 2 }, height: rows + 2 }
    }

    fn len(&self) -> usize {
        self.width * self.height * 2
    }

    /// The index of a vertex's corner (any of its three names, any copy on a wrapping map);
    /// `None` for a corner of no tile of the map.
    fn get(&self, geometry: &Geometry, v: GridVertex) -> Option<usize> {
        let c = canonical(v);
        let owner = if self.wraps { geometry.wrap_tile(c.origin) } else { c.origin };
        let [col, row] = geometry.offset_of(owner);
        let col = usize::try_from(col - self.rect.min[0] + i32::from(!self.wraps)).ok()?;
        let row = usize::try_from(row - self.rect.min[1] + 1).ok()?;
        (col < self.width && row < self.height).then(|| (row * self.width + col) * 2 + usize::from(c.direction.index()))
    }

    /// The index of a corner of a tile of the map.
    fn index(&self, geometry: &Geometry, v: GridVertex) -> usize {
        self.get(geometry, v).expect("a corner of a tile of the map")
    }
}

/// A corner's name whose direction is 0 or 1: each corner has three names (one from each of
/// its tiles, their directions two apart), and exactly one of them has it.
fn canonical(v: GridVertex) -> GridVertex {
    let d = v.direction;
    [
        v,
        GridVertex { origin: v.origin + d.direction_cw(), direction: d.rotate_ccw(2) },
        GridVertex { origin: v.origin + d.direction_ccw(), direction: d.rotate_cw(2) },
    ]
    .into_iter()
    .find(|n| n.direction.index() < 2)
    .expect("one of a corner's three names has direction 0 or 1")
}

/// The three edges meeting at a corner, each named from one of its tiles, and the corner at
/// its other end.
fn links(v: GridVertex) -> [(GridEdge, GridVertex); 3] {
    let d = v.direction;
    let [a, b] = v.side_edges();
    // The third edge lies between the corner's two other tiles.
    let other = v.origin + d.direction_cw();
    let toward = v.origin + d.direction_ccw();
    let third_dir = EdgeDirection::ALL_DIRECTIONS
        .into_iter()
        .find(|&e| other + e == toward)
        .expect("a corner's other two tiles are neighbors");
    let third = GridEdge { origin: other, direction: third_dir };
    [a, b, third].map(|edge| {
        let [p, q] = edge.vertices();
        (edge, if p.equivalent(&v) { q } else { p })
    })
}

/// Heap entry: lowest level first, then first pushed.
#[derive(PartialEq)]
struct Entry(f32, u32, u32);

impl Eq for Entry {}

impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}

impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// What the network is built from: the map's tiles, row by row.
pub(crate) struct EdgeInput<'a> {
    /// The map's tiles.
    pub rect: TileRect,
    /// Each tile's center height, raw.
    pub raw: &'a [f32],
    /// Each tile's kind.
    pub kinds: &'a [TileKind],
    /// Whether each tile is a lake tile.
    pub lakes: &'a [bool],
    /// Each tile's rain.
    pub rain: &'a [f32],
}

impl EdgeRivers {
    /// Builds the network; `index` gives a tile's row-major index in the map (any copy of it on
    /// a wrapping map), `None` past the map's edge.
    pub(crate) fn build(
        config: &RiverConfig,
        geometry: &Geometry,
        input: &EdgeInput<'_>,
        index: impl Fn(Hex) -> Option<usize>,
    ) -> Self {
        let rect = input.rect;
        let grid = CornerGrid::new(rect, geometry.wrap().is_some());
        let n = grid.len();
        let tiles: Vec<Hex> = rect.iter().map(|oc| geometry.tile_from_offset(oc)).collect();
        // Every corner of a map tile, by the name its first tile gives it.
        let mut vertex = vec![Hex::ZERO.all_vertices()[0]; n];
        let mut used = vec![false; n];
        for &t in &tiles {
            for v in t.all_vertices() {
                let c = grid.index(geometry, v);
                if !used[c] {
                    used[c] = true;
                    vertex[c] = canonical(v);
                }
            }
        }
        let mut height = vec![0.0_f32; n];
        let mut outlet = vec![false; n];
        for c in (0..n).filter(|&c| used[c]) {
            let (mut sum, mut count) = (0.0, 0.0);
            for t in vertex[c].coordinates() {
                match index(t) {
                    Some(i) => {
                        sum += input.raw[i];
                        count += 1.0;
                        outlet[c] |= input.kinds[i] == TileKind::Sea || input.lakes[i];
                    }
                    None => outlet[c] = true,
                }
            }
            height[c] = sum / count;
        }
        // Priority flood from the outlets.
        let mut level = height.clone();
        let mut down = vec![NONE; n];
        let mut taken = outlet.clone();
        let mut heap = BinaryHeap::new();
        let mut seq = 0_u32;
        for c in (0..n).filter(|&c| used[c] && outlet[c]) {
            heap.push(Entry(level[c], seq, c as u32));
            seq += 1;
        }
        let mut order = Vec::with_capacity(n);
        while let Some(Entry(l, _, c)) = heap.pop() {
            let c = c as usize;
            order.push(c);
            for (_, next) in links(vertex[c]) {
                let Some(j) = grid.get(geometry, next) else { continue };
                if used[j] && !taken[j] {
                    taken[j] = true;
                    level[j] = level[j].max(l);
                    down[j] = c as u32;
                    heap.push(Entry(level[j], seq, j as u32));
                    seq += 1;
                }
            }
        }
        // Rain: a sixth of each land tile's to each of its corners, then downstream.
        let mut flow = vec![0.0_f32; n];
        for (i, &t) in tiles.iter().enumerate() {
            if input.kinds[i] != TileKind::Sea && !input.lakes[i] {
                for v in t.all_vertices() {
                    flow[grid.index(geometry, v)] += input.rain[i] / 6.0;
                }
            }
        }
        for &c in order.iter().rev() {
            if down[c] != NONE {
                flow[down[c] as usize] += flow[c];
            }
        }
        let river = Self::rivers(config, geometry, input, &index, (&vertex, &down, &flow, &order));
        let mut network = Self { grid, down, level, flow, river, vertex, edges: vec![0; tiles.len()] };
        for c in 0..n {
            if network.river[c] {
                let edge = network.edge_down(geometry, c).expect("a river corner drains");
                for (from, to) in [(edge.origin, edge.destination()), (edge.destination(), edge.origin)] {
                    let d = from.all_neighbors().iter().position(|&nb| nb == to).expect("an edge joins neighbors");
                    let i = index(from).expect("a river edge lies between tiles of the map");
                    network.edges[i] |= 1 << d;
                }
            }
        }
        network
    }

    /// Which corners' downstream edges carry a river: those whose flow reaches the threshold,
    /// downstream of a source (a river corner no river flows into) at least `sea_distance`
    /// tiles from the sea.
    fn rivers(
        config: &RiverConfig,
        geometry: &Geometry,
        input: &EdgeInput<'_>,
        index: &impl Fn(Hex) -> Option<usize>,
        (vertex, down, flow, order): (&[GridVertex], &[u32], &[f32], &[usize]),
    ) -> Vec<bool> {
        let n = down.len();
        let wet: Vec<bool> = (0..n).map(|c| down[c] != NONE && flow[c] >= config.threshold).collect();
        let mut fed = vec![false; n];
        for c in 0..n {
            if wet[c] {
                fed[down[c] as usize] = true;
            }
        }
        let far = sea_distances(geometry, input, index);
        let mut keep = vec![false; n];
        for &c in order.iter().rev() {
            if !wet[c] {
                continue;
            }
            if !fed[c] {
                let nearest = vertex[c].coordinates().iter().filter_map(|&t| index(t)).map(|i| far[i]).min();
                keep[c] = nearest.is_some_and(|d| d >= config.sea_distance);
            }
            let next = down[c] as usize;
            if keep[c] && wet[next] {
                keep[next] = true;
            }
        }
        keep
    }

    /// The edge from corner `c` to its downstream corner, named from one of its tiles.
    fn edge_down(&self, geometry: &Geometry, c: usize) -> Option<GridEdge> {
        let next = self.down[c];
        (next != NONE).then(|| {
            links(self.vertex[c])
                .into_iter()
                .find(|&(_, v)| self.grid.get(geometry, v) == Some(next as usize))
                .map(|(edge, _)| edge)
                .expect("the downstream corner is a neighbor")
        })
    }

    /// The river edges of map tile `i`, a bit for each neighbor direction.
    #[must_use]
    #[inline]
    pub(crate) fn edges_of(&self, i: usize) -> u8 {
        self.edges[i]
    }

    /// The river edges of `tile` (map tile `i`), from its side.
    pub(crate) fn river_edges(&self, geometry: &Geometry, tile: Hex, i: usize) -> Vec<RiverEdge> {
        let mask = self.edges[i];
        EdgeDirection::ALL_DIRECTIONS
            .into_iter()
            .enumerate()
            .filter(|&(d, _)| mask & (1 << d) != 0)
            .map(|(_, direction)| {
                let edge = GridEdge { origin: tile, direction };
                let [p, q] = edge.vertices();
                let (a, b) = (self.grid.index(geometry, p), self.grid.index(geometry, q));
                // The river runs from one end to the other: the end whose downstream is the other.
                let (from, to) = if self.down[a] == b as u32 && self.river[a] { (a, q) } else { (b, p) };
                RiverEdge { edge, flow: self.flow[from], downstream: to, level: self.level[from] }
            })
            .collect()
    }

    /// The river's course from `edge` (a river edge) down to where it ends: each edge, named
    /// from a tile beside it, in order.
    pub(crate) fn course(&self, geometry: &Geometry, edge: GridEdge) -> Vec<GridEdge> {
        let [p, q] = edge.vertices();
        let (a, b) = (self.grid.index(geometry, p), self.grid.index(geometry, q));
        let mut at = if self.river[a] && self.down[a] == b as u32 {
            a
        } else if self.river[b] && self.down[b] == a as u32 {
            b
        } else {
            return Vec::new();
        };
        let mut out = Vec::new();
        while self.river[at] {
            out.push(self.edge_down(geometry, at).expect("a river corner drains"));
            at = self.down[at] as usize;
        }
        out
    }

    /// Whether map tile `i` has the same river edges in `self` and `other`.
    #[must_use]
    pub(crate) fn same_tile(&self, other: &Self, i: usize) -> bool {
        self.edges[i] == other.edges[i]
    }
}

/// Each map tile's distance in tiles to the nearest sea tile (a breadth-first search from every
/// sea tile at once); `u32::MAX` on a map without sea.
fn sea_distances(geometry: &Geometry, input: &EdgeInput<'_>, index: &impl Fn(Hex) -> Option<usize>) -> Vec<u32> {
    let tiles: Vec<Hex> = input.rect.iter().map(|oc| geometry.tile_from_offset(oc)).collect();
    let mut far = vec![u32::MAX; tiles.len()];
    let mut queue = VecDeque::new();
    for (i, &kind) in input.kinds.iter().enumerate() {
        if kind == TileKind::Sea {
            far[i] = 0;
            queue.push_back(i);
        }
    }
    while let Some(i) = queue.pop_front() {
        for nb in tiles[i].all_neighbors() {
            if let Some(j) = index(nb)
                && far[j] == u32::MAX
            {
                far[j] = far[i] + 1;
                queue.push_back(j);
            }
        }
    }
    far
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A corner's three names give one corner, its links are three other corners, and each
    /// link's edge has the corner at one end.
    #[test]
    fn corners_have_one_name_and_three_links() {
        for t in [Hex::ZERO, Hex::new(3, -5), Hex::new(-7, 2)] {
            for v in t.all_vertices() {
                let c = canonical(v);
                assert!(c.equivalent(&v) && c.direction.index() < 2);
                let names = [
                    v,
                    GridVertex { origin: v.origin + v.direction.direction_cw(), direction: v.direction.rotate_ccw(2) },
                    GridVertex { origin: v.origin + v.direction.direction_ccw(), direction: v.direction.rotate_cw(2) },
                ];
                for name in names {
                    assert_eq!(canonical(name), c, "{v:?} as {name:?}");
                }
                let ends: Vec<GridVertex> = links(v).into_iter().map(|(_, end)| canonical(end)).collect();
                assert_eq!(ends.len(), 3);
                assert!(ends[0] != ends[1] && ends[1] != ends[2] && ends[0] != ends[2], "{ends:?}");
                for (edge, end) in links(v) {
                    let [p, q] = edge.vertices();
                    assert!((p.equivalent(&v) && q == end) || (q.equivalent(&v) && p == end), "{edge:?}");
                }
            }
        }
        // `all_neighbors` runs in the edge directions' order.
        for (d, nb) in Hex::ZERO.all_neighbors().into_iter().enumerate() {
            assert_eq!(Hex::ZERO + EdgeDirection::ALL_DIRECTIONS[d], nb);
        }
    }
}
