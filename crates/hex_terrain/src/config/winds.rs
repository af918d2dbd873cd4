//! Prevailing winds, the climate's `winds` settings: where they blow from and how they carry
//! and drop the rain. The step that computes the rain is `crate::climate::winds`.

use serde::{Deserialize, Serialize};

use super::MAX_WATER_TILES;

/// Prevailing winds and the rain they bring (the climate's `winds`). Air picks up humidity
/// over the sea and carries it downwind; over land a share of it rains out every tile, and
/// where the land rises above what the air can hold the excess rains out on the slope, so the
/// land behind a range (its lee) is drier: a rain shadow. Where the bands' winds meet the air
/// rises and rains more, where they part it sinks and rains less (the horse latitudes).
///
/// The numbers follow Red Blob Games' mapgen4 (`assignRainfall`: evaporation 0.5, raininess
/// 0.9, rain shadow 0.5); the bands follow Earth's three cells, as Azgaar's Fantasy Map
/// Generator blows them.
///
/// ```
/// use hex_terrain::{MapConfig, Terrain, WindPattern};
///
/// let config = MapConfig::from_ron(
///     "(size: Bounded(x: 40, z: 24), climate: (enabled: true, winds: Some((pattern: One(270)))))",
/// )
/// .unwrap();
/// assert_eq!(config.climate.winds.as_ref().unwrap().pattern, WindPattern::One(270.0));
/// let terrain = Terrain::new(config).unwrap();
/// assert!(terrain.tile_climate(terrain.tile_from_offset([5, 5])).is_some());
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct WindConfig {
    /// Where the winds blow from.
    pub pattern: WindPattern,
    /// Humidity the air picks up over a sea tile, in `[0, 1]` (air holds at most 1).
    pub evaporation: f32,
    /// Share of the air's humidity that rains on a land tile, in `[0, 1]` (rain does not dry
    /// the air: `drying` does).
    pub raininess: f32,
    /// Share of the humidity above what the air holds over a tile (1 at sea level, a quarter
    /// halfway up the land's range, 0 at its top) that rains out there, in `[0, 1]`: the rain
    /// shadow's strength.
    pub rain_shadow: f32,
    /// Share of its humidity the air loses over each land tile, in `[0, 1]`, so the middle of
    /// a large continent is drier than its coasts.
    pub drying: f32,
    /// How much more it rains where the bands' winds meet (rising air) and less where they
    /// part (sinking air), in `[0, 1]`.
    pub uplift: f32,
    /// How far the moisture fBm moves a tile's moisture from its rain's, for local variety, in
    /// `[0, 1]`: up or down by at most half of it.
    pub variety: f32,
}

impl Default for WindConfig {
    fn default() -> Self {
        Self {
            pattern: WindPattern::default(),
            evaporation: 0.5,
            raininess: 0.9,
            rain_shadow: 0.5,
            drying: 0.03,
            uplift: 0.5,
            variety: 0.3,
        }
    }
}

/// Most latitude bands of a [`WindPattern::Bands`].
pub const MAX_WIND_BANDS: usize = 8;

/// Where the winds blow from, as bearings in degrees clockwise from north (north is `-z`,
/// the map's first row; 90 is east), the way the light's sun is given.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum WindPattern {
    /// Bands of equal width from the equator (the map's middle row) to each pole, each with
    /// the bearing its wind blows from in the northern half; the southern half mirrors them
    /// north to south. The default is Earth's: north-east trade winds (45), westerlies from
    /// the south-west (225) and polar easterlies (45).
    Bands(Vec<f32>),
    /// One bearing over the whole map.
    One(f32),
}

impl Default for WindPattern {
    fn default() -> Self {
        Self::Bands(vec![45.0, 225.0, 45.0])
    }
}

impl super::MapConfig {
    /// Checks `climate.winds` (part of [`super::MapConfig::validate`]).
    pub(super) fn validate_winds(&self, w: &WindConfig) -> Result<(), crate::error::ConfigError> {
        use super::check::{check, finite_in};
        check(
            self.climate.enabled,
            "climate.winds",
            "Some on a map without climate",
            "None, or climate.enabled: true (the winds bring the climate's moisture)",
        )?;
        match self.size.bounds() {
            None => check(
                false,
                "climate.winds",
                "Some on an Unbounded map",
                "None on an Unbounded map (a tile's rain depends on every tile upwind, which no chunk sees): use a \
                 Bounded size",
            )?,
            Some((x, z)) => {
                let tiles = u64::from(x) * u64::from(z);
                check(
                    tiles <= MAX_WATER_TILES,
                    "climate.winds",
                    format!("Some on a {x}x{z} map ({tiles} tiles)"),
                    format!(
                        "None on maps of more than {MAX_WATER_TILES} tiles (the rain of a whole map is computed at once)"
                    ),
                )?;
            }
        }
        let bearing = |v: f32| v.is_finite() && (0.0..360.0).contains(&v);
        match &w.pattern {
            WindPattern::Bands(bands) => {
                check(
                    (1..=MAX_WIND_BANDS).contains(&bands.len()),
                    "climate.winds.pattern",
                    format!("{} bands", bands.len()),
                    format!("1 to {MAX_WIND_BANDS} bands"),
                )?;
                for (i, &b) in bands.iter().enumerate() {
                    check(bearing(b), &format!("climate.winds.pattern.Bands[{i}]"), b, "[0, 360) degrees")?;
                }
            }
            WindPattern::One(b) => check(bearing(*b), "climate.winds.pattern.One", b, "[0, 360) degrees")?,
        }
        let unit = |v: f32| finite_in(f64::from(v), 0.0, 1.0);
        for (name, v) in [
            ("evaporation", w.evaporation),
            ("raininess", w.raininess),
            ("rain_shadow", w.rain_shadow),
            ("drying", w.drying),
            ("uplift", w.uplift),
            ("variety", w.variety),
        ] {
            check(unit(v), &format!("climate.winds.{name}"), v, "[0, 1]")?;
        }
        Ok(())
    }
}
