//! Engine-agnostic generator of 3D hexagonal tiled terrain, after the thesis "Applying Perlin
//! noise on 3D hexagonal tiled maps".
//!
//! Heights come from Perlin fBm ([`noise::Fbm`]), optionally shaped into an island, a
//! mediterranean, an inland map or a gradient ([`shape`]). Tiles are hexagons cut into a
//! hex-in-hex lattice ([`lattice`]); each tile's type (sea, land, mountain) is read from its
//! centre and every other vertex is pulled into that type's height range, so a tile's type is
//! obvious at a glance ([`classify`]). Every stage is a pure function of position, so any
//! rectangle of tiles (a [`ChunkCoord`] chunk or the whole map) can be generated alone, in any
//! order, on any thread, and meets its neighbours bit for bit.
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
pub mod classify;
pub mod config;
pub mod error;
pub mod image_source;
pub mod lattice;
pub mod mesh;
pub mod metrics;
pub mod noise;
pub mod shape;
pub mod terrain;

pub use chunk::{ChunkCoord, TileRect};
pub use classify::{Thresholds, TileKind};
pub use config::{
    AppearanceConfig, HeightSourceConfig, LayoutConfig, ManipulationConfig, MapConfig, MapSize, NoiseConfig,
    Orientation, PullMode, Shape, TerrainConfig,
};
pub use error::{ConfigError, LoadError};
pub use hexx;
pub use image_source::{HeightImage, ImageError};
pub use mesh::{ChunkMesh, MeshBuffers};
pub use metrics::Sharpness;
pub use terrain::{RayHit, Terrain, TileInfo, VertexSample};
