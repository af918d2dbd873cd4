//! Climate and water settings: the biome table (Whittaker-style: temperature by moisture, per
//! relief kind), the fields temperature and moisture come from, and rivers and lakes.

use serde::{Deserialize, Serialize};

use super::NoiseConfig;
use super::winds::WindConfig;
use crate::vocab::{Biome, TileKind};

/// Temperature, moisture and biomes. Off by default: the thesis' maps have relief types only.
///
/// ```
/// use hex_terrain::{Biome, MapConfig, Terrain};
///
/// let config = MapConfig::from_ron("(size: Bounded(x: 24, z: 16), climate: (enabled: true))").unwrap();
/// let terrain = Terrain::new(config).unwrap();
/// let info = terrain.tile_info(terrain.tile_from_offset([5, 5])).unwrap();
/// // Without a ruleset of its own, a tile's terrain is one of the 13 biomes.
/// let biome = terrain.ruleset().biome(info.terrain.terrain).unwrap();
/// assert!(Biome::ALL.contains(&biome));
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct ClimateConfig {
    /// Whether tiles get biomes (and meshes a color per vertex).
    pub enabled: bool,
    /// Added to the map seed for the moisture field's permutation table.
    pub moisture_seed: u32,
    /// The moisture fBm (its `scale` in the same units as the height noise's).
    pub moisture: NoiseConfig,
    /// Moisture added to tiles next to sea, in `[0, 1]`.
    pub coast_moisture: f32,
    /// Unbounded maps: scale of the very low-frequency temperature field (same units as
    /// `noise.scale`); bounded maps take temperature from latitude.
    pub temperature_scale: f64,
    /// Bounded maps: how far (in temperature) a low-frequency field bends the latitude bands,
    /// in `[0, 1]`.
    pub temperature_jitter: f32,
    /// Bounded maps: the latitudes of the first and the last row's outer edges, each in
    /// `[-1, 1]` (1 the north pole, 0 the equator, -1 the south pole), different: `(1, -1)`,
    /// the default, is a world from pole to pole; `(0.6, -0.6)` a temperate and tropical
    /// region, as a regional map (Civilization V's Inland Sea) is. Temperature and the winds'
    /// bands follow them.
    pub latitudes: (f32, f32),
    /// Cooling from the sea threshold to the top of the relief, in temperature, in `[0, 2]`.
    pub lapse_rate: f32,
    /// Land tiles whose center lies this far up the land range (in `[0, 1]`) are hills;
    /// 1 turns hills off.
    pub hills: f32,
    /// Land and mountain biomes by temperature and moisture. For each of the two kinds the
    /// entries must cover `[0, 1] x [0, 1]` exactly once (half-open ranges, 1 included).
    pub biomes: Vec<BiomeRule>,
    /// Prevailing winds: moisture from the rain the winds bring from the sea, drier in the lee
    /// of high ground, instead of from the moisture fBm alone (which then adds local variety).
    /// Bounded maps (wrapping or not) of at most [`MAX_WATER_TILES`] tiles: the rain of a tile
    /// depends on every tile upwind, so it is computed once for the whole map. `None` (the
    /// default) keeps the moisture fBm's climate, unchanged.
    pub winds: Option<WindConfig>,
}

impl Default for ClimateConfig {
    fn default() -> Self {
        Self {
            enabled: false,
            moisture_seed: 7919,
            moisture: NoiseConfig { octaves: 4, persistence: 0.5, lacunarity: 2.0, scale: 160.0 },
            coast_moisture: 0.15,
            temperature_scale: 2000.0,
            temperature_jitter: 0.12,
            latitudes: (1.0, -1.0),
            lapse_rate: 0.3,
            hills: 0.7,
            biomes: BiomeRule::defaults(),
            winds: None,
        }
    }
}

/// One rectangle of the biome table: tiles of `relief` whose temperature and moisture fall in
/// the ranges get `biome`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(deny_unknown_fields)]
pub struct BiomeRule {
    /// The biome given.
    pub biome: Biome,
    /// Which relief kind it applies to (`Land` or `Mountain`; sea is ocean or coast by depth).
    pub relief: TileKind,
    /// Temperature range `[lo, hi)`, 0 coldest, 1 hottest.
    pub temperature: (f32, f32),
    /// Moisture range `[lo, hi)`, 0 driest, 1 wettest.
    pub moisture: (f32, f32),
}

