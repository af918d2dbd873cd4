//! Water in the mesh: river channels carved from tile centers to the edges they cross, lake
//! tiles flattened to the bottom of their kind's range, and each vertex's color (its tiles'
//! biome colors averaged, water in alpha).
//!
//! A vertex is carved by the tiles that hold it, each from its own channels, so the two tiles
//! on either side of a river's edge agree on it whichever chunk evaluates it. Carving only
//! lowers a vertex towards the bottom of its kind's range, and never moves a border vertex
//! between tiles of different kinds (hex unity keeps it on the threshold), so every non-border
//! vertex stays inside its kind's range.

use hexx::Hex;

use super::Biome;
use crate::kind::TileKind;
use crate::manipulate::VertexSample;
use crate::terrain::Terrain;

impl Terrain {
    /// How much of a channel or lake covers lattice point `p` of `tile`: 1 on a lake tile and on
    /// a channel's middle line, falling smoothly to 0 at the channel's half-width.
    #[must_use]
    pub fn water_profile(&self, tile: Hex, p: Hex) -> f32 {
        let Some(table) = &self.table else { return 0.0 };
        let Some(h) = &table.hydrology else { return 0.0 };
        let Some(i) = table.index(self, tile) else { return 0.0 };
        if h.lake_of(i).is_some() {
            return 1.0;
        }
        let channels = h.channels(i);
        if channels.iter().all(|&w| w == 0.0) {
            return 0.0;
        }
        let lattice = &self.lattice;
        let center = lattice.tile_center(tile);
        let step = f64::from(self.config.layout.hex_size) / f64::from(lattice.subdivisions());
        let [px, pz] = lattice.world(p - center);
        let mut best = 0.0_f64;
        for (nb, &w) in tile.all_neighbors().iter().zip(channels) {
            if w == 0.0 {
                continue;
            }
            let [ex, ez] = lattice.world(lattice.tile_center(*nb) - center);
            let (mx, mz) = (ex * 0.5, ez * 0.5);
            let t = ((px * mx + pz * mz) / (mx * mx + mz * mz)).clamp(0.0, 1.0);
            let (dx, dz) = (px - t * mx, pz - t * mz);
            let x = ((dx * dx + dz * dz).sqrt() / (step * f64::from(w))).min(1.0);
            best = best.max(1.0 - x * x * (3.0 - 2.0 * x));
        }
        best as f32
    }

    /// Whether any water (a lake, or a river channel) lies on a tile: a point of a dry tile has
    /// a water profile of 0.
    #[must_use]
    pub fn tile_is_wet(&self, tile: Hex) -> bool {
        let Some(table) = &self.table else { return false };
        let (Some(h), Some(i)) = (&table.hydrology, table.index(self, tile)) else { return false };
        h.lake_of(i).is_some() || h.channels(i).iter().any(|&w| w > 0.0)
    }

    /// Carves a manipulated vertex at `p` shared by the in-map `tiles` of `kinds` (same order):
    /// lowers it by the water profile towards the bottom of its kind's range. A no-op on a map
    /// without rivers.
    #[inline]
    pub(crate) fn carve(&self, p: Hex, tiles: &[Hex], kinds: &[TileKind], mut s: VertexSample) -> VertexSample {
        let Some(&first) = kinds.first() else { return s };
        if self.hydrology().is_none() || kinds.iter().any(|&k| k != first) {
            return s;
        }
        let f = tiles.iter().map(|&t| self.water_profile(t, p)).fold(0.0_f32, f32::max);
        if f > 0.0 {
            let lo = self.thresholds.range(first).0;
            if s.height > lo {
                let carved = s.height - f * self.config.rivers.carve * (s.height - lo);
                s.moved |= carved != s.height;
                s.height = carved.max(lo);
            }
            s.water = f;
        }
        s
    }

    /// Whether meshes carry a color per vertex (climate or rivers on).
    #[must_use]
    pub fn has_vertex_colors(&self) -> bool {
        self.config.climate.enabled || self.config.rivers.enabled
    }

    /// The color of a vertex shared by tiles of `biomes`: their colors averaged (integer
    /// arithmetic, so the order of the tiles does not matter), the water profile in alpha.
    #[must_use]
    #[inline]
    pub fn vertex_color(biomes: &[Biome], water: f32) -> [u8; 4] {
        let mut sum = [0_u32; 3];
        for b in biomes {
            for (s, c) in sum.iter_mut().zip(b.color()) {
                *s += u32::from(c);
            }
        }
        let n = biomes.len().max(1) as u32;
        let avg = sum.map(|s| ((s + n / 2) / n) as u8);
        [avg[0], avg[1], avg[2], (water.clamp(0.0, 1.0) * 255.0).round() as u8]
    }

    /// Color of the lattice point `p` evaluated on its own: [`Terrain::vertex_color`] of the
    /// in-map tiles holding it and its water profile.
    #[must_use]
    pub fn point_color(&self, p: Hex) -> [u8; 4] {
        let set = self.lattice.tiles_at(p);
        let biomes: Vec<Biome> =
            set.tiles().iter().filter(|&&t| self.contains(t)).map(|&t| self.tile_biome(t)).collect();
        Self::vertex_color(&biomes, self.vertex(p).water)
    }
}
