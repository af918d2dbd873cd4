//! The tiles of a bounded map as a graph of their neighbors, which a map type's tries are
//! measured on ([`super::targets`], [`super::knots`]).

use crate::geometry::Geometry;

/// The tiles of a bounded map as a grid for measuring: each tile's neighbors (wrapped) and
/// whether it lies on the map's edge.
pub(crate) struct TileGraph {
    /// Each tile's neighbors in the map, by index.
    pub neighbors: Vec<[Option<u32>; 6]>,
    /// Whether a tile lies on the map's edge.
    pub edge: Vec<bool>,
    /// Each tile's row, from 0.
    pub row: Vec<u32>,
    /// The map's rows.
    pub rows: u32,
}

impl TileGraph {
    /// The tiles of a bounded map by row (none for an unbounded world).
    pub(crate) fn of(geometry: &Geometry) -> Self {
        let Some(rect) = geometry.bounds() else {
            return Self { neighbors: Vec::new(), edge: Vec::new(), row: Vec::new(), rows: 0 };
        };
        let width = rect.max[0] - rect.min[0];
        let index = |[col, row]: [i32; 2]| ((row - rect.min[1]) * width + (col - rect.min[0])) as u32;
        let wraps = geometry.wrap().is_some();
        let mut neighbors = Vec::with_capacity(rect.len());
        let mut edge = Vec::with_capacity(rect.len());
        let mut rows = Vec::with_capacity(rect.len());
        for tile in geometry.tiles() {
            let [col, row] = geometry.offset_of(tile);
            rows.push((row - rect.min[1]) as u32);
            let around = geometry.wrapped_neighbors(tile);
            neighbors.push(around.map(|nb| geometry.contains(nb).then(|| index(geometry.offset_of(nb)))));
            edge.push(
                row == rect.min[1]
                    || row == rect.max[1] - 1
                    || (!wraps && (col == rect.min[0] || col == rect.max[0] - 1)),
            );
        }
        TileGraph { neighbors, edge, row: rows, rows: (rect.max[1] - rect.min[1]) as u32 }
    }
}
