//! Climate: each tile's temperature and moisture, and the biome they give with its relief kind.
//!
//! Temperature comes from latitude on a bounded map (the middle row is the equator, the first
//! and last rows the poles, bent by a low-frequency field) and from a very low-frequency field
//! on an unbounded one, and falls with elevation. Moisture is a second fBm with its own seed and
//! scale, wetter next to the sea. The biome table of the config maps both to a land or mountain
//! biome; sea tiles are coast next to land and ocean elsewhere; lake tiles come from
//! [`hydrology`]. All of it is a pure function of the tile, read from the center sample, so
//! every chunk agrees.

pub mod hydrology;
mod table;
mod water;

use hexx::Hex;
use serde::{Deserialize, Serialize};

pub use hydrology::{Hydrology, RiverTile};
pub(crate) use table::TileTable;

use crate::config::MapConfig;
use crate::heights::Fbm;
use crate::kind::TileKind;
use crate::terrain::Terrain;

/// A tile's biome: the relief kind refined by climate and water.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[repr(u8)]
pub enum Biome {
    /// Deep sea, away from land.
    Ocean = 0,
    /// Shallow sea next to land.
    Coast,
    /// Water above sea level, filling a depression.
    Lake,
    /// Hot and dry land.
    Desert,
    /// Dry or temperate open land.
    Plains,
    /// Temperate, moist open land.
    Grassland,
    /// Temperate, wet land.
    Forest,
    /// Hot, wet land.
    Rainforest,
    /// Cold land.
    Tundra,
    /// The coldest land.
    Snow,
    /// High land (the upper part of the land range).
    Hills,
    /// Bare mountains.
    Rock,
    /// Cold mountains.
    SnowPeak,
}

impl Biome {
    /// Every biome, in discriminant order.
    pub const ALL: [Self; 13] = [
        Self::Ocean,
        Self::Coast,
        Self::Lake,
        Self::Desert,
        Self::Plains,
        Self::Grassland,
        Self::Forest,
        Self::Rainforest,
        Self::Tundra,
        Self::Snow,
        Self::Hills,
        Self::Rock,
        Self::SnowPeak,
    ];

    /// Lower-case name.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Ocean => "ocean",
            Self::Coast => "coast",
            Self::Lake => "lake",
            Self::Desert => "desert",
            Self::Plains => "plains",
            Self::Grassland => "grassland",
            Self::Forest => "forest",
            Self::Rainforest => "rainforest",
            Self::Tundra => "tundra",
            Self::Snow => "snow",
            Self::Hills => "hills",
            Self::Rock => "rock",
            Self::SnowPeak => "snow peak",
        }
    }

    /// Its color in the meshes' vertex colors and the CLI's renders (sRGB).
    #[must_use]
    pub fn color(self) -> [u8; 3] {
        match self {
            Self::Ocean => [30, 66, 128],
            Self::Coast => [62, 136, 182],
            Self::Lake => [52, 118, 176],
            Self::Desert => [224, 202, 142],
            Self::Plains => [184, 182, 98],
            Self::Grassland => [104, 164, 66],
            Self::Forest => [42, 110, 50],
            Self::Rainforest => [22, 88, 42],
            Self::Tundra => [150, 148, 122],
            Self::Snow => [238, 242, 246],
            Self::Hills => [138, 142, 82],
            Self::Rock => [122, 112, 104],
            Self::SnowPeak => [228, 234, 242],
        }
    }

    /// Whether it is water (ocean, coast, lake).
    #[must_use]
    pub fn is_water(self) -> bool {
        matches!(self, Self::Ocean | Self::Coast | Self::Lake)
    }

    /// Whether the biome is bare rock or a snow peak (the mountain biomes).
    #[must_use]
    pub fn is_rocky(self) -> bool {
        matches!(self, Self::Rock | Self::SnowPeak)
    }

    /// The biome a tile of `kind` has when the map has no climate.
    #[must_use]
    pub fn of_kind(kind: TileKind) -> Self {
        match kind {
            TileKind::Sea => Self::Ocean,
            TileKind::Land => Self::Grassland,
            TileKind::Mountain => Self::Rock,
        }
    }
}

/// A tile's climate, both in `[0, 1]`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct Climate {
    /// 0 coldest, 1 hottest.
    pub temperature: f32,
    /// 0 driest, 1 wettest.
    pub moisture: f32,
}

/// The noise fields climate samples: one fBm (one permutation table to build), read at the
/// moisture scale for moisture and, far from there, at the temperature scale for temperature.
#[derive(Debug, Clone)]
pub(crate) struct ClimateFields {
    moisture: Fbm,
    /// Temperature positions are moisture positions times this.
    temperature_zoom: f64,
    /// On a wrapping map, temperature's own fBm, periodic over the map like moisture's (the
    /// zoomed moisture field would not be).
    wrapped_temperature: Option<Fbm>,
}

/// Where the temperature field is read in the moisture fBm's space, away from moisture.
const TEMPERATURE_SHIFT: f64 = 7.0e4;

impl ClimateFields {
    /// The fields of a map; `wrap_width` is a wrapping map's width in hex radii.
    pub(crate) fn new(config: &MapConfig, wrap_width: Option<f64>) -> Self {
        let c = &config.climate;
        let seed = config.seed.wrapping_add(c.moisture_seed);
        let Some(width) = wrap_width else {
            return Self {
                moisture: Fbm::new(seed, &c.moisture),
                temperature_zoom: c.moisture.scale / c.temperature_scale,
                wrapped_temperature: None,
            };
        };
        let temperature = crate::config::NoiseConfig { scale: c.temperature_scale, ..c.moisture.clone() };
        Self {
            moisture: Fbm::wrapped(seed, &c.moisture, width),
            temperature_zoom: 1.0,
            wrapped_temperature: Some(Fbm::wrapped(seed.wrapping_add(1), &temperature, width)),
        }
    }

