//! Climate, a stage of the per-map tile table: each tile's temperature and moisture, and the biome they give with its relief kind.
//!
//! Temperature comes from latitude on a bounded map (the middle row is the equator, the first
//! and last rows the poles, bent by a low-frequency field) and from a very low-frequency field
//! on an unbounded one, and falls with elevation. Moisture is a second fBm with its own seed and
//! scale, wetter next to the sea. The biome table of the config maps both to a land or mountain
//! biome; sea tiles are coast next to land and ocean elsewhere; lake tiles come from
//! the water network ([`crate::water`]). All of it is a pure function of the tile, read from the center sample, so
//! every chunk agrees.

use hexx::Hex;

use crate::config::{ClimateConfig, MapConfig, NoiseConfig};
use crate::geometry::Geometry;
use crate::heights::{Fbm, HeightField};
use crate::kind::Thresholds;
use crate::ruleset::{Landform, TileFacts};
pub use crate::vocab::{Biome, TileKind};

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

/// Moisture per unit of rain from the winds (rain about 1 on a windward coast).
const RAIN_TO_MOISTURE: f32 = 0.9;

/// Where the temperature field is read in the moisture fBm's space, away from moisture.
pub(crate) const TEMPERATURE_SHIFT: f64 = 7.0e4;

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
        let temperature = NoiseConfig { scale: c.temperature_scale, ..c.moisture.clone() };
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

/// The biome of a land or mountain tile from its sample and climate, by the config's biome
/// table: the rule covering its climate for its kind, or hills where a land tile (not snow or
/// tundra) lies high enough up the land range. Flat maps and globes alike.
pub(crate) fn biome_by_table(c: &ClimateConfig, thresholds: &Thresholds, s: &TileSample, climate: Climate) -> Biome {
    let found = c
        .biomes
        .iter()
        .find(|rule| rule.relief == s.kind && rule.covers(climate.temperature, climate.moisture))
        .map_or(Biome::of_kind(s.kind), |rule| rule.biome);
    if s.kind == TileKind::Land && !matches!(found, Biome::Snow | Biome::Tundra) {
        let (sea, mountain) = (thresholds.sea, thresholds.mountain);
        if (s.raw - sea) >= c.hills * (mountain - sea) && c.hills < 1.0 {
            return Biome::Hills;
        }
    }
    found
}

/// Spreads an fBm value (which gathers around 0.5) over `[0, 1]`.
#[inline]
pub(crate) fn stretch(v: f64, by: f64) -> f32 {
    (((v - 0.5) * by) + 0.5).clamp(0.0, 1.0) as f32
}

/// What the biome of a tile is decided from: its center's raw height and kind, and whether a
/// neighbor in the map is sea or land.
#[derive(Debug, Clone, Copy)]
pub struct TileSample {
    /// Raw height of its center.
    pub raw: f32,
    /// Its kind.
    pub kind: TileKind,
    /// Whether a neighbor in the map is sea.
    pub next_to_sea: bool,
    /// Whether a neighbor in the map is land or mountain.
    pub next_to_land: bool,
}

