//! The water methods of [`Terrain`]: rivers, lakes, channel cover, vertex colors and the water
//! surface of a chunk.

use hexx::{GridEdge, Hex};

use super::Terrain;
use crate::mesh::{self, ChunkMesh};
use crate::vocab::Biome;
use crate::water::{self, Hydrology, RiverEdge, RiverTile, WaterBuffers};

impl Terrain {
    /// The map's water network: `None` on a map without rivers.
    #[must_use]
    pub fn hydrology(&self) -> Option<&Hydrology> {
        self.pipeline.table()?.hydrology()
    }

    /// The river on a tile of the map, if one runs through it.
    #[must_use]
    pub fn river(&self, tile: Hex) -> Option<RiverTile> {
        if !self.contains(tile) {
            return None;
        }
        self.pipeline.table()?.river(self.geometry(), tile)
    }

    /// Water a river on a tile of the map carries, `Some(0.0)` when no river runs through it;
    /// `None` for a tile not on the map.
    #[must_use]
    pub fn river_flow(&self, tile: Hex) -> Option<f32> {
        if !self.contains(tile) {
            return None;
        }
        Some(self.pipeline.table().map_or(0.0, |t| t.river_flow(self.geometry(), tile)))
    }

    /// The river edges of a tile of the map (`rivers.model: Edges`), from its side: which of
    /// its edges carry a river, the flow and the corner it flows toward. Empty for a tile with
    /// none, off the map, or on a map whose rivers run through tile centers.
    #[must_use]
    pub fn river_edges(&self, tile: Hex) -> Vec<RiverEdge> {
        let Some(tile) = self.wrap_tile(tile).filter(|&t| self.contains(t)) else { return Vec::new() };
        self.pipeline.table().map_or_else(Vec::new, |t| t.river_edges(self.geometry(), tile))
    }

    /// Whether the step from `from` to its neighbor `to` crosses a river on the edge between
    /// them (`rivers.model: Edges`); `false` when they are not neighbors on the map.
    #[must_use]
    pub fn crosses_river(&self, from: Hex, to: Hex) -> bool {
        let Some(d) = self.step_direction(from, to) else { return false };
        let Some(from) = self.wrap_tile(from) else { return false };
        self.pipeline.table().is_some_and(|t| t.river_edge_mask(self.geometry(), from) & (1 << d) != 0)
    }

    /// The index into `all_neighbors` of the step from `from` to its neighbor `to` (any copies
    /// of them on a wrapping map), when both are on the map.
    pub(crate) fn step_direction(&self, from: Hex, to: Hex) -> Option<usize> {
        let (a, b) = (self.wrap_tile(from)?, self.wrap_tile(to)?);
        if !(self.contains(a) && self.contains(b)) {
            return None;
        }
        a.all_neighbors().iter().position(|&nb| self.wrap_tile(nb) == Some(b))
    }

    /// The course of the river on `edge` (an edge carrying a river, named from either side)
    /// down to where it ends (the sea, a lake or the map's edge): each edge, named from a tile
    /// beside it, in order, `edge` first. Empty when `edge` carries no river.
    #[must_use]
    pub fn river_course(&self, edge: GridEdge) -> Vec<GridEdge> {
        let Some(table) = self.pipeline.table() else { return Vec::new() };
        match (table.edge_rivers(), table.index(self.geometry(), edge.origin)) {
            (Some(rivers), Some(i)) => rivers.course(i, usize::from(edge.direction.index())),
            _ => Vec::new(),
        }
    }

    /// The lake a tile belongs to (an id, 0 for the first lake), if it is a lake tile.
    #[must_use]
    pub fn lake(&self, tile: Hex) -> Option<u32> {
        if !self.contains(tile) {
            return None;
        }
        self.pipeline.table()?.lake(self.geometry(), tile)
    }

    /// Every river tile of the map, row by row.
    #[must_use]
    pub fn rivers(&self) -> Vec<RiverTile> {
        self.tiles().filter_map(|t| self.river(t)).collect()
    }

    /// Water level of a tile of the map (the filled surface, normalised), on a map with
    /// rivers.
    #[must_use]
    pub fn water_level(&self, tile: Hex) -> Option<f32> {
        if !self.contains(tile) {
            return None;
        }
        self.pipeline.table()?.water_level(self.geometry(), tile)
    }

    /// How much of a channel or lake covers lattice point `p` of `tile`: 1 on a lake tile and on
    /// a channel's middle line, falling smoothly to 0 at the channel's half-width (`Some(0.0)`
    /// on a dry tile); `None` for a tile not on the map or a point past the world.
    #[must_use]
    pub fn water_cover(&self, tile: Hex, p: Hex) -> Option<f32> {
        (self.contains(tile) && self.geometry().point_in_world(p)).then(|| self.pipeline.water_cover(tile, p))
    }

    /// Whether any water (a lake, or a river channel) lies on a tile: every point of a dry tile
    /// has a water cover of 0.
    #[must_use]
    pub fn tile_is_wet(&self, tile: Hex) -> bool {
        self.contains(tile) && self.pipeline.tile_is_wet(tile)
    }

    /// Whether meshes carry a color per vertex (climate or rivers on).
    #[must_use]
    pub fn has_vertex_colors(&self) -> bool {
        self.pipeline.has_vertex_colors()
    }

    /// The color of a vertex shared by tiles of `biomes`: their colors averaged (integer
    /// arithmetic, so the order of the tiles does not matter), the water cover in alpha.
    #[must_use]
    pub fn vertex_color(biomes: &[Biome], water: f32) -> [u8; 4] {
        mesh::vertex_color(biomes, water)
    }

    /// Color of the lattice point `p` evaluated on its own: the in-map tiles holding it, their
    /// colors averaged ([`Terrain::vertex_color`]'s rule; under the map's own ruleset, its
    /// terrains' and features' colors), and its water cover; `None` past the world.
    #[must_use]
    pub fn point_color(&self, p: Hex) -> Option<[u8; 4]> {
        if !self.geometry().point_in_world(p) {
            return None;
        }
        let set = self.lattice().tiles_at(p);
        let colors: Vec<[u8; 3]> =
            set.tiles().iter().filter(|&&t| self.contains(t)).map(|&t| self.pipeline.tile_color(t)).collect();
        Some(mesh::mixed_color(&colors, self.pipeline.vertex(p).water))
    }

    /// World height of the sea surface: the sea threshold times the maximum elevation (the
    /// height of every border vertex between sea and land tiles).
    #[must_use]
    pub fn sea_level(&self) -> f32 {
        self.pipeline.sea_level()
    }

    /// The water surface over a generated chunk (see `crate::water::surface`); `river_depth`
    /// is the height of river and lake water over a fully covered vertex, in world units. Empty
    /// for a dry chunk.
    #[must_use]
    pub fn water_surface(&self, chunk: &ChunkMesh, river_depth: f32) -> WaterBuffers {
        water::water_surface(&chunk.buffers, self.sea_level(), river_depth)
    }
}
