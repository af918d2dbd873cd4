//! The corners of a bounded map's tiles, where three tiles meet, as the edge river network
//! ([`super::edges`]) keeps them: one name a corner (hexx's `GridVertex` seen in direction 0 or
//! 1), two corners a tile in a grid over the map, and the same names from every tile; and the
//! queue the network's flood takes them from.

use hexx::{EdgeDirection, GridEdge, GridVertex, Hex};

use crate::chunk::TileRect;
use crate::geometry::Geometry;

/// How a tile's corners and edges are named, the same for every tile: for each vertex
/// direction, the corner's owner (the tile seeing it in direction 0 or 1) relative to the tile
/// and that direction; for each edge direction, the two vertex directions at its ends.
pub(super) struct Shape {
    pub(super) owners: [(Hex, u8); 6],
    pub(super) ends: [(usize, usize); 6],
}

impl Shape {
    pub(super) fn new() -> Self {
        let vertices = Hex::ZERO.all_vertices();
        let owners = vertices.map(|v| {
            let c = canonical(v);
            (c.origin, c.direction.index())
        });
        let ends = EdgeDirection::ALL_DIRECTIONS.map(|d| {
            let [p, q] = GridEdge { origin: Hex::ZERO, direction: d }.vertices();
            let slot = |v: GridVertex| vertices.iter().position(|w| w.equivalent(&v)).expect("a vertex of the tile");
            (slot(p), slot(q))
        });
        Self { owners, ends }
    }
}

/// The offsets (in offset coordinates) from a tile to the owners of its six corners, which
/// depend on the parity of the tile's row (pointy tiles: odd rows are shoved) or column (flat
/// tiles) alone, so two tables serve every tile of the map.
pub(super) struct Owners {
    /// For even (`[0]`) and odd (`[1]`) rows or columns.
    offsets: [[[i32; 2]; 6]; 2],
    /// Whether the row's parity picks the table (else the column's).
    by_row: bool,
}

impl Owners {
    pub(super) fn new(geometry: &Geometry, shape: &Shape) -> Self {
        let offsets = std::array::from_fn(|parity| {
            // A tile of this parity along both axes, so it serves either layout.
            let reference = geometry.tile_from_offset([2 + parity as i32, 2 + parity as i32]);
            let [c, r] = geometry.offset_of(reference);
            shape.owners.map(|(owner, _)| {
                let [oc, or] = geometry.offset_of(reference + owner);
                [oc - c, or - r]
            })
        });
        Self { offsets, by_row: geometry.layout().orientation == hexx::HexOrientation::Pointy }
    }
}

/// Where corners are kept: two a tile (its vertices 0 and 1), over the map's tiles with a row
/// more above and below and, on a map that does not wrap, a column more either side.
#[derive(Debug, Clone, Copy)]
pub(super) struct CornerGrid {
    rect: TileRect,
    wraps: bool,
    cols: i32,
    width: usize,
    height: usize,
}

impl CornerGrid {
    pub(super) fn new(rect: TileRect, wraps: bool) -> Self {
        let cols = rect.max[0] - rect.min[0];
        let rows = (rect.max[1] - rect.min[1]) as usize;
        let width = if wraps { cols as usize } else { cols as usize + 2 };
        Self { rect, wraps, cols, width, height: rows + 2 }
    }

    pub(super) fn len(&self) -> usize {
        self.width * self.height * 2
    }

    /// The six corners of the map tile at offset `[col, row]`.
    pub(super) fn tile_corners(&self, shape: &Shape, owners: &Owners, [col, row]: [i32; 2]) -> [u32; 6] {
        let parity = (if owners.by_row { row } else { col }).rem_euclid(2) as usize;
        let deltas = &owners.offsets[parity];
        std::array::from_fn(|j| {
            let [dc, dr] = deltas[j];
            self.at([col + dc, row + dr], shape.owners[j].1) as u32
        })
    }

    /// The index of the corner `owner` sees in direction `k` (0 or 1), `owner` any copy of a
    /// tile next to the map (a wrapping map's columns repeat every `cols`, their parity kept).
    #[cfg(test)]
    fn index(&self, geometry: &Geometry, owner: Hex, k: u8) -> usize {
        self.at(geometry.offset_of(owner), k)
    }

