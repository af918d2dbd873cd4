//! The tiles of a bounded map, computed once when the map is compiled: center heights, kinds,
//! rivers and lakes, biomes. Chunks read it, so a non-local feature (a river drains a whole
//! basin) is the same in every chunk and in the whole map.

use hexx::Hex;

use super::hydrology::Hydrology;
use super::{Biome, Climate, TileSample};
use crate::chunk::TileRect;
use crate::kind::TileKind;
use crate::terrain::Terrain;

/// Per-tile data of a bounded map, row by row.
#[derive(Debug, Clone)]
pub(crate) struct TileTable {
    pub rect: TileRect,
    pub raw: Vec<f32>,
    pub kinds: Vec<TileKind>,
    pub biomes: Vec<Biome>,
    pub hydrology: Option<Hydrology>,
}

impl TileTable {
    /// Row-major index of an in-map tile.
    #[inline]
    pub fn index(&self, terrain: &Terrain, tile: Hex) -> Option<usize> {
        self.index_of(terrain.offset_of(terrain.wrap_tile(tile)))
    }

    /// Row-major index of an offset coordinate in the map.
    #[inline]
    pub fn index_of(&self, [c, r]: [i32; 2]) -> Option<usize> {
        let rect = self.rect;
        rect.contains([c, r]).then(|| (r - rect.min[1]) as usize * self.cols() + (c - rect.min[0]) as usize)
    }

    /// Number of columns.
    #[inline]
    pub fn cols(&self) -> usize {
        (self.rect.max[0] - self.rect.min[0]) as usize
    }

    /// Builds the table of a bounded map: one height sample a tile, then the water network and
    /// the biomes.
    pub fn build(terrain: &Terrain, rect: TileRect) -> Self {
        let tiles: Vec<Hex> = rect.iter().map(|oc| terrain.tile_from_offset(oc)).collect();
        let centers: Vec<Hex> = tiles.iter().map(|&t| terrain.lattice().tile_center(t)).collect();
        let mut noise = vec![0.0; centers.len()];
        terrain.base_heights(&centers, &mut noise);
        let raw: Vec<f32> = noise.iter().zip(&centers).map(|(&n, &p)| terrain.shaped(n, p)).collect();
        let kinds: Vec<TileKind> = raw.iter().map(|&h| terrain.thresholds().classify(h)).collect();
        let mut table = Self { rect, raw, kinds, biomes: Vec::new(), hydrology: None };
        let samples: Vec<TileSample> = tiles.iter().enumerate().map(|(i, &t)| table.sample(terrain, i, t)).collect();
        // Each land tile's climate, once: rain and biome both read it.
        let climates: Vec<Option<Climate>> = tiles
            .iter()
            .zip(&samples)
            .map(|(&t, s)| (terrain.climate.is_some() && s.kind != TileKind::Sea).then(|| terrain.climate_of(t, s)))
            .collect();
        if terrain.config().rivers.enabled {
            let sea = terrain.thresholds().sea;
            let rain: Vec<f32> = samples
                .iter()
                .zip(&climates)
                .map(|(s, c)| {
                    // Wetter and higher tiles get more rain (air rising over relief rains out), so
                    // rivers rise on high, wet ground; the floor makes every land tile add water,
                    // so flow grows strictly downstream.
                    let relief = 0.5 + ((s.raw - sea) / (1.0 - sea).max(f32::EPSILON)).clamp(0.0, 1.0);
                    match (s.kind, c) {
                        (TileKind::Sea, _) => 0.0,
                        (_, Some(c)) => (0.05 + 0.95 * c.moisture) * relief,
                        (_, None) => relief,
                    }
                })
                .collect();
            table.hydrology = Some(Hydrology::build(terrain, &table, &tiles, &rain));
        }
        table.biomes = samples
            .iter()
            .zip(climates)
            .enumerate()
            .map(|(i, (s, climate))| {
                let lake = table.hydrology.as_ref().is_some_and(|h| h.lake_of(i).is_some());
                terrain.biome_from(s, lake, climate)
            })
            .collect();
        table
    }

    /// Tile `i`'s sample, its neighbors' kinds read from the table.
    fn sample(&self, terrain: &Terrain, i: usize, tile: Hex) -> TileSample {
        let neighbors = tile.all_neighbors().map(|nb| self.index(terrain, nb).map(|j| self.kinds[j]));
        TileSample::new(self.raw[i], self.kinds[i], neighbors)
    }
}
