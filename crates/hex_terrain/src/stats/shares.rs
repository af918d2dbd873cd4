//! The shares and counts a map type's targets and the survey read from [`MapStats`].

use super::{IN_LINE, Landmass, LandmassKind, MapStats};
use crate::vocab::Biome;

impl MapStats {
    /// Water's share of the map's tiles (sea and lakes).
    #[must_use]
    pub fn water_share(&self) -> f64 {
        f64::from(self.sea_tiles + self.lake_tiles) / f64::from(self.tiles.max(1))
    }

    /// Land's share of the map's tiles.
    #[must_use]
    pub fn land_share(&self) -> f64 {
        f64::from(self.land_tiles) / f64::from(self.tiles.max(1))
    }

    /// Of the pairs of continents, the share whose centers lie in line: within
    /// [`IN_LINE`] tiles of each other's row or column (round the map on a wrapping map,
    /// [`MapStats::wrap_columns`]). Continents set out on a grid are mostly in line (a 3 by 2 grid: 9 pairs of 15);
    /// placed at random, one pair in ten or so. 0 with fewer than two continents.
    #[must_use]
    pub fn continents_in_line(&self) -> f64 {
        let centers: Vec<[f64; 2]> = self.continents().map(|c| c.center).collect();
        let (mut pairs, mut in_line) = (0_u32, 0_u32);
        for (k, a) in centers.iter().enumerate() {
            for b in &centers[k + 1..] {
                let dx = (a[0] - b[0]).abs();
                let dx = self.wrap_columns.map_or(dx, |columns| dx.min(f64::from(columns) - dx));
                pairs += 1;
                in_line += u32::from(dx < IN_LINE || (a[1] - b[1]).abs() < IN_LINE);
            }
        }
        if pairs == 0 { 0.0 } else { f64::from(in_line) / f64::from(pairs) }
    }

    /// The continents, largest first.
    pub fn continents(&self) -> impl Iterator<Item = &Landmass> {
        self.landmasses.iter().filter(|m| m.kind == LandmassKind::Continent)
    }

    /// The islands, largest first.
    pub fn islands(&self) -> impl Iterator<Item = &Landmass> {
        self.landmasses.iter().filter(|m| m.kind == LandmassKind::Island)
    }

    /// The largest landmass' share of the land (0 without land).
    #[must_use]
    pub fn largest_landmass_share(&self) -> f64 {
        self.landmasses.first().map_or(0.0, |m| f64::from(m.tiles) / f64::from(self.land_tiles.max(1)))
    }

    /// Mountains' share of the land.
    #[must_use]
    pub fn mountain_share(&self) -> f64 {
        f64::from(self.mountain_tiles) / f64::from(self.land_tiles.max(1))
    }

    /// How many mountain neighbors a mountain tile has on average (0 without mountains): about
    /// 2 when the mountains run in chains, more in massifs.
    #[must_use]
    pub fn mountain_neighbors(&self) -> f64 {
        f64::from(self.mountain_adjacencies) / f64::from(self.mountain_tiles.max(1))
    }

    /// Snow, tundra and snow peaks' share of the land (0 without land): how much of it is cold.
    #[must_use]
    pub fn cold_share(&self) -> f64 {
        let cold: u32 = [Biome::Snow, Biome::Tundra, Biome::SnowPeak].map(|b| self.biome_tiles(b)).iter().sum();
        f64::from(cold) / f64::from(self.land_tiles.max(1))
    }

    /// A land biome's share of the land (0 without land or without the biome).
    #[must_use]
    pub fn biome_share(&self, biome: Biome) -> f64 {
        f64::from(self.biome_tiles(biome)) / f64::from(self.land_tiles.max(1))
    }

    /// Tiles of a biome.
    fn biome_tiles(&self, biome: Biome) -> u32 {
        self.biomes.iter().find(|&&(b, _)| b == biome).map_or(0, |&(_, n)| n)
    }

    /// The polar rows' land, as a share of the land ([`MapStats::polar_land_tiles`]).
    #[must_use]
    pub fn polar_land_share(&self) -> f64 {
        f64::from(self.polar_land_tiles) / f64::from(self.land_tiles.max(1))
    }

    /// Mountains in blobs, as a share of the mountains ([`MapStats::blob_mountains`]).
    #[must_use]
    pub fn blob_share(&self) -> f64 {
        f64::from(self.blob_mountains) / f64::from(self.mountain_tiles.max(1))
    }

    /// Lake tiles' share of the land.
    #[must_use]
    pub fn lake_share(&self) -> f64 {
        f64::from(self.lake_tiles) / f64::from(self.land_tiles.max(1))
    }

    /// Lakes per 1,000 land tiles.
    #[must_use]
    pub fn lakes_per_thousand(&self) -> f64 {
        f64::from(self.lakes) * 1000.0 / f64::from(self.land_tiles.max(1))
    }

    /// The share of the land on a river ([`RiverStats::tiles`](super::RiverStats::tiles)).
    #[must_use]
    pub fn river_share(&self) -> f64 {
        f64::from(self.rivers.tiles) / f64::from(self.land_tiles.max(1))
    }

    /// The share of the sources within 2 tiles of relief (0 without a river).
    #[must_use]
    pub fn sources_near_relief_share(&self) -> f64 {
        f64::from(self.rivers.sources_near_relief) / f64::from(self.rivers.sources.max(1))
    }

    /// Landmasses of at least `min_tiles` tiles with no tile on a river.
    #[must_use]
    pub fn landmasses_without_river(&self, min_tiles: u32) -> usize {
        self.landmasses.iter().filter(|m| m.tiles >= min_tiles && m.river_tiles == 0).count()
    }

    /// The share of mountain tiles that lie in ranges (0 without mountains).
    #[must_use]
    pub fn range_share(&self) -> f64 {
        f64::from(self.range_tiles) / f64::from(self.mountain_tiles.max(1))
    }
}
