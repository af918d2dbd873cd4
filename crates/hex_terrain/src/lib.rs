//! Engine-agnostic generator of 3D hexagonal tiled terrain, after the thesis "Applying Perlin
//! noise on 3D hexagonal tiled maps".
//!
//! [`Terrain::new`] compiles a [`MapConfig`] into a [`Pipeline`] of stage objects, each in its
//! own module and each taking the stages it depends on as arguments. Every stage is a pure
//! function of the config and the position, so any rectangle of tiles (a [`ChunkCoord`] chunk or
//! the whole map) can be generated alone, in any order, on any thread, and meets its neighbors
//! bit for bit. In the order data flows through them:
//!
//! | module (private: the stages are reached through [`Terrain`] and the types re-exported here) | stage |
//! | --- | --- |
//! | [`vocab`] | the words every stage uses: [`TileKind`], [`Biome`], [`TileInfo`], [`PropKind`] (imports nothing of the crate) |
//! | [`config`] | [`MapConfig`] (RON), validation with the field, value and allowed range of every error |
//! | `lattice`, `chunk`, `wrap`, `geometry` | the hex-in-hex lattice, rectangles and chunks, east-west wrapping; [`Geometry`] composes them: where tiles and points are |
//! | `heights` | [`HeightField`]: Perlin fBm or a heightmap, then the shaping filters |
//! | `edits` | [`Edits`]: a designer's changes ([`TileEdit`]s, the config's `edits`) applied to the raw heights, so every later stage sees them |
//! | `kind` | [`Thresholds`]: a tile's kind from its center height, each kind's height range |
//! | `climate` | [`ClimateModel`]: temperature, moisture and the biome table |
//! | `table`, `water::hydrology` | [`TileTable`]: every tile's kind and biome and the water network of a bounded map, computed once |
//! | `manipulate`, `relief`, `water::channels`, `vertex` | the vertex chain [`VertexRules`]: manipulation, relief, carving |
//! | `pipeline` | [`Pipeline`]: the stages compiled from one config, and the questions that combine them |
//! | `mesh` | any rectangle of tiles to [`MeshBuffers`], on all cores or the calling thread |
//! | `water::surface`, `props` | what stands on a generated chunk: its water surface, its trees, rocks and reeds |
//! | `query`, `metrics` | the surface under a position and ray casts, in f64; sharpness (thesis eq. 4.1, 7.3) |
//! | `paths` | cheapest paths (A*), the tiles within a budget and a path's turns, by the map's movement model |
//! | `sight` | what a unit sees from a tile, by the map's sight rule |
//! | `stats` | [`MapStats`]: land and water, landmasses (continents and islands), coast, straits, mountain ranges, biomes, rivers, lakes |
//! | [`setup`] | [`Setup`]: a game on the map: start positions in regions of equal fertility, resources, natural wonders, and the fairness report (after the terrain; it changes no height) |
//! | [`terrain`] | [`Terrain`], the facade over all of it |
//! | [`editor`] | [`Editor`]: strokes of a [`Tool`] with a [`Brush`] that change the config's edits, undo and redo, and the [`Change`] (tiles, chunks) of each |
//! | [`minimap`] | a top-down picture of the map for a minimap: each pixel's tile, the tiles' colors, rivers, fog of war and owners, repainted per tile |
//! | [`save`] | what a game writes on the tiles ([`FogState`], owners, overlays, [`Highlight`]s) as a [`TileStateSave`] file: RON or compact binary, checked against the map |
//!
//! ```
//! use hex_terrain::{MapConfig, Terrain};
//!
//! let terrain = Terrain::new(MapConfig::default()).unwrap();
//! let map = terrain.generate_map().unwrap();
//! assert_eq!(map.buffers.triangle_count(), 30 * 30 * 24); // 6n² triangles a tile, n = 2
//! ```

#![cfg_attr(not(test), warn(clippy::unwrap_used))]

pub mod vocab;

pub mod config;
pub mod error;

mod chunk;
mod geometry;
mod globe;
mod lattice;
mod wrap;

mod edits;
mod heights;
mod kind;

mod climate;
mod ruleset;
mod table;
mod water;

mod hash;
mod manipulate;
mod relief;
mod vertex;

mod info;
mod pipeline;

mod mesh;
mod props;

mod fog;
mod metrics;
mod paths;
mod query;
mod sight;
mod stats;

pub mod minimap;

pub mod setup;

pub mod editor;

pub mod terrain;

pub mod save;