impl BiomeRule {
    const fn new(biome: Biome, relief: TileKind, temperature: (f32, f32), moisture: (f32, f32)) -> Self {
        Self { biome, relief, temperature, moisture }
    }

    /// The default table: snow, tundra, desert, plains, grassland, forest and rainforest on
    /// land; snow peaks and rock on mountains.
    #[must_use]
    pub fn defaults() -> Vec<Self> {
        use Biome::*;
        use TileKind::{Land, Mountain};
        vec![
            Self::new(Snow, Land, (0.0, 0.12), (0.0, 1.0)),
            Self::new(Tundra, Land, (0.12, 0.27), (0.0, 1.0)),
            Self::new(Plains, Land, (0.27, 0.6), (0.0, 0.3)),
            Self::new(Desert, Land, (0.6, 1.0), (0.0, 0.3)),
            Self::new(Plains, Land, (0.27, 1.0), (0.3, 0.42)),
            Self::new(Grassland, Land, (0.27, 1.0), (0.42, 0.58)),
            Self::new(Forest, Land, (0.27, 0.68), (0.58, 1.0)),
            Self::new(Rainforest, Land, (0.68, 1.0), (0.58, 1.0)),
            Self::new(SnowPeak, Mountain, (0.0, 0.4), (0.0, 1.0)),
            Self::new(Rock, Mountain, (0.4, 1.0), (0.0, 1.0)),
        ]
    }

    /// Whether `(temperature, moisture)`, both in `[0, 1]`, falls in this rule.
    #[must_use]
    #[inline]
    pub fn covers(&self, temperature: f32, moisture: f32) -> bool {
        in_range(temperature, self.temperature) && in_range(moisture, self.moisture)
    }
}

/// `[lo, hi)`, with 1 itself inside a range ending at 1.
#[inline]
fn in_range(v: f32, (lo, hi): (f32, f32)) -> bool {
    v >= lo && (v < hi || (hi >= 1.0 && v <= 1.0))
}

/// Most rules in a biome table (checking that a table covers the unit square once takes time
/// cubic in the number of rules).
pub const MAX_BIOME_RULES: usize = 64;

/// Most tiles of a map with rivers (and of a map whose biomes are computed once for the whole
/// map; larger maps with a climate compute each chunk's biomes as unbounded maps do).
pub const MAX_WATER_TILES: u64 = 1 << 18;

/// Rivers and lakes, computed once per bounded map from the tiles' center heights. Off by
/// default. Refused on unbounded maps: a river drains a whole basin, which no chunk sees.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct RiverConfig {
    /// Whether the map has rivers and lakes.
    pub enabled: bool,
    /// Water (a tile's rain is its moisture, or 1 without climate) a tile must collect from
    /// itself and upstream to carry a river, in `[1, 1e6]`.
    pub threshold: f32,
    /// Whether depressions fill into lakes. Off, rivers still cross them (at the spill height)
    /// but no tile is a lake.
    pub lakes: bool,
    /// Smallest depth (normalised height, spill height less the tile's center) of a lake tile,
    /// in `[0, 1]`; shallower depressions are crossed by rivers.
    pub min_lake_depth: f32,
    /// How deep the channel cuts: the fraction of a vertex's height above the bottom of its
    /// type's range it loses at the channel's middle, in `[0, 1]`.
    pub carve: f32,
    /// Half-width of the channel at the threshold flow, in lattice steps, in `[0.5, 4]`; it
    /// grows with the square root of the flow, up to twice that.
    pub width: f32,
    /// Where rivers run: through tile centers (the default) or along the edges between tiles.
    pub model: RiverModel,
    /// Edge rivers: a river rises at least this many tiles from the sea, in
    /// `0..=MAX_SEA_DISTANCE` (Civilization VI starts its rivers 2 tiles from the sea); streams
    /// rising nearer are dropped.
    pub sea_distance: u32,
    /// Edge rivers: where rivers rise (the water they collect still sets their width).
    pub sources: RiverSources,
}

impl Default for RiverConfig {
    fn default() -> Self {
        Self {
            enabled: false,
            threshold: 8.0,
            lakes: true,
            min_lake_depth: 0.015,
            carve: 0.8,
            width: 1.0,
            model: RiverModel::Centers,
            sea_distance: 2,
            sources: RiverSources::Flow,
        }
    }
}