impl TileSample {
    /// A tile's sample from its center's raw height and kind and its neighbors' kinds (`None`
    /// outside the map).
    #[must_use]
    pub fn new(raw: f32, kind: TileKind, neighbors: impl IntoIterator<Item = Option<TileKind>>) -> Self {
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

impl TileSample {
    /// The center sample of a tile and its neighbors' kinds, computed from the height field.
    #[must_use]
    pub fn of(geometry: &Geometry, heights: &HeightField, thresholds: &Thresholds, tile: Hex) -> Self {
        let raw = heights.raw_height(geometry, geometry.lattice().tile_center(tile));
        let neighbors = tile.all_neighbors().map(|nb| thresholds.map_tile_kind(geometry, heights, nb));
        Self::new(raw, thresholds.classify(raw), neighbors)
    }
}

/// The climate stage: the climate's noise fields and biome table, and the thresholds that place
/// a tile in the land range. Without a climate in the config, biomes follow the relief kind.
#[derive(Debug, Clone)]
pub struct ClimateModel {
    fields: Option<ClimateFields>,
    config: ClimateConfig,
    thresholds: Thresholds,
}

impl ClimateModel {
    /// The climate of a validated config over `geometry`.
    #[must_use]
    pub fn new(config: &MapConfig, geometry: &Geometry, thresholds: Thresholds) -> Self {
        let fields = config.climate.enabled.then(|| {
            let wrap_width = geometry.wrap().map(|w| w.width / geometry.hex_size());
            ClimateFields::new(config, wrap_width)
        });
        Self { fields, config: config.climate.clone(), thresholds }
    }

    /// The climate's winds, when it has them.
    #[must_use]
    pub fn winds(&self) -> Option<&crate::config::WindConfig> {
        self.fields.as_ref().and(self.config.winds.as_ref())
    }

    /// The latitudes of the map's first and last rows ([`ClimateConfig::latitudes`]).
    #[must_use]
    pub(crate) fn latitudes(&self) -> (f32, f32) {
        self.config.latitudes
    }

    /// Whether the map has a climate.
    #[must_use]
    pub fn is_enabled(&self) -> bool {
        self.fields.is_some()
    }

    /// Temperature and moisture of a tile from its sample (0.5 each without a climate).
    #[must_use]
    pub fn climate_of(&self, geometry: &Geometry, heights: &HeightField, tile: Hex, s: &TileSample) -> Climate {
        match self.fields_at(geometry, heights, tile) {
            Some(fields) => self.climate_with(geometry, tile, s, fields),
            None => Climate { temperature: 0.5, moisture: 0.5 },
        }
    }

    /// The climate's noise at a tile's center, `[temperature field, moisture]`: what depends on
    /// the tile's position alone (no edit changes it); `None` without a climate.
    #[must_use]
    pub fn fields_at(&self, geometry: &Geometry, heights: &HeightField, tile: Hex) -> Option<[f64; 2]> {
        let fields = self.fields.as_ref()?;
        let [ux, uz] = heights.noise_position(geometry, geometry.lattice().tile_center(tile));
        Some([fields.temperature(ux, uz), fields.moisture.sample(ux, uz)])
    }

    /// Temperature and moisture of a tile from its sample and its noise ([`fields_at`](Self::fields_at)).
    #[must_use]
    pub fn climate_with(&self, geometry: &Geometry, tile: Hex, s: &TileSample, [field, wet]: [f64; 2]) -> Climate {
        let mut moisture = stretch(wet, 2.4);
        if s.next_to_sea {
            moisture = (moisture + self.config.coast_moisture).min(1.0);
        }
        Climate { temperature: self.temperature(geometry, tile, s, field), moisture }
    }

    /// Temperature and moisture of a tile on a map with winds, from its sample, its noise and
    /// the rain the winds bring it ([`winds::rainfall`]): the moisture is the rain's, moved up
    /// or down by the moisture fBm (by up to half of `variety`) for local variety.
    pub(crate) fn climate_with_rain(
        &self,
        geometry: &Geometry,
        tile: Hex,
        s: &TileSample,
        [field, wet]: [f64; 2],
        rain: f32,
    ) -> Climate {
        let variety = self.config.winds.as_ref().map_or(0.0, |w| w.variety);
        let moisture = rain * RAIN_TO_MOISTURE + variety * (stretch(wet, 2.4) - 0.5);
        Climate { temperature: self.temperature(geometry, tile, s, field), moisture: moisture.clamp(0.0, 1.0) }
    }

    /// A tile's temperature: from its latitude on a bounded map (bent by the temperature
    /// field; with winds, by the sun's height), from the field on an unbounded one, cooler the
    /// higher it lies.
    fn temperature(&self, geometry: &Geometry, tile: Hex, s: &TileSample, field: f64) -> f32 {
        let c = &self.config;
        let base = match geometry.bounds() {
            Some(bounds) => {
                let (latitude, _) = winds::latitude(bounds, geometry.offset_of(tile)[1], c.latitudes);
                // With winds, halfway to the sun's height (the cosine of the latitude): the
                // tropics stay hot out to the horse latitudes, where the deserts lie, and the
                // middle latitudes cool faster.
                let sun = match c.winds {
                    Some(_) => 0.5 * ((latitude * std::f32::consts::FRAC_PI_2).cos() + 1.0 - latitude),
                    None => 1.0 - latitude,
                };
                sun + c.temperature_jitter * (2.0 * field as f32 - 1.0)
            }
            None => stretch(field, 3.0),
        };
        let sea = self.thresholds.sea;
        let above = ((s.raw - sea) / (1.0 - sea).max(f32::EPSILON)).max(0.0);
        (base - c.lapse_rate * above).clamp(0.0, 1.0)
    }

    /// The climate a tile's biome needs: `None` without a climate, and for sea and lake tiles.
    #[must_use]
    pub fn climate_for_biome(
        &self,
        geometry: &Geometry,
        heights: &HeightField,
        tile: Hex,
        s: &TileSample,
        lake: bool,
    ) -> Option<Climate> {
        (self.is_enabled() && !lake && s.kind != TileKind::Sea).then(|| self.climate_of(geometry, heights, tile, s))
    }

    /// The biome of a tile from its sample; `lake` from the hydrology.
    #[must_use]
    pub fn biome_of(&self, geometry: &Geometry, heights: &HeightField, tile: Hex, s: &TileSample, lake: bool) -> Biome {
        self.biome_from(s, lake, self.climate_for_biome(geometry, heights, tile, s, lake))
    }

    /// The biome of a tile from its sample and climate (`None` when the map has none, or when
    /// the tile is sea or lake, which need none).
    #[must_use]
    pub fn biome_from(&self, s: &TileSample, lake: bool, climate: Option<Climate>) -> Biome {
        if lake {
            return Biome::Lake;
        }
        if !self.is_enabled() {
            return Biome::of_kind(s.kind);
        }
        if s.kind == TileKind::Sea {
            return if s.next_to_land { Biome::Coast } else { Biome::Ocean };
        }
        let Some(climate) = climate else { return Biome::of_kind(s.kind) };
        biome_by_table(&self.config, &self.thresholds, s, climate)
    }
}

impl ClimateModel {
    /// Where a tile lies ([`Landform`]): a lake tile; sea next to land (the shore) or away from
    /// it; a mountain; land above the hills line (on a map with a climate, when
    /// [`ClimateConfig::hills`](crate::ClimateConfig::hills) is under 1) or below it.
    #[must_use]
    pub fn landform(&self, s: &TileSample, lake: bool) -> Landform {
        landform(
            s,
            lake,
            (self.thresholds.sea, self.thresholds.mountain),
            self.is_enabled().then_some(self.config.hills),
        )
    }

    /// What a ruleset decides a tile's terrain and feature from: its landform, its climate
    /// (`None`: mid temperature and moisture), its center's height within its kind's band, its
    /// latitude (0.5 on a map without bounds), and `(near_water, near_river)`: whether a
    /// neighbor is sea or lake, whether a river runs through it or on one of its edges.
    #[must_use]
    pub fn facts(
        &self,
        geometry: &Geometry,
        tile: Hex,
        s: &TileSample,
        lake: bool,
        climate: Option<Climate>,
        (near_water, near_river): (bool, bool),
    ) -> TileFacts {
        let (sea, mountain) = (self.thresholds.sea, self.thresholds.mountain);
        let band = |lo: f32, hi: f32| ((s.raw - lo) / (hi - lo).max(f32::EPSILON)).clamp(0.0, 1.0);
        let elevation = match s.kind {
            TileKind::Sea => band(0.0, sea),
            TileKind::Land => band(sea, mountain),
            TileKind::Mountain => band(mountain, 1.0),
        };
        let latitude = geometry
            .bounds()
            .map_or(0.5, |rect| winds::latitude(rect, geometry.offset_of(tile)[1], self.config.latitudes).0);
        let climate = climate.unwrap_or(Climate { temperature: 0.5, moisture: 0.5 });
        TileFacts {
            landform: self.landform(s, lake),
            temperature: climate.temperature,
            moisture: climate.moisture,
            elevation,
            latitude: latitude.clamp(0.0, 1.0),
            near_water,
            near_river,
            climate: self.is_enabled(),
        }
    }
}

/// Where a tile lies (see [`ClimateModel::landform`]), with the sea and mountain thresholds
/// and, on a map with a climate, the hills line
/// ([`ClimateConfig::hills`](crate::ClimateConfig::hills)): a flat map's and a globe's rule.
pub(crate) fn landform(s: &TileSample, lake: bool, (sea, mountain): (f32, f32), hills: Option<f32>) -> Landform {
    match s.kind {
        _ if lake => Landform::Lake,
        TileKind::Sea if s.next_to_land => Landform::Shore,
        TileKind::Sea => Landform::OpenSea,
        TileKind::Mountain => Landform::Mountain,
        TileKind::Land => match hills {
            Some(hills) if hills < 1.0 && (s.raw - sea) >= hills * (mountain - sea) => Landform::Hills,
            _ => Landform::Flat,
        },
    }
}

#[cfg(test)]
mod tests;
pub(crate) mod winds;
