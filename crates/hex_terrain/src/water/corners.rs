//! The corners of a bounded map's tiles, where three tiles meet, as the edge river network
//! ([`super::edges`]) keeps them: one name a corner (hexx's `GridVertex` seen in direction 0 or
//! 1), two corners a tile in a grid over the map, and the same names from every tile.

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

    /// The index of the corner `owner` sees in direction `k` (0 or 1), `owner` any copy of a
    /// tile next to the map (a wrapping map's columns repeat every `cols`, their parity kept).
    pub(super) fn index(&self, geometry: &Geometry, owner: Hex, k: u8) -> usize {
        let [col, row] = geometry.offset_of(owner);
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

#[cfg(test)]
mod tests {
    use super::*;

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
        // `all_neighbors` runs in the edge directions' order.
        for (d, nb) in Hex::ZERO.all_neighbors().into_iter().enumerate() {
            assert_eq!(Hex::ZERO + EdgeDirection::ALL_DIRECTIONS[d], nb);
        }
    }
}
