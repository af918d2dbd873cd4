//! Map configuration: every knob of the generator, loaded from RON, with defaults equal to the
//! thesis' reference map (Map0) and validation that names the offending field.

use serde::{Deserialize, Serialize};

use crate::error::LoadError;

mod check;
mod climate;
mod edits;
mod file;
mod map_type;
mod movement;
mod setup;
mod sight;
mod validate;
mod winds;

pub use climate::{
    BiomeRule, ClimateConfig, MAX_BIOME_RULES, MAX_SEA_DISTANCE, MAX_WATER_TILES, RIVER_MIN_LANDMASS, RIVER_SPACING,
    RiverConfig, RiverModel, RiverSources,
};
pub use winds::{MAX_WIND_BANDS, WindConfig, WindPattern};

pub use edits::{FeatureEdit, MAX_EDITS, PropDensity, RiverEdit, TileEdit};
pub use file::MapFile;
pub use map_type::{MAX_MOUNTAIN_SHARE, MapType, MapTypeConfig, SEA_SHARE_TOLERANCE, WaterLevel};
pub use movement::{MAX_MOVE_COST, MovementConfig};
pub use setup::{
    MAX_PER_PLAYER, MAX_PLAYERS, MAX_SETUP_DISTANCE, MAX_SETUP_RINGS, MAX_SETUP_RULES, MAX_SETUP_TILES, MAX_YIELD,
    Place, ResourceClass, ResourceRule, SetupConfig, StartOn, ValueWeights, WonderConfig, WonderRule, YieldTable,
    Yields,
};
pub use sight::{MAX_SIGHT_BONUS, SightConfig};
pub use validate::{
    MAX_CHUNK_BYTES, MAX_CHUNK_SIDE, MAX_INNER_RINGS, MAX_MAP_BYTES, MAX_OCTAVES, MAX_OFFSET, MAX_WORLD_TILE,
    MIN_MAP_TYPE_FREQUENCY, MIN_MAP_TYPE_SIDE, MIN_WRAP_COLUMNS,
};

/// The whole description of a map. Defaults reproduce the thesis' Map0 (tables 2-4) on a
/// 30x30 map.
///
/// ```
/// use hex_terrain::MapConfig;
///
/// let config = MapConfig::from_ron("(seed: 7, size: Bounded(x: 20, z: 10))").unwrap();
/// assert_eq!(config.seed, 7);
/// assert_eq!(config.noise.octaves, 10); // unspecified fields keep the Map0 defaults
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct MapConfig {
    /// A human readable name, shown by tools.
    pub name: String,
    /// Height source, the Perlin fBm of the thesis by default.
    pub source: HeightSourceConfig,
    /// Seed of the Perlin permutation table.
    pub seed: u32,
    /// Map size in hexes, or unbounded.
    pub size: MapSize,
    /// East-west wrapping (bounded maps): walking east off the map comes back on its west side,
    /// as on Civilization's maps. Column `x + width` is column `x`, for heights, shapes,
    /// climate, rivers, meshes and queries.
    pub wrap: bool,
    /// Shift of the sampled window, in tiles `(x, z)`: the map's first tile is the tile at these
    /// offset coordinates of the infinite world, so a map offset by its own width continues it.
    pub offset: (i32, i32),
    /// Fractal Brownian motion parameters (thesis Algorithm 2).
    pub noise: NoiseConfig,
    /// Elevation and tile-type parameters.
    pub terrain: TerrainConfig,
    /// Shaping filter of section 7.1 (island, mediterranean, inland, gradient).
    pub shape: Shape,
    /// The map's type (Pangaea, Continents, Archipelago...; see [`MapTypeConfig`]), in place of
    /// the shape on a bounded map; `None` (the default): the shape.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub map_type: Option<MapTypeConfig>,
    /// Which manipulation stages run; all off gives the raw map of the thesis figures.
    pub manipulation: ManipulationConfig,
    /// Hexagon size and orientation.
    pub layout: LayoutConfig,
    /// Chunk size in tiles, for streaming.
    pub chunk_size: (u32, u32),
    /// Appearance parameters that renderers read (Algorithm 5).
    pub appearance: AppearanceConfig,
    /// Temperature, moisture and biomes (off by default).
    pub climate: ClimateConfig,
    /// The game's own terrain: the path of a terrain ruleset (`*.terrain.ron`, see
    /// [`TerrainRuleset`](crate::TerrainRuleset)), relative to the map file. `None` (the
    /// default): the 13 biomes of `climate.biomes`
    /// ([`TerrainRuleset::biomes`](crate::TerrainRuleset::biomes)). With one,
    /// [`TileInfo::terrain`](crate::TileInfo::terrain) answers by it and the meshes take its
    /// terrains' and features' colors.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ruleset: Option<String>,
    /// Rivers and lakes (off by default; bounded maps only).
    pub rivers: RiverConfig,
    /// Peaks on mountains and swells on hills, inside their ranges (off by default: Map0).
    pub relief: ReliefConfig,
    /// How units move: the cost of entering each tile, for the game's rules and the setup's
    /// fairness (see [`MovementConfig`]; left out of a file, the defaults).
    #[serde(skip_serializing_if = "MovementConfig::is_default")]
    pub movement: MovementConfig,
    /// What units see: how far, and what blocks their view (see [`SightConfig`]; left out of a
    /// file, the defaults).
    #[serde(skip_serializing_if = "SightConfig::is_default")]
    pub sight: SightConfig,
    /// Game setup: start positions, resources, natural wonders and the fairness report (off by
    /// default; see [`SetupConfig`]).
    pub setup: Option<SetupConfig>,
    /// What a designer changed on the generated map, a tile an entry (empty by default; see
    /// [`TileEdit`]): the map is the seed's plus these.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub edits: Vec<TileEdit>,
}

