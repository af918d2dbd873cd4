//! Rivers on the edges between tiles (`rivers.model: Edges`), built with the per-map tile table
//! of a bounded map: the network of corners (the points where three tiles meet) and the edges
//! between them, from the tiles' center heights, kinds, lakes and rain.
//!
//! A corner's height is the mean of its tiles' in the map; a corner touching the sea, a lake or
//! the map's edge is an outlet. A priority flood from the outlets (lowest water level first,
//! ties in the order pushed, a corner filling a depression right after the corner it is reached
//! from) gives every other corner a downstream corner, one of its three
//! neighbors, and a water level (its height, or the level of the corner it drains into when
//! that is higher, so a depression fills to its spill height): every path downstream ends at an
//! outlet, never rises in level and never loops. Each land tile's rain goes a sixth to each of
//! its corners and flows downstream, added up in reverse order of the flood. An edge carries a
//! river where the flow of its upstream corner reaches `rivers.threshold`, unless every source
//! of that river rises nearer the sea than `rivers.sea_distance` tiles. A river set by hand
//! ([`RiverEdit`]) rises at its tile's lowest corner that drains (`Source`, wherever it lies),
//! or keeps every corner of its tile, and all that drains through them, dry (`Dry`). A non-outlet corner's
//! tiles are all land in the map, so every river edge lies between two land tiles of the map.

use std::collections::VecDeque;

use hexx::{EdgeDirection, GridEdge, GridVertex, Hex};
use serde::{Deserialize, Serialize};

use super::corners::{CornerGrid, Owners, RadixHeap, Shape, key};
use crate::chunk::TileRect;
use crate::config::{RiverConfig, RiverEdit};
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
    /// The map's tiles, row by row.
    tiles: Vec<Hex>,
    /// Each map tile's six corners, in hexx's vertex direction order.
    corners: Vec<[u32; 6]>,
    /// The vertex directions at the ends of each edge direction.
    ends: [(usize, usize); 6],
    /// Each corner's neighbors: the corner across each edge meeting there, with the edge as a
    /// map tile beside it and its direction from that tile ([`NONE`] past the map).
    links: Vec<[Link; 3]>,
    /// Downstream corner of each corner; [`NONE`] for outlets and unused corners.
    down: Vec<u32>,
    /// Water level of each corner.
    level: Vec<f32>,
    /// Water each corner collects from itself and upstream.
    flow: Vec<f32>,
    /// Whether the edge from each corner to its downstream corner carries a river.
    river: Vec<bool>,
    /// Per map tile, row-major: bit `d` set when its edge toward `all_neighbors()[d]` carries a
    /// river.
    edges: Vec<u8>,
    /// Per map tile, the channel's half-width in lattice steps along each of its six edges (0:
    /// no river there); the two tiles of an edge give it the same.
    widths: Vec<[f32; 6]>,
}

/// An edge from a corner: the corner at its other end, a map tile beside it and the edge's
/// direction from that tile.
#[derive(Debug, Clone, Copy)]
struct Link {
    to: u32,
    tile: u32,
    direction: u8,
}

const NO_LINK: Link = Link { to: NONE, tile: NONE, direction: 0 };

