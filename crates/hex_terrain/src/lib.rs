//! Engine-agnostic generator of 3D hexagonal tiled terrain, after the thesis "Applying Perlin
//! noise on 3D hexagonal tiled maps".
//!
//! Heights come from Perlin fBm or a heightmap image, optionally shaped into an island, a
//! mediterranean, an inland map or a gradient ([`heights`]). Tiles are hexagons cut into a
//! hex-in-hex lattice ([`lattice`]); each tile's type (sea, land, mountain, [`kind`]) is read
//! from its center and every other vertex is pulled into that type's height range
//! ([`manipulate`]), so a tile's type is obvious at a glance. [`mesh`] turns any rectangle of
//! tiles into buffers; [`query`] answers where things are on the surface. Every stage is a pure function of position, so any
//! rectangle of tiles (a [`ChunkCoord`] chunk or the whole map) can be generated alone, in any
//! order, on any thread, and meets its neighbors bit for bit.
//!
//! ```
//! use hex_terrain::{MapConfig, Terrain};
//!
//! let terrain = Terrain::new(MapConfig::default()).unwrap();
//! let map = terrain.generate_map().unwrap();
//! assert_eq!(map.buffers.triangle_count(), 30 * 30 * 24); // 6n² triangles a tile, n = 2
//! ```

#![cfg_attr(not(test), warn(clippy::unwrap_used))]

pub mod chunk;
pub mod climate;
pub mod config;
pub mod error;
pub mod hash;
pub mod heights;
pub mod kind;
pub mod lattice;
pub mod manipulate;
pub mod mesh;
pub mod metrics;
pub mod props;
pub mod query;
pub mod relief;
pub mod terrain;
pub mod wrap;

pub use chunk::{ChunkCoord, TileRect};
pub use climate::{Biome, Climate, Hydrology, RiverTile};
pub use config::{
    AppearanceConfig, BiomeRule, ClimateConfig, HeightSourceConfig, LayoutConfig, ManipulationConfig, MapConfig,
    MapFile, MapSize, NoiseConfig, Orientation, PullMode, ReliefConfig, RiverConfig, Shape, TerrainConfig,
};
pub use error::{ConfigError, LoadError};
pub use heights::{HeightImage, ImageError};
pub use hexx;
pub use kind::{Thresholds, TileKind};
pub use lattice::Lattice;
pub use manipulate::VertexSample;
pub use mesh::{ChunkMesh, Diagnostics, GenerateOptions, MeshBuffers, Threads, WaterBuffers};
pub use metrics::Sharpness;
pub use props::{PROP_VARIANTS, Prop, PropKind};
pub use query::RayHit;
pub use terrain::{Terrain, TileInfo};
pub use wrap::Wrap;