impl Default for MapConfig {
    fn default() -> Self {
        Self {
            name: "Map0".into(),
            source: HeightSourceConfig::default(),
            seed: 1000,
            size: MapSize::Bounded { x: 30, z: 30 },
            wrap: false,
            offset: (0, 0),
            noise: NoiseConfig::default(),
            terrain: TerrainConfig::default(),
            shape: Shape::None,
            map_type: None,
            manipulation: ManipulationConfig::default(),
            layout: LayoutConfig::default(),
            chunk_size: (16, 16),
            appearance: AppearanceConfig::default(),
            climate: ClimateConfig::default(),
            rivers: RiverConfig::default(),
            relief: ReliefConfig::default(),
            movement: MovementConfig::default(),
            sight: SightConfig::default(),
            setup: None,
            ruleset: None,
            edits: Vec::new(),
        }
    }
}

/// Relief after manipulation (see the `relief` module): how far mountain tiles rise to a peak
/// and land tiles swell into hills, always inside their tile type's height range. All zero
/// (the default, the thesis' Map0) leaves the manipulated surface as it is; so does turning
/// hex unity off (relief shapes tiles inside the ranges hex unity gives them).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct ReliefConfig {
    /// Height of a mountain tile's peak as a fraction of the mountain range above its bottom,
    /// in `[0, 1]`: the center vertex rises to at least this, the rings between fall linearly
    /// to the border.
    pub peaks: f32,
    /// How much each vertex's rise is lowered at random (from a hash of its position), in
    /// `[0, 1]`: 0 gives smooth cones, higher values ridges and gullies.
    pub ridges: f32,
    /// Height of hills, a fraction of the land range, in `[0, 1]`: land tiles whose noise lies
    /// in the upper half of the land range swell by up to this.
    pub hills: f32,
}

impl ReliefConfig {
    /// The relief of the bundled strategy maps: tall peaks, visible ridges, gentle hills.
    pub const MOUNTAINS: Self = Self { peaks: 0.8, ridges: 0.45, hills: 0.45 };

    /// Whether any relief is on.
    #[must_use]
    pub fn any(&self) -> bool {
        self.peaks > 0.0 || self.hills > 0.0
    }
}

/// Where heights come from.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum HeightSourceConfig {
    /// Perlin fBm (thesis section 5.1).
    #[default]
    Noise,
    /// A greyscale PNG heightmap stretched over the (bounded) map: the thesis' filter use.
    Image {
        /// Path of the PNG; relative paths are resolved against the RON file's folder by
        /// [`MapConfig::load`].
        path: String,
        /// Image value (in `[0, 1]`) of sea level: darker pixels become sea.
        sea_level: f32,
    },
}

