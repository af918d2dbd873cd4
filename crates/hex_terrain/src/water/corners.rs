//! The corners of a bounded map's tiles, where three tiles meet, as the edge river network
//! ([`super::edges`]) keeps them: one name a corner (hexx's `GridVertex` seen in direction 0 or
//! 1), two corners a tile in a grid over the map, the same names from every tile, and each
//! corner's tiles and neighbors from a few stencils.

use hexx::{EdgeDirection, GridEdge, GridVertex, Hex};

use crate::chunk::TileRect;
use crate::geometry::Geometry;

/// How a tile's corners and edges are named, the same for every tile: for each vertex
/// direction, the corner's owner (the tile seeing it in direction 0 or 1) relative to the tile
/// and that direction; for each edge direction, the two vertex directions at its ends.
#[derive(Debug, Clone)]
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
#[derive(Debug, Clone)]
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

/// The corners around a corner, the same for every corner of one kind (direction 0 or 1) whose
/// owner has the same parity: offsets (in offset coordinates) from the owner to the corner's
/// three tiles, to the owners of the three corners it has edges to (with their direction), and
/// for each of those edges a tile beside it and the edge's direction from that tile.
#[derive(Debug, Clone, Copy)]
pub(super) struct Stencil {
    pub(super) tiles: [[i32; 2]; 3],
    pub(super) links: [([i32; 2], u8); 3],
    pub(super) edges: [([i32; 2], u8); 3],
}

/// The four stencils of a map's corners, by the owner's parity (as [`Owners`]) and direction.
#[derive(Debug, Clone)]
pub(super) struct Stencils {
    by_parity: [[Stencil; 2]; 2],
    /// Offsets from a tile to its neighbors in `Hex::all_neighbors` order, by parity.
    neighbors: [[[i32; 2]; 6]; 2],
    by_row: bool,
}

impl Stencils {
    pub(super) fn new(geometry: &Geometry) -> Self {
        // A tile of each parity along both axes, so it serves either layout, and offsets from it.
        let reference = |parity: usize| geometry.tile_from_offset([2 + parity as i32, 2 + parity as i32]);
        let offset = |parity: usize, h: Hex| {
            let [rc, rr] = geometry.offset_of(reference(parity));
            let [c, r] = geometry.offset_of(h);
            [c - rc, r - rr]
        };
        let neighbors = std::array::from_fn(|parity| reference(parity).all_neighbors().map(|n| offset(parity, n)));
        let by_parity = std::array::from_fn(|parity| {
            let reference = reference(parity);
            let offset = |h: Hex| offset(parity, h);
            std::array::from_fn(|k| {
                let corner = GridVertex { origin: reference, direction: hexx::VertexDirection::ALL_DIRECTIONS[k] };
                let tiles = corner.coordinates();
                // Each edge from the corner lies between two of its tiles; its other end is the
                // corner across it.
                let pairs = [(0, 1), (1, 2), (2, 0)];
                let edge = |m: usize| {
                    let (a, b) = (tiles[pairs[m].0], tiles[pairs[m].1]);
                    let d = a.all_neighbors().iter().position(|&n| n == b).expect("a corner's tiles are neighbors");
                    GridEdge { origin: a, direction: EdgeDirection::ALL_DIRECTIONS[d] }
                };
                Stencil {
                    tiles: tiles.map(offset),
                    links: std::array::from_fn(|m| {
                        let [p, q] = edge(m).vertices();
                        let other = canonical(if p.equivalent(&corner) { q } else { p });
                        (offset(other.origin), other.direction.index())
                    }),
                    edges: std::array::from_fn(|m| {
                        let e = edge(m);
                        (offset(e.origin), e.direction.index())
                    }),
                }
            })
        });
        Self { by_parity, neighbors, by_row: geometry.layout().orientation == hexx::HexOrientation::Pointy }
    }

    /// The offsets from the tile at offset `[col, row]` to its neighbors, in `Hex::all_neighbors`
    /// order.
    #[inline]
    pub(super) fn neighbors(&self, [col, row]: [i32; 2]) -> &[[i32; 2]; 6] {
        &self.neighbors[self.parity([col, row])]
    }

    #[inline]
    fn parity(&self, [col, row]: [i32; 2]) -> usize {
        ((if self.by_row { row } else { col }) & 1) as usize
    }

    /// How far (in columns or rows) a stencil reaches from a corner's owner.
    pub(super) fn reach(&self) -> i32 {
        let mut reach = 0;
        for stencil in self.by_parity.iter().flatten() {
            let offsets = stencil.tiles.iter().chain(stencil.links.iter().map(|(d, _)| d));
            reach = offsets.fold(reach, |r, [dc, dr]| r.max(dc.abs()).max(dr.abs()));
        }
        reach
    }

    /// The stencils as index shifts, for a corner away from the map's edges: to each of its
    /// tiles from its owner's row-major index in a map `cols` wide, and to each of its links
    /// from its own index in a grid whose rows hold `row_corners` corners.
    pub(super) fn shifts(&self, cols: isize, row_corners: isize) -> Shifts {
        Shifts {
            by_parity: self.by_parity.map(|kinds| {
                let mut k = 0;
                kinds.map(|stencil| {
                    let tiles = stencil.tiles.map(|[dc, dr]| dr as isize * cols + dc as isize);
                    let links = stencil
                        .links
                        .map(|([dc, dr], to)| dr as isize * row_corners + dc as isize * 2 + isize::from(to) - k);
                    k += 1;
                    (tiles, links)
                })
            }),
            by_row: self.by_row,
        }
    }