/// What the network is built from: the map's tiles, row by row.
pub(crate) struct EdgeInput<'a> {
    /// The map's tiles: their rectangle, and each tile row by row.
    pub rect: TileRect,
    pub tiles: &'a [Hex],
    /// Each tile's center height, raw.
    pub raw: &'a [f32],
    /// Each tile's kind.
    pub kinds: &'a [TileKind],
    /// Whether each tile is a lake tile.
    pub lakes: &'a [bool],
    /// Each tile's rain.
    pub rain: &'a [f32],
    /// Each tile's river set by hand (empty when no tile has one).
    pub by_hand: &'a [Option<RiverEdit>],
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
        let shape = Shape::new();
        let owners = Owners::new(geometry, &shape);
        let n = grid.len();
        let tiles = input.tiles.to_vec();
        let corners: Vec<[u32; 6]> = rect.iter().map(|oc| grid.tile_corners(&shape, &owners, oc)).collect();
        // Each corner's height (its map tiles' mean), whether it is an outlet (beside water or
        // the map's edge: fewer than three map tiles), and its links, from every tile's ring.
        let (mut sum, mut count) = (vec![0.0_f32; n], vec![0_u8; n]);
        let mut outlet = vec![false; n];
        let mut links = vec![[NO_LINK; 3]; n];
        let mut link = |from: u32, to: u32, tile: usize, direction: usize| {
            let slots = &mut links[from as usize];
            if slots.iter().any(|l| l.to == to) {
                return;
            }
            let free = slots.iter_mut().find(|l| l.to == NONE).expect("a corner has three edges");
            *free = Link { to, tile: tile as u32, direction: direction as u8 };
        };
        for (i, ring) in corners.iter().enumerate() {
            let water = input.kinds[i] == TileKind::Sea || input.lakes[i];
            for &c in ring {
                sum[c as usize] += input.raw[i];
                count[c as usize] += 1;
                outlet[c as usize] |= water;
            }
            for (d, &(a, b)) in shape.ends.iter().enumerate() {
                link(ring[a], ring[b], i, d);
                link(ring[b], ring[a], i, d);
            }
        }
        let used: Vec<bool> = count.iter().map(|&c| c > 0).collect();
        let mut level: Vec<f32> = (0..n).map(|c| if used[c] { sum[c] / f32::from(count[c]) } else { 0.0 }).collect();
        for c in 0..n {
            outlet[c] |= used[c] && count[c] < 3;
        }
        // Priority flood from the outlets.
        let mut down = vec![NONE; n];
        let mut taken = outlet.clone();
        let mut heap = RadixHeap::new();
        let mut seq = 0_u32;
        // Only the outlets beside a corner that drains matter (the open sea's corners do not).
        let shore = |c: usize| links[c].iter().take_while(|l| l.to != NONE).any(|l| !outlet[l.to as usize]);
        for c in (0..n).filter(|&c| used[c] && outlet[c] && shore(c)) {
            heap.push(key(level[c], seq), c as u32);
            seq += 1;
        }
        // A corner no higher than the level it is reached at fills to that level: it is taken
        // next, from a queue, before any corner the heap holds (Barnes, Lehman and Mulla's
        // Priority-Flood+FIFO), which gives the same levels with fewer heap operations.
        let mut order = Vec::with_capacity(n);
        let mut pit = VecDeque::new();
        loop {
            let (l, c) = match pit.pop_front() {
                Some(c) => (level[c as usize], c),
                None => match heap.pop() {
                    Some(c) => (level[c as usize], c),
                    None => break,
                },
            };
            order.push(c as usize);
            for next in links[c as usize].iter().take_while(|l| l.to != NONE) {
                let j = next.to as usize;
                if !taken[j] {
                    taken[j] = true;
                    down[j] = c;
                    if level[j] <= l {
                        level[j] = l;
                        pit.push_back(j as u32);
                    } else {
                        heap.push(key(level[j], seq), j as u32);
                        seq += 1;
                    }
                }
            }
        }
        // Rain: a sixth of each land tile's to each of its corners, then downstream.
        let mut flow = vec![0.0_f32; n];
        for (i, ring) in corners.iter().enumerate() {
            if input.kinds[i] != TileKind::Sea && !input.lakes[i] {
                for &c in ring {
                    flow[c as usize] += input.rain[i] / 6.0;
                }
            }
        }
        // Rivers set by hand: a dry tile's corners, and every corner draining through them,
        // carry nothing; a source rises at the tile's lowest corner that drains.
        let mut source = vec![false; n];
        if !input.by_hand.is_empty() {
            let mut dry = vec![false; n];
            for (i, ring) in corners.iter().enumerate() {
                match input.by_hand[i] {
                    Some(RiverEdit::Dry) => ring.iter().for_each(|&c| dry[c as usize] = true),
                    Some(RiverEdit::Source) => {
                        let lowest = ring
                            .iter()
                            .map(|&c| c as usize)
                            .filter(|&c| down[c] != NONE)
                            .min_by(|&a, &b| level[a].total_cmp(&level[b]));
                        if let Some(c) = lowest {
                            source[c] = true;
                        }
                    }
                    None => {}
                }
            }
            // Downstream first: a corner is dry when it or the corner it drains into is.
            for &c in &order {
                dry[c] |= down[c] != NONE && dry[down[c] as usize];
                if dry[c] {
                    flow[c] = 0.0;
                    source[c] = false;
                } else if source[c] {
                    flow[c] = flow[c].max(config.threshold);
                }
            }
        }
        for &c in order.iter().rev() {
            if down[c] != NONE {
                flow[down[c] as usize] += flow[c];
            }
        }
        let count = tiles.len();
        let mut network = Self {
            tiles,
            corners,
            ends: shape.ends,
            links,
            down,
            level,
            flow,
            river: Vec::new(),
            edges: vec![0; count],
            widths: vec![[0.0; 6]; count],
        };
        network.river = network.rivers(config, input, &index, (&order, &source));
        let width = |flow: f32| config.width * (flow / config.threshold).sqrt().clamp(1.0, 2.0);
        for c in 0..n {
            if network.river[c] {
                let edge = network.link_down(c);
                let (i, d) = (edge.tile as usize, usize::from(edge.direction));
                let other = index(network.tiles[i].all_neighbors()[d]).expect("a river edge lies between map tiles");
                let w = width(network.flow[c]);
                for (tile, d) in [(i, d), (other, (d + 3) % 6)] {
                    network.edges[tile] |= 1 << d;
                    network.widths[tile][d] = w;
                }
            }
        }
        network
    }

    /// Which corners' downstream edges carry a river: those whose flow reaches the threshold,
    /// downstream of a source (a river corner no river flows into) at least `sea_distance`
    /// tiles from the sea.
    fn rivers(
        &self,
        config: &RiverConfig,
        input: &EdgeInput<'_>,
        index: &impl Fn(Hex) -> Option<usize>,
        (order, by_hand): (&[usize], &[bool]),
    ) -> Vec<bool> {
        let (down, flow) = (&self.down, &self.flow);
        let n = down.len();
        let wet: Vec<bool> = (0..n).map(|c| down[c] != NONE && flow[c] >= config.threshold).collect();
        let mut fed = vec![false; n];
        for c in 0..n {
            if wet[c] {
                fed[down[c] as usize] = true;
            }
        }
        // The distance of a corner to the sea: its nearest map tile's.
        let far = sea_distances(input, index);
        let mut near = vec![u32::MAX; n];
        for (i, ring) in self.corners.iter().enumerate() {
            for &c in ring {
                near[c as usize] = near[c as usize].min(far[i]);
            }
        }
        let mut keep = vec![false; n];
        for &c in order.iter().rev() {
            if !wet[c] {
                continue;
            }
            if !fed[c] {
                keep[c] = by_hand[c] || near[c] >= config.sea_distance;
            }
            let next = down[c] as usize;
            if keep[c] && wet[next] {
                keep[next] = true;
            }
        }
        keep
    }

    /// The edge from corner `c` to its downstream corner.
    fn link_down(&self, c: usize) -> Link {
        *self.links[c].iter().find(|l| l.to == self.down[c]).expect("the downstream corner is a neighbor")
    }

    /// The river edges of map tile `i`, a bit for each neighbor direction.
    #[must_use]
    #[inline]
    pub(crate) fn edges_of(&self, i: usize) -> u8 {
        self.edges[i]
    }

    /// The channel half-widths of map tile `i` along its six edges, in lattice steps (0: none).
    #[must_use]
    #[inline]
    pub(crate) fn widths(&self, i: usize) -> &[f32; 6] {
        &self.widths[i]
    }

    /// The two corners at the ends of map tile `i`'s edge `d`, in the order of the edge's
    /// vertices.
    fn ends(&self, i: usize, d: usize) -> (usize, usize) {
        let (a, b) = self.ends[d];
        (self.corners[i][a] as usize, self.corners[i][b] as usize)
    }

    /// The river edges of `tile` (map tile `i`), from its side.
    pub(crate) fn river_edges(&self, tile: Hex, i: usize) -> Vec<RiverEdge> {
        let mask = self.edges[i];
        EdgeDirection::ALL_DIRECTIONS
            .into_iter()
            .enumerate()
            .filter(|&(d, _)| mask & (1 << d) != 0)
            .map(|(d, direction)| {
                let edge = GridEdge { origin: tile, direction };
                let [p, q] = edge.vertices();
                let (a, b) = self.ends(i, d);
                // The river runs from one end to the other: the end whose downstream is the other.
                let (from, to) = if self.river[a] && self.down[a] == b as u32 { (a, q) } else { (b, p) };
                RiverEdge { edge, flow: self.flow[from], downstream: to, level: self.level[from] }
            })
            .collect()
    }

    /// The river's course from map tile `i`'s edge `d` (a river edge) down to where it ends:
    /// each edge, named from a map tile beside it, in order.
    pub(crate) fn course(&self, i: usize, d: usize) -> Vec<GridEdge> {
        let (a, b) = self.ends(i, d);
        let mut at = if self.river[a] && self.down[a] == b as u32 {
            a
        } else if self.river[b] && self.down[b] == a as u32 {
            b
        } else {
            return Vec::new();
        };
        let mut out = Vec::new();
        while self.river[at] {
            let link = self.link_down(at);
            let direction = EdgeDirection::ALL_DIRECTIONS[usize::from(link.direction)];
            out.push(GridEdge { origin: self.tiles[link.tile as usize], direction });
            at = self.down[at] as usize;
        }
        out
    }

    /// Whether map tile `i` has the same river edges, as wide, in `self` and `other`.
    #[must_use]
    pub(crate) fn same_tile(&self, other: &Self, i: usize) -> bool {
        self.edges[i] == other.edges[i] && self.widths[i].map(f32::to_bits) == other.widths[i].map(f32::to_bits)
    }
}

/// Each map tile's distance in tiles to the nearest sea tile (a breadth-first search from every
/// sea tile at once); `u32::MAX` on a map without sea.
fn sea_distances(input: &EdgeInput<'_>, index: &impl Fn(Hex) -> Option<usize>) -> Vec<u32> {
    let tiles = input.tiles;
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