/// Map extent.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum MapSize {
    /// A finite map of `x` columns by `z` rows of hexes.
    Bounded {
        /// Number of hexes along x.
        x: u32,
        /// Number of hexes along z.
        z: u32,
    },
    /// An infinite world, generated chunk by chunk around whatever needs it.
    Unbounded,
    /// A round world: the hex globe of [`GlobeGrid`](crate::GlobeGrid) at `frequency` (1 to
    /// [`MAX_GLOBE_FREQUENCY`](crate::MAX_GLOBE_FREQUENCY)), `10 f^2 + 2` tiles of which 12 are
    /// pentagons; [`GlobeTerrain::new`](crate::GlobeTerrain::new) generates it
    /// ([`GlobeSize`](crate::GlobeSize) names the frequencies of Civilization's map sizes).
    Globe {
        /// Tiles along an edge of the icosahedron.
        frequency: u32,
    },
}

impl MapSize {
    /// The `(x, z)` size in hexes, or `None` for an unbounded world or a globe.
    #[must_use]
    pub fn bounds(self) -> Option<(u32, u32)> {
        match self {
            Self::Bounded { x, z } => Some((x, z)),
            Self::Unbounded | Self::Globe { .. } => None,
        }
    }

    /// The globe's frequency, or `None` for a flat map.
    #[must_use]
    pub fn globe(self) -> Option<u32> {
        match self {
            Self::Globe { frequency } => Some(frequency),
            Self::Bounded { .. } | Self::Unbounded => None,
        }
    }
}

/// Fractal Brownian motion parameters (thesis section 5.1.1, Algorithm 2).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct NoiseConfig {
    /// Number of Perlin signals summed.
    pub octaves: u32,
    /// Amplitude multiplier between octaves, in (0, 1].
    pub persistence: f64,
    /// Frequency multiplier between octaves, at least 1.
    pub lacunarity: f64,
    /// Zoom of the noise: thesis vertex steps (a quarter of a hex radius) per noise period.
    pub scale: f64,
}

impl Default for NoiseConfig {
    fn default() -> Self {
        Self { octaves: 10, persistence: 0.3, lacunarity: 2.0, scale: 40.0 }
    }
}

/// Elevation and tile-type parameters (thesis table 4, section 5.5-5.6).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct TerrainConfig {
    /// World height of normalised height 1.
    pub max_elevation: f32,
    /// Normalised height below which a tile is sea.
    pub sea_threshold: f32,
    /// Normalised height from which a tile is mountain.
    pub mountain_threshold: f32,
    /// Gap opened on each side of a threshold by linear interpolation (eq. 5.6).
    pub interpolation_tolerance: f32,
    /// Number of inner hexagons between a tile's center and its border (the thesis uses 1).
    pub inner_rings: u32,
}

impl Default for TerrainConfig {
    fn default() -> Self {
        Self {
            max_elevation: 10.0,
            sea_threshold: 0.3,
            mountain_threshold: 0.7,
            interpolation_tolerance: 0.03,
            inner_rings: 1,
        }
    }
}

/// Shaping filters of thesis section 7.1. They need the map's bounds.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum Shape {
    /// Heights as the noise gives them.
    #[default]
    None,
    /// Multiply by `1 - f(d)` (Algorithm 6, eq. 7.1): sea at the map's edges.
    Island {
        /// Steepness of the transition (eq. 7.1 `a`).
        a: f32,
        /// Width of the sea margin (eq. 7.1 `b`).
        b: f32,
    },
    /// Multiply by `f(d)`: sea in the middle, land at the edges.
    Mediterranean {
        /// Steepness of the transition (eq. 7.1 `a`).
        a: f32,
        /// Width of the land margin (eq. 7.1 `b`).
        b: f32,
    },
    /// Remap `[0, 1]` linearly to `[min, max]` (section 7.1.4).
    Inland {
        /// New lowest height.
        min: f32,
        /// New highest height.
        max: f32,
    },
    /// Eq. 7.2: multiply by `mapX / x * z / mapZ` (weaker noise to the south, stronger to the
    /// west), clamped to `[0, 1]`.
    Gradient,
}

/// How hex unity pulls a vertex that lies outside its tile type's height range.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum PullMode {
    /// Clamp to the range: the least displacement that meets the "easily recognisable"
    /// requirement, and the default.
    #[default]
    Clamp,
    /// Thesis Algorithm 3 as written: an inner vertex moves halfway to the threshold,
    /// `(threshold + h) / 2`, which may leave it outside the range.
    Thesis,
}