/// Where the rivers of an edge river network rise ([`RiverConfig::sources`]).
///
/// ```
/// use hex_terrain::{MapConfig, RiverSources};
///
/// let config = MapConfig::from_ron(
///     "(size: Bounded(x: 40, z: 30), rivers: (enabled: true, model: Edges, sources: Relief(tiles_per_edge: 12.0)))",
/// )
/// .unwrap();
/// assert_eq!(config.rivers.sources, RiverSources::Relief { tiles_per_edge: 12.0 });
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum RiverSources {
    /// Wherever the water a corner collects from the rain upstream reaches
    /// [`RiverConfig::threshold`] (the default): rivers rise where rain gathers.
    #[default]
    Flow,
    /// Civilization V's rule (its `MapGenerator.lua`, `AddRivers`): rivers rise among hills and
    /// mountains, away from the sea and from other rivers and lakes, and run down the drainage
    /// to the sea or a lake; then, on each landmass of at least [`RIVER_MIN_LANDMASS`] tiles with
    /// fewer than one river edge for every `tiles_per_edge` of its land tiles (and one more),
    /// among its hills and mountains nearer the sea and other rivers, then within two tiles of
    /// them, then anywhere on it, until it has them. `tiles_per_edge` in `[1, 1000]`
    /// (Civilization V: 12). No river ends at the map's edge.
    Relief {
        /// Land tiles of a landmass for each river edge it is given at least.
        tiles_per_edge: f32,
    },
}

/// How far (in tiles) a river Civilization V's way ([`RiverSources::Relief`]) rises from
/// another river or a lake: in its first pass, and in the passes that fill a landmass' share.
pub const RIVER_SPACING: [u32; 2] = [4, 2];

/// The fewest land tiles of a landmass given its share of rivers Civilization V's way
/// ([`RiverSources::Relief`]): smaller islands have a river only where one rises among their
/// hills in the first pass.
pub const RIVER_MIN_LANDMASS: u32 = 20;

/// Largest `rivers.sea_distance`.
pub const MAX_SEA_DISTANCE: u32 = 16;

/// Where a map's rivers run (Catlike Coding's Hex Map names the models).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum RiverModel {
    /// Through tile centers, tile to tile (Endless Legend): a river is a property of the tiles
    /// it runs through, which a unit stands on.
    #[default]
    Centers,
    /// Along the edges between tiles, corner to corner (Civilization V and VI, Unciv): a river
    /// lies between two tiles, which a step between them crosses.
    Edges,
}

