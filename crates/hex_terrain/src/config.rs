//! Map configuration: every knob of the generator, loaded from RON, with defaults equal to the
//! thesis' reference map (Map0) and validation that names the offending field.

use serde::{Deserialize, Serialize};

use crate::error::{ConfigError, LoadError};

mod file;
pub use file::MapFile;

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
    /// Shift of the sampled window, in tiles `(x, z)`: the map's first tile is the tile at these
    /// offset coordinates of the infinite world, so a map offset by its own width continues it.
    pub offset: (i32, i32),
    /// Fractal Brownian motion parameters (thesis Algorithm 2).
    pub noise: NoiseConfig,
    /// Elevation and tile-type parameters.
    pub terrain: TerrainConfig,
    /// Shaping filter of section 7.1 (island, mediterranean, inland, gradient).
    pub shape: Shape,
    /// Which manipulation stages run; all off gives the raw map of the thesis figures.
    pub manipulation: ManipulationConfig,
    /// Hexagon size and orientation.
    pub layout: LayoutConfig,
    /// Chunk size in tiles, for streaming.
    pub chunk_size: (u32, u32),
    /// Appearance parameters that renderers read (Algorithm 5).
    pub appearance: AppearanceConfig,
}

impl Default for MapConfig {
    fn default() -> Self {
        Self {
            name: "Map0".into(),
            source: HeightSourceConfig::default(),
            seed: 1000,
            size: MapSize::Bounded { x: 30, z: 30 },
            offset: (0, 0),
            noise: NoiseConfig::default(),
            terrain: TerrainConfig::default(),
            shape: Shape::None,
            manipulation: ManipulationConfig::default(),
            layout: LayoutConfig::default(),
            chunk_size: (16, 16),
            appearance: AppearanceConfig::default(),
        }
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
}

impl MapSize {
    /// The `(x, z)` size in hexes, or `None` for an unbounded world.
    #[must_use]
    pub fn bounds(self) -> Option<(u32, u32)> {
        match self {
            Self::Bounded { x, z } => Some((x, z)),
            Self::Unbounded => None,
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

/// Largest number of octaves accepted.
pub const MAX_OCTAVES: u32 = 32;
/// Largest number of inner rings accepted.
pub const MAX_INNER_RINGS: u32 = 16;
/// Largest absolute tile offset accepted.
pub const MAX_OFFSET: i32 = 1_000_000;
/// Largest chunk side, in tiles.
pub const MAX_CHUNK_SIDE: u32 = 512;
/// Largest estimated size of one chunk's mesh, in bytes: a chunk is generated on one thread
/// while a game runs, so this keeps one chunk well under a second.
pub const MAX_CHUNK_BYTES: u64 = 256 << 20;
/// Largest estimated size of a whole bounded map's mesh, in bytes.
pub const MAX_MAP_BYTES: u64 = 12 << 30;
/// Bytes a mesh vertex and its share of the index buffer take, about.
const BYTES_PER_VERTEX: u64 = 3 * 4 + 3 * 4 + 2 * 4 + 4 + 4 + 2 * 3 * 4;

fn check(ok: bool, field: &str, value: impl std::fmt::Display, allowed: impl Into<String>) -> Result<(), ConfigError> {
    if ok { Ok(()) } else { Err(ConfigError::new(field, value.to_string(), allowed.into())) }
}

fn finite_in(v: f64, lo: f64, hi: f64) -> bool {
    v.is_finite() && v >= lo && v <= hi
}

impl MapConfig {
    /// Parses a RON document and validates it.
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

    /// Checks every field against its allowed range.
    ///
    /// # Errors
    /// The first invalid field, with its value and the allowed range.
    pub fn validate(&self) -> Result<(), ConfigError> {
        let n = &self.noise;
        check((1..=MAX_OCTAVES).contains(&n.octaves), "noise.octaves", n.octaves, format!("1..={MAX_OCTAVES}"))?;
        check(
            n.persistence.is_finite() && n.persistence > 0.0 && n.persistence <= 1.0,
            "noise.persistence",
            n.persistence,
            "(0, 1]",
        )?;
        check(finite_in(n.lacunarity, 1.0, 64.0), "noise.lacunarity", n.lacunarity, "[1, 64]")?;
        check(n.scale.is_finite() && n.scale > 0.0 && n.scale <= 1e9, "noise.scale", n.scale, "(0, 1e9]")?;

        let t = &self.terrain;
        check(finite_in(f64::from(t.max_elevation), 0.0, 1e6), "terrain.max_elevation", t.max_elevation, "[0, 1e6]")?;
        check(finite_in(f64::from(t.sea_threshold), 0.0, 1.0), "terrain.sea_threshold", t.sea_threshold, "[0, 1]")?;
        check(
            finite_in(f64::from(t.mountain_threshold), 0.0, 1.0),
            "terrain.mountain_threshold",
            t.mountain_threshold,
            "[0, 1]",
        )?;
        check(
            t.sea_threshold < t.mountain_threshold,
            "terrain.sea_threshold",
            t.sea_threshold,
            format!("below terrain.mountain_threshold ({})", t.mountain_threshold),
        )?;
        let max_tol =
            t.sea_threshold.min(1.0 - t.mountain_threshold).min((t.mountain_threshold - t.sea_threshold) / 2.0);
        check(
            t.interpolation_tolerance.is_finite()
                && t.interpolation_tolerance >= 0.0
                && (t.interpolation_tolerance < max_tol || t.interpolation_tolerance == 0.0),
            "terrain.interpolation_tolerance",
            t.interpolation_tolerance,
            format!("[0, {max_tol}) (below the sea threshold, 1 - the mountain threshold and half the land range)"),
        )?;
        check(
            (1..=MAX_INNER_RINGS).contains(&t.inner_rings),
            "terrain.inner_rings",
            t.inner_rings,
            format!("1..={MAX_INNER_RINGS}"),
        )?;

        let l = &self.layout;
        check(
            l.hex_size.is_finite() && l.hex_size > 0.0 && l.hex_size <= 1e4,
            "layout.hex_size",
            l.hex_size,
            "(0, 1e4]",
        )?;
        check(
            (1..=MAX_CHUNK_SIDE).contains(&self.chunk_size.0) && (1..=MAX_CHUNK_SIDE).contains(&self.chunk_size.1),
            "chunk_size",
            format!("{:?}", self.chunk_size),
            format!("each side in 1..={MAX_CHUNK_SIDE}"),
        )?;
        let per_hex = 3 * u64::from(self.subdivisions()).pow(2);
        let chunk_bytes = u64::from(self.chunk_size.0) * u64::from(self.chunk_size.1) * per_hex * BYTES_PER_VERTEX;
        check(
            chunk_bytes <= MAX_CHUNK_BYTES,
            "chunk_size",
            format!(
                "{:?} ({} MiB of mesh a chunk with {} inner rings)",
                self.chunk_size,
                chunk_bytes >> 20,
                t.inner_rings
            ),
            format!("a chunk mesh of at most {} MiB: fewer tiles a chunk or fewer inner rings", MAX_CHUNK_BYTES >> 20),
        )?;
        check(
            self.offset.0.unsigned_abs() <= MAX_OFFSET as u32 && self.offset.1.unsigned_abs() <= MAX_OFFSET as u32,
            "offset",
            format!("{:?}", self.offset),
            format!("each in -{MAX_OFFSET}..={MAX_OFFSET}"),
        )?;
        check(
            finite_in(f64::from(self.appearance.blend), 0.0, 1.0),
            "appearance.blend",
            self.appearance.blend,
            "[0, 1]",
        )?;

        if let HeightSourceConfig::Image { sea_level, path } = &self.source {
            check(finite_in(f64::from(*sea_level), 0.0, 1.0), "source.sea_level", sea_level, "[0, 1]")?;
            check(!path.is_empty(), "source.path", "\"\"", "the path of a PNG heightmap")?;
            check(
                self.size != MapSize::Unbounded,
                "source",
                "Image on an Unbounded map",
                "Noise for an Unbounded map (an image covers a bounded map)",
            )?;
        }

        match self.size {
            MapSize::Bounded { x, z } => {
                check(x >= 1 && z >= 1, "size", format!("{x}x{z}"), "at least 1x1 hexes")?;
                check(
                    x <= 2 * MAX_OFFSET as u32 && z <= 2 * MAX_OFFSET as u32,
                    "size",
                    format!("{x}x{z}"),
                    format!("at most {0}x{0} hexes", 2 * MAX_OFFSET),
                )?;
                let bytes = u64::from(x) * u64::from(z) * per_hex * BYTES_PER_VERTEX;
                check(
                    bytes <= MAX_MAP_BYTES,
                    "size",
                    format!("{x}x{z} ({} GiB of mesh with {} inner rings)", bytes >> 30, t.inner_rings),
                    format!(
                        "a mesh of at most {} GiB; use Unbounded and chunks for larger worlds",
                        MAX_MAP_BYTES >> 30
                    ),
                )?;
            }
            MapSize::Unbounded => {
                check(
                    self.shape == Shape::None,
                    "shape",
                    format!("{:?}", self.shape),
                    "None for an Unbounded map (shapes need the map's bounds)",
                )?;
            }
        }

        match self.shape {
            Shape::None | Shape::Gradient => {}
            Shape::Island { a, b } | Shape::Mediterranean { a, b } => {
                check(finite_in(f64::from(a), 1e-3, 100.0), "shape.a", a, "[0.001, 100]")?;
                check(finite_in(f64::from(b), 1e-3, 100.0), "shape.b", b, "[0.001, 100]")?;
            }
            Shape::Inland { min, max } => {
                check(finite_in(f64::from(min), 0.0, 1.0), "shape.min", min, "[0, 1]")?;
                check(finite_in(f64::from(max), 0.0, 1.0) && max > min, "shape.max", max, format!("({min}, 1]"))?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests;