    /// The index of the corner the tile at offset `[col, row]` sees in direction `k`.
    fn at(&self, [col, row]: [i32; 2], k: u8) -> usize {
        let col = col - self.rect.min[0];
        let col = if self.wraps { col.rem_euclid(self.cols) } else { col + 1 };
        let row = (row - self.rect.min[1] + 1) as usize;
        debug_assert!((col as usize) < self.width && row < self.height, "a corner of a map tile");
        (row * self.width + col as usize) * 2 + usize::from(k)
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

/// A queue key: the level's bits turned so integers order as the levels do (`f32::total_cmp`),
/// then the order pushed; the smallest first.
pub(super) fn key(level: f32, seq: u32) -> u64 {
    let bits = level.to_bits();
    let ordered = if bits >> 31 == 1 { !bits } else { bits | 0x8000_0000 };
    (u64::from(ordered) << 32) | u64::from(seq)
}

/// A radix heap: a priority queue for keys that never fall below the last one taken (a priority
/// flood's levels only rise), taking them smallest first in constant time amortised. Keys are
/// unique (the order pushed is in them), so the order taken is the keys' alone.
pub(super) struct RadixHeap {
    last: u64,
    /// Bucket `b` holds the keys whose highest bit differing from `last` is bit `b - 1` (bucket
    /// 0: `last` itself).
    buckets: [Vec<(u64, u32)>; 65],
}

impl RadixHeap {
    pub(super) fn new() -> Self {
        Self { last: 0, buckets: std::array::from_fn(|_| Vec::new()) }
    }

    fn bucket(&self, key: u64) -> usize {
        64 - (key ^ self.last).leading_zeros() as usize
    }

    pub(super) fn push(&mut self, key: u64, value: u32) {
        debug_assert!(key >= self.last, "a key below the last one taken");
        let b = self.bucket(key);
        self.buckets[b].push((key, value));
    }

    pub(super) fn pop(&mut self) -> Option<u32> {
        if self.buckets[0].is_empty() {
            let b = self.buckets.iter().position(|v| !v.is_empty())?;
            let moved = std::mem::take(&mut self.buckets[b]);
            self.last = moved.iter().map(|&(k, _)| k).min().expect("a bucket that is not empty");
            for (k, v) in moved {
                let to = self.bucket(k);
                self.buckets[to].push((k, v));
            }
        }
        self.buckets[0].pop().map(|(_, v)| v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The radix heap takes keys smallest first, as a sort does, while pushes never go below
    /// the last key taken (as in a flood); the keys order as the levels (then the pushes) do.
    #[test]
    fn the_radix_heap_takes_keys_in_order() {
        assert!(key(-0.5, 9) < key(0.0, 0) && key(0.0, 3) < key(0.0, 4) && key(0.25, 0) < key(0.5, 0));
        let mut heap = RadixHeap::new();
        let (mut taken, mut pushed) = (Vec::new(), Vec::new());
        let mut seed = 12345_u64;
        let mut next = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 33) as u32
        };
        let mut last = 0.0_f32;
        for round in 0..2000_u32 {
            for _ in 0..next() % 4 {
                let k = key(last + (next() % 1000) as f32 / 100.0, round * 8 + pushed.len() as u32 % 8);
                heap.push(k, pushed.len() as u32);
                pushed.push(k);
            }
            if next() % 3 > 0
                && let Some(v) = heap.pop()
            {
                taken.push(pushed[v as usize]);
                last = f32::from_bits(((pushed[v as usize] >> 32) as u32) & 0x7fff_ffff);
            }
        }
        while let Some(v) = heap.pop() {
            taken.push(pushed[v as usize]);
        }
        assert_eq!(taken.len(), pushed.len());
        assert!(taken.windows(2).all(|w| w[0] < w[1]), "keys taken out of order");
    }

    /// A corner's three names give one corner; the shape's owners name a tile's corners, and
    /// the ends of each edge are two of them, next to each other around the tile.
    #[test]
    fn corners_have_one_name_and_edges_two_ends() {
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
            }
        }
        let shape = Shape::new();
        for (j, v) in Hex::ZERO.all_vertices().into_iter().enumerate() {
            let (owner, k) = shape.owners[j];
            assert!(
                GridVertex { origin: owner, direction: hexx::VertexDirection::ALL_DIRECTIONS[usize::from(k)] }
                    .equivalent(&v)
            );
        }
        for &(a, b) in &shape.ends {
            assert!(a != b && (a + 1) % 6 == b || (b + 1) % 6 == a, "{a} {b}");
        }
        // A tile's corners from the owners' offset tables are the corners its vertices name,
        // for both layouts, wrapping or not.
        for (orientation, wrap) in [(crate::Orientation::Pointy, false), (crate::Orientation::Flat, true)] {
            let mut config =
                crate::MapConfig { size: crate::MapSize::Bounded { x: 12, z: 9 }, wrap, ..Default::default() };
            config.layout.orientation = orientation;
            let geometry = Geometry::new(&config);
            let rect = geometry.bounds().unwrap();
            let grid = CornerGrid::new(rect, wrap);
            let owners = Owners::new(&geometry, &shape);
            for oc in rect.iter() {
                let tile = geometry.tile_from_offset(oc);
                let named = tile.all_vertices().map(|v| {
                    let c = canonical(v);
                    let owner = if wrap { geometry.wrap_tile(c.origin) } else { c.origin };
                    grid.index(&geometry, owner, c.direction.index()) as u32
                });
                assert_eq!(grid.tile_corners(&shape, &owners, oc), named, "{orientation:?} {oc:?}");
            }
        }
        // `all_neighbors` runs in the edge directions' order.
        for (d, nb) in Hex::ZERO.all_neighbors().into_iter().enumerate() {
            assert_eq!(Hex::ZERO + EdgeDirection::ALL_DIRECTIONS[d], nb);
        }
    }
}