impl super::MapConfig {
    /// Checks the climate and river settings (part of [`super::MapConfig::validate`]).
    pub(super) fn validate_climate(&self) -> Result<(), crate::error::ConfigError> {
        use super::check::{check, finite_in};
        use super::validate::check_noise;
        let c = &self.climate;
        check_noise("climate.moisture", &c.moisture)?;
        let unit = |v: f32| finite_in(f64::from(v), 0.0, 1.0);
        check(unit(c.coast_moisture), "climate.coast_moisture", c.coast_moisture, "[0, 1]")?;
        check(
            c.temperature_scale.is_finite() && c.temperature_scale > 0.0 && c.temperature_scale <= 1e9,
            "climate.temperature_scale",
            c.temperature_scale,
            "(0, 1e9]",
        )?;
        check(unit(c.temperature_jitter), "climate.temperature_jitter", c.temperature_jitter, "[0, 1]")?;
        let (north, south) = c.latitudes;
        check(
            finite_in(f64::from(north), -1.0, 1.0) && finite_in(f64::from(south), -1.0, 1.0) && north != south,
            "climate.latitudes",
            format!("({north}, {south})"),
            "(north, south), each in [-1, 1], different",
        )?;
        check(finite_in(f64::from(c.lapse_rate), 0.0, 2.0), "climate.lapse_rate", c.lapse_rate, "[0, 2]")?;
        check(unit(c.hills), "climate.hills", c.hills, "[0, 1]")?;
        check(
            c.biomes.len() <= MAX_BIOME_RULES,
            "climate.biomes",
            format!("{} rules", c.biomes.len()),
            format!("at most {MAX_BIOME_RULES} rules"),
        )?;
        for (i, rule) in c.biomes.iter().enumerate() {
            let field = |name: &str| format!("climate.biomes[{i}].{name}");
            check(
                matches!(rule.relief, TileKind::Land | TileKind::Mountain),
                &field("relief"),
                format!("{:?}", rule.relief),
                "Land or Mountain (sea tiles are ocean or coast by their neighbors)",
            )?;
            check(
                !rule.biome.is_water(),
                &field("biome"),
                format!("{:?}", rule.biome),
                "a land or mountain biome (ocean, coast and lake are given by water)",
            )?;
            for (name, (lo, hi)) in [("temperature", rule.temperature), ("moisture", rule.moisture)] {
                check(
                    unit(lo) && unit(hi) && lo < hi,
                    &field(name),
                    format!("({lo}, {hi})"),
                    "(lo, hi) with 0 <= lo < hi <= 1",
                )?;
            }
        }
        if c.enabled {
            for relief in [TileKind::Land, TileKind::Mountain] {
                check_coverage(&c.biomes, relief)?;
            }
        }
        if let Some(winds) = &c.winds {
            self.validate_winds(winds)?;
        }
        let r = &self.rivers;
        check(finite_in(f64::from(r.threshold), 1.0, 1e6), "rivers.threshold", r.threshold, "[1, 1e6]")?;
        check(unit(r.min_lake_depth), "rivers.min_lake_depth", r.min_lake_depth, "[0, 1]")?;
        check(unit(r.carve), "rivers.carve", r.carve, "[0, 1]")?;
        check(finite_in(f64::from(r.width), 0.5, 4.0), "rivers.width", r.width, "[0.5, 4]")?;
        check(
            r.sea_distance <= MAX_SEA_DISTANCE,
            "rivers.sea_distance",
            r.sea_distance,
            format!("0..={MAX_SEA_DISTANCE} tiles"),
        )?;
        if let RiverSources::Relief { tiles_per_edge } = r.sources {
            check(
                finite_in(f64::from(tiles_per_edge), 1.0, 1000.0),
                "rivers.sources.tiles_per_edge",
                tiles_per_edge,
                "[1, 1000]",
            )?;
            check(
                r.model == RiverModel::Edges,
                "rivers.sources",
                format!("{:?} with model: {:?}", r.sources, r.model),
                "Flow with model: Centers (Relief places rivers on tile edges: model: Edges)",
            )?;
        }
        if let (true, Some((x, z))) = (r.enabled, self.size.bounds()) {
            let tiles = u64::from(x) * u64::from(z);
            check(
                tiles <= MAX_WATER_TILES,
                "rivers.enabled",
                format!("true on a {x}x{z} map ({tiles} tiles)"),
                format!(
                    "false on maps of more than {MAX_WATER_TILES} tiles (the river network of a whole map is computed \
                     at once when the map is compiled)"
                ),
            )?;
        }
        check(
            !(r.enabled && self.size == super::MapSize::Unbounded),
            "rivers.enabled",
            "true on an Unbounded map",
            "false on an Unbounded map (a river drains a whole basin, which no chunk sees): use a Bounded size",
        )
    }
}

/// The rules of one relief kind cover the unit square exactly once: every cell between
/// consecutive range ends, on both axes, lies in exactly one rule.
fn check_coverage(rules: &[BiomeRule], relief: TileKind) -> Result<(), crate::error::ConfigError> {
    let mine: Vec<(usize, &BiomeRule)> = rules.iter().enumerate().filter(|(_, r)| r.relief == relief).collect();
    let cuts = |axis: fn(&BiomeRule) -> (f32, f32)| {
        let mut v: Vec<f32> = vec![0.0, 1.0];
        for (_, r) in &mine {
            let (lo, hi) = axis(r);
            v.extend([lo, hi]);
        }
        v.sort_by(f32::total_cmp);
        v.dedup();
        v
    };
    let ts = cuts(|r| r.temperature);
    let ms = cuts(|r| r.moisture);
    for t in ts.windows(2) {
        for m in ms.windows(2) {
            let (tc, mc) = ((t[0] + t[1]) * 0.5, (m[0] + m[1]) * 0.5);
            let covering: Vec<usize> = mine.iter().filter(|(_, r)| r.covers(tc, mc)).map(|(i, _)| *i).collect();
            match covering.as_slice() {
                [_] => {}
                [] => {
                    return Err(crate::error::ConfigError::new(
                        "climate.biomes",
                        format!("no {relief:?} rule for temperature {tc} and moisture {mc}"),
                        format!("{relief:?} rules covering temperature and moisture [0, 1] x [0, 1] without gaps"),
                    ));
                }
                [a, b, ..] => {
                    return Err(crate::error::ConfigError::new(
                        &format!("climate.biomes[{b}]"),
                        format!("overlaps climate.biomes[{a}] at temperature {tc} and moisture {mc}"),
                        format!("{relief:?} rules covering temperature and moisture [0, 1] x [0, 1] once"),
                    ));
                }
            }
        }
    }
    Ok(())
}