    /// The stencil of the corner the tile at offset `[col, row]` sees in direction `k`.
    #[inline]
    pub(super) fn of(&self, offset: [i32; 2], k: usize) -> &Stencil {
        &self.by_parity[self.parity(offset)][k]
    }
}

/// [`Stencils`] as index shifts away from the map's edges.
pub(super) struct Shifts {
    by_parity: [[([isize; 3], [isize; 3]); 2]; 2],
    by_row: bool,
}

impl Shifts {
    /// The shifts to the tiles and links of the corner the tile at offset `[col, row]` sees in
    /// direction `k`.
    #[inline]
    pub(super) fn of(&self, [col, row]: [i32; 2], k: usize) -> &([isize; 3], [isize; 3]) {
        &self.by_parity[((if self.by_row { row } else { col }) & 1) as usize][k]
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

    /// The grid's width and height in tiles (each two corners).
    pub(super) fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// The offset coordinate of the tile at column `col` and row `row` of the grid.
    #[inline]
    pub(super) fn offset_at(&self, col: usize, row: usize) -> [i32; 2] {
        let col = if self.wraps { col as i32 } else { col as i32 - 1 };
        [self.rect.min[0] + col, self.rect.min[1] + row as i32 - 1]
    }

    /// A column of the map, brought onto it on a wrapping map (`col` at most a map's width
    /// past it).
    #[inline]
    fn wrap_col(&self, col: i32) -> i32 {
        if !self.wraps {
            col
        } else if col < 0 {
            col + self.cols
        } else if col >= self.cols {
            col - self.cols
        } else {
            col
        }
    }

    /// The map's width and height in tiles.
    pub(super) fn map_size(&self) -> (i32, i32) {
        (self.cols, self.height as i32 - 2)
    }

    /// The column and row in the map of offset `[col, row]` (past the map for a tile past it).
    #[inline]
    pub(super) fn map_col_row(&self, [col, row]: [i32; 2]) -> (i32, i32) {
        (col - self.rect.min[0], row - self.rect.min[1])
    }

    /// The links of corner `c`, owned by the tile at offset `owner` with this stencil: the
    /// corners across its edges, the corner itself past the grid.
    pub(super) fn links(&self, stencil: &Stencil, [col, row]: [i32; 2], c: usize) -> [u32; 3] {
        stencil.links.map(|([dc, dr], k)| self.at([col + dc, row + dr], k).map_or(c as u32, |j| j as u32))
    }

    /// The offset coordinate of the tile that owns corner `c`, and the direction it sees it in.
    #[inline]
    pub(super) fn owner(&self, c: usize) -> ([i32; 2], usize) {
        let slot = c / 2;
        (self.offset_at(slot % self.width, slot / self.width), c % 2)
    }

    /// The row-major index in the map of the tile at offset `[col, row]` (any copy of it on a
    /// wrapping map), `None` past the map.
    #[inline]
    pub(super) fn tile(&self, [col, row]: [i32; 2]) -> Option<usize> {
        let (col, row) = (self.wrap_col(col - self.rect.min[0]), row - self.rect.min[1]);
        (row >= 0 && row < self.height as i32 - 2 && col >= 0 && col < self.cols)
            .then(|| row as usize * self.cols as usize + col as usize)
    }

    /// The offset coordinate of map tile `i`.
    #[inline]
    pub(super) fn tile_offset(&self, i: usize) -> [i32; 2] {
        let cols = self.cols as usize;
        [self.rect.min[0] + (i % cols) as i32, self.rect.min[1] + (i / cols) as i32]
    }

    /// The six corners of the map tile at offset `[col, row]`.
    pub(super) fn tile_corners(&self, shape: &Shape, owners: &Owners, [col, row]: [i32; 2]) -> [u32; 6] {
        let parity = (if owners.by_row { row } else { col }).rem_euclid(2) as usize;
        let deltas = &owners.offsets[parity];
        std::array::from_fn(|j| {
            let [dc, dr] = deltas[j];
            self.at([col + dc, row + dr], shape.owners[j].1).expect("a map tile's corner is in the grid") as u32
        })
    }

    /// The index of the corner `owner` sees in direction `k` (0 or 1), `owner` any copy of a
    /// tile next to the map (a wrapping map's columns repeat every `cols`, their parity kept).
    #[cfg(test)]
    fn index(&self, geometry: &Geometry, owner: Hex, k: u8) -> usize {
        self.at(geometry.offset_of(owner), k).expect("a corner in the grid")
    }

    /// The index of the corner the tile at offset `[col, row]` sees in direction `k`, `None`
    /// past the grid.
    #[inline]
    pub(super) fn at(&self, [col, row]: [i32; 2], k: u8) -> Option<usize> {
        let col = self.wrap_col(col - self.rect.min[0]) + i32::from(!self.wraps);
        let row = row - self.rect.min[1] + 1;
        (col >= 0 && (col as usize) < self.width && row >= 0 && (row as usize) < self.height)
            .then(|| (row as usize * self.width + col as usize) * 2 + usize::from(k))
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
mod tests;