/// Manipulation stages (thesis section 6.4). All off gives the raw ("basic PTG") map.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct ManipulationConfig {
    /// Hex unity (Algorithm 3): border vertices between different types go to the threshold,
    /// inner vertices are pulled into the tile type's range.
    pub hex_unity: bool,
    /// Linear interpolation (Algorithm 4): opens a gap of the tolerance around each threshold.
    pub interpolation: bool,
    /// Edge/corner correction (6.4.3): border vertices between tiles of one type are pulled into
    /// that type's range.
    pub edge_correction: bool,
    /// How inner vertices are pulled.
    pub pull: PullMode,
}

impl Default for ManipulationConfig {
    fn default() -> Self {
        Self { hex_unity: true, interpolation: true, edge_correction: true, pull: PullMode::Clamp }
    }
}

impl ManipulationConfig {
    /// Every stage off: the thesis' raw map / basic PTG.
    #[must_use]
    pub fn raw() -> Self {
        Self { hex_unity: false, interpolation: false, edge_correction: false, ..Self::default() }
    }

    /// Whether any stage changes heights.
    #[must_use]
    pub fn any(&self) -> bool {
        self.hex_unity || self.interpolation || self.edge_correction
    }
}

/// Hexagon orientation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum Orientation {
    /// Flat top: columns of hexes (the thesis' frame).
    #[default]
    Flat,
    /// Pointy top: rows of hexes.
    Pointy,
}

/// Hexagon size and orientation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct LayoutConfig {
    /// Circumradius of a hex in world units.
    pub hex_size: f32,
    /// Flat or pointy tops.
    pub orientation: Orientation,
}

impl Default for LayoutConfig {
    fn default() -> Self {
        Self { hex_size: 1.0, orientation: Orientation::Flat }
    }
}

/// Parameters renderers read (thesis section 6.3).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct AppearanceConfig {
    /// Blend distance of Algorithm 5, in normalised height, in `[0, 1]`.
    pub blend: f32,
}

impl Default for AppearanceConfig {
    fn default() -> Self {
        Self { blend: 0.1 }
    }
}

impl MapConfig {
    /// Parses a RON document and validates it ([`MapConfig::validate`]: every field's range).
    /// What only the generated map can tell, whether a game setup fits it (enough tiles a start
    /// may stand on, far enough apart: `setup.players`, `setup.min_distance`), is checked when
    /// the map is compiled ([`Terrain::new`](crate::Terrain::new)), which names the field too.
    ///
    /// # Errors
    /// [`LoadError::Ron`] with line and column for malformed RON, [`LoadError::Invalid`] naming the
    /// field for out-of-range values.
    pub fn from_ron(text: &str) -> Result<Self, LoadError> {
        let config: Self = ron::de::from_str(text)?;
        config.validate()?;
        Ok(config)
    }

    /// Reads and parses a RON file.
    ///
    /// # Errors
    /// As [`MapConfig::from_ron`], plus [`LoadError::Io`] when the file cannot be read.
    pub fn load(path: impl AsRef<std::path::Path>) -> Result<Self, LoadError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path)
            .map_err(|source| LoadError::Io { path: path.display().to_string(), source })?;
        let mut config = Self::from_ron(&text)?;
        if let (HeightSourceConfig::Image { path: image, .. }, Some(dir)) = (&mut config.source, path.parent())
            && std::path::Path::new(image.as_str()).is_relative()
        {
            *image = dir.join(&*image).display().to_string();
        }
        if let (Some(ruleset), Some(dir)) = (&mut config.ruleset, path.parent())
            && std::path::Path::new(ruleset.as_str()).is_relative()
        {
            *ruleset = dir.join(&*ruleset).display().to_string();
        }
        Ok(config)
    }

    /// Serialises to pretty RON.
    #[must_use]
    pub fn to_ron(&self) -> String {
        let pretty = ron::ser::PrettyConfig::new().struct_names(false);
        // Serialising plain data with derived impls cannot fail.
        ron::ser::to_string_pretty(self, pretty).unwrap_or_default()
    }

    /// Inner subdivisions from center to corner: `inner_rings + 1`.
    #[must_use]
    pub fn subdivisions(&self) -> u32 {
        self.terrain.inner_rings + 1
    }
}

#[cfg(test)]
mod tests;