pub use chunk::{ChunkCoord, TileRect};
pub use climate::{Climate, ClimateModel, TileSample};
pub use config::{
    AppearanceConfig, BiomeRule, ClimateConfig, FeatureEdit, HeightSourceConfig, LayoutConfig, MAX_EDITS,
    ManipulationConfig, MapConfig, MapFile, MapSize, MapType, MapTypeConfig, MovementConfig, NoiseConfig, Orientation,
    Place, PropDensity, PullMode, ReliefConfig, ResourceClass, ResourceRule, RiverConfig, RiverEdit, RiverModel,
    RiverSources, SetupConfig, Shape, SightConfig, StartOn, TerrainConfig, TileEdit, ValueWeights, WaterLevel,
    WindConfig, WindPattern, WonderConfig, WonderRule, YieldTable, Yields,
};
pub use config::{
    MAX_BIOME_RULES, MAX_CHUNK_BYTES, MAX_CHUNK_SIDE, MAX_INNER_RINGS, MAX_MAP_BYTES, MAX_MOUNTAIN_SHARE,
    MAX_MOVE_COST, MAX_OCTAVES, MAX_OFFSET, MAX_PER_PLAYER, MAX_PLAYERS, MAX_SEA_DISTANCE, MAX_SETUP_DISTANCE,
    MAX_SETUP_RINGS, MAX_SETUP_RULES, MAX_SETUP_TILES, MAX_SIGHT_BONUS, MAX_WATER_TILES, MAX_WIND_BANDS,
    MAX_WORLD_TILE, MAX_YIELD, MIN_MAP_TYPE_FREQUENCY, MIN_MAP_TYPE_SIDE, MIN_WRAP_COLUMNS, RIVER_MIN_LANDMASS,
    RIVER_SPACING, SEA_SHARE_TOLERANCE,
};
pub use editor::{Brush, Change, EditError, EditTimings, Editor, MAX_BRUSH_RADIUS, MAX_FLOOD_TILES, Stroke, Tool};
pub use edits::Edits;
pub use error::{ConfigError, LoadError};
pub use fog::{FOG_MAGIC, FOG_VERSION, FogError, FogOfWar};
pub use geometry::Geometry;
pub use globe::{
    GLOBE_FOG_MAGIC, GLOBE_FOG_VERSION, GLOBE_SIGHT_SAMPLES, GlobeChange, GlobeChunk, GlobeEditor, GlobeFog, GlobeGrid,
    GlobeLandmass, GlobeMesh, GlobeNeighbors, GlobePath, GlobePoint, GlobeProp, GlobeRayHit, GlobeSize, GlobeStats,
    GlobeStroke, GlobeTerrain, GlobeTile, GlobeTileInfo, MAX_GLOBE_FREQUENCY, POLAR_LATITUDE,
};
/// The stable hash the core places props with, for the plugin's prop meshes. Hidden from the
/// docs: an internal the two crates share, not an API.
#[doc(hidden)]
pub use hash::{hash, unit};
pub use heights::{
    FastPerlin, Fbm, HeightField, HeightImage, ImageError, Kernel, MAX_BLOB_SHARE, MAX_IMAGE_PIXELS, MAX_LAYOUTS,
    MAX_PNG_BYTES, MAX_STRAIGHT_RIDGE, MAX_TRIES, MapTypeReport, MapTypeTarget, SEA_STEPS, TargetCheck,
};
pub use hexx;
pub use info::TileInfo;
pub use kind::Thresholds;
pub use lattice::Lattice;
pub use mesh::{ChunkMesh, Detail, Diagnostics, GenerateOptions, MeshBuffers, Threads, texture_class};
pub use metrics::Sharpness;
pub use paths::{MAX_PATH_TILES, Path, Turns};
pub use pipeline::Pipeline;
pub use props::{Marker, MarkerKind, Prop};
pub use query::{MAX_RAY_STEPS, RayHit};
pub use relief::Relief;
pub use ruleset::{
    FeatureDef, FeatureId, FeaturePatches, Landform, Look, MAX_FEATURES, MAX_PATCH, MAX_PROPS_ON_TILE, MAX_RULES,
    MAX_TERRAINS, Occurs, PATCH_SPREAD, PropGrowth, TerrainDef, TerrainId, TerrainRuleset, TileFacts, TileTerrain,
    Traits,
};
pub use save::{FogState, Highlight, MAX_OWNERS, MAX_SAVED_TILES, SAVE_VERSION, SaveError, TileStateSave};
pub use setup::{
    GlobeRegion, GlobeSetup, MAX_START_SEARCH_CHECKS, PlacedResource, PlacedWonder, Setup, SetupNote, SetupReport,
    SetupTimings, Shortfall, Stages, StartReport, TileSetup,
};
pub use sight::{MAX_UNBOUNDED_SIGHT, SightError};
pub use stats::{
    CONTINENT_MIN_SHARE, CONTINENT_MIN_TILES, IN_LINE, Landmass, LandmassKind, MapStats, RainShadow, RiverStats,
    SHADOW_REACH, SurveyFigure, SurveyTarget, SurveyVerdict, survey_targets,
};
pub use table::TileTable;
pub use terrain::Terrain;
pub use vertex::{Sharing, VertexRules, VertexSample};
pub use vocab::{Biome, MAX_ID_LEN, PROP_VARIANTS, PropKind, RuleId, TileKind};
pub use water::{EdgeRivers, Hydrology, RiverEdge, RiverTile, WaterBuffers};
pub use wrap::Wrap;