    fn temperature(&self, x: f64, z: f64) -> f64 {
        if let Some(fbm) = &self.wrapped_temperature {
            return fbm.sample(x, z);
        }
        let k = self.temperature_zoom;
        self.moisture.sample(x * k + TEMPERATURE_SHIFT, z * k - TEMPERATURE_SHIFT)
    }
}

/// Spreads an fBm value (which gathers around 0.5) over `[0, 1]`.
#[inline]
fn stretch(v: f64, by: f64) -> f32 {
    (((v - 0.5) * by) + 0.5).clamp(0.0, 1.0) as f32
}

/// What the biome of a tile is decided from: its center's raw height and kind, and whether a
/// neighbor in the map is sea or land.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TileSample {
    pub raw: f32,
    pub kind: TileKind,
    pub next_to_sea: bool,
    pub next_to_land: bool,
}

impl TileSample {
    /// A tile's sample from its center's raw height and kind and its neighbors' kinds (`None`
    /// outside the map).
    pub(crate) fn new(raw: f32, kind: TileKind, neighbors: impl IntoIterator<Item = Option<TileKind>>) -> Self {
        let (mut next_to_sea, mut next_to_land) = (false, false);
        for nb in neighbors {
            match nb {
                Some(TileKind::Sea) => next_to_sea = true,
                Some(_) => next_to_land = true,
                None => {}
            }
        }
        Self { raw, kind, next_to_sea, next_to_land }
    }
}

impl Terrain {
    /// Temperature and moisture of a tile, `None` when the map has no climate.
    #[must_use]
    pub fn tile_climate(&self, tile: Hex) -> Option<Climate> {
        self.climate.as_ref()?;
        Some(self.climate_of(tile, &self.tile_sample(tile)))
    }

    /// A tile's biome (from the relief kind alone when the map has no climate; lake tiles are
    /// [`Biome::Lake`] whether or not it has).
    #[must_use]
    pub fn tile_biome(&self, tile: Hex) -> Biome {
        if let Some(table) = &self.table
            && let Some(i) = table.index(self, tile)
        {
            return table.biomes[i];
        }
        let sample = self.tile_sample(tile);
        self.biome_of(tile, &sample, false)
    }

    /// The center sample of a tile and its neighbors' kinds.
    pub(crate) fn tile_sample(&self, tile: Hex) -> TileSample {
        let raw = self.raw_height(self.lattice.tile_center(tile));
        TileSample::new(raw, self.thresholds.classify(raw), tile.all_neighbors().map(|nb| self.map_tile_kind(nb)))
    }

    /// Temperature and moisture of a tile from its sample (climate must be on).
    pub(crate) fn climate_of(&self, tile: Hex, s: &TileSample) -> Climate {
        let Some(fields) = &self.climate else {
            return Climate { temperature: 0.5, moisture: 0.5 };
        };
        let c = &self.config.climate;
        let [ux, uz] = self.noise_position(self.lattice.tile_center(tile));
        let field = fields.temperature(ux, uz);
        let base = match self.bounds {
            Some(bounds) => {
                let rows = (bounds.max[1] - bounds.min[1]).max(1) as f32;
                let row = self.offset_of(tile)[1] as f32;
                let latitude = ((row + 0.5) / rows - 0.5).abs() * 2.0;
                1.0 - latitude + c.temperature_jitter * (2.0 * field as f32 - 1.0)
            }
            None => stretch(field, 3.0),
        };
        let sea = self.thresholds.sea;
        let above = ((s.raw - sea) / (1.0 - sea).max(f32::EPSILON)).max(0.0);
        let temperature = (base - c.lapse_rate * above).clamp(0.0, 1.0);
        let mut moisture = stretch(fields.moisture.sample(ux, uz), 2.4);
        if s.next_to_sea {
            moisture = (moisture + c.coast_moisture).min(1.0);
        }
        Climate { temperature, moisture }
    }

    /// The biome of a tile from its sample; `lake` from the hydrology.
    pub(crate) fn biome_of(&self, tile: Hex, s: &TileSample, lake: bool) -> Biome {
        let climate = (self.climate.is_some() && !lake && s.kind != TileKind::Sea).then(|| self.climate_of(tile, s));
        self.biome_from(s, lake, climate)
    }

    /// The biome of a tile from its sample and climate (`None` when the map has none, or when
    /// the tile is sea or lake, which need none).
    pub(crate) fn biome_from(&self, s: &TileSample, lake: bool, climate: Option<Climate>) -> Biome {
        if lake {
            return Biome::Lake;
        }
        if self.climate.is_none() {
            return Biome::of_kind(s.kind);
        }
        if s.kind == TileKind::Sea {
            return if s.next_to_land { Biome::Coast } else { Biome::Ocean };
        }
        let Some(climate) = climate else { return Biome::of_kind(s.kind) };
        let c = &self.config.climate;
        let found = c
            .biomes
            .iter()
            .find(|rule| rule.relief == s.kind && rule.covers(climate.temperature, climate.moisture))
            .map_or(Biome::of_kind(s.kind), |rule| rule.biome);
        if s.kind == TileKind::Land && !matches!(found, Biome::Snow | Biome::Tundra) {
            let (sea, mountain) = (self.thresholds.sea, self.thresholds.mountain);
            if (s.raw - sea) >= c.hills * (mountain - sea) && c.hills < 1.0 {
                return Biome::Hills;
            }
        }
        found
    }
}

#[cfg(test)]
mod tests;
