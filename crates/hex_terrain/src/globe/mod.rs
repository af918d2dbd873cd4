//! The hex globe's grid: a Goldberg polyhedron `GP(f, 0)`, `10 f^2 + 2` tiles of which exactly 12
//! are pentagons, indexed as an integer atlas (`atlas.rs`) and placed on the unit sphere
//! (`project.rs`).
//!
//! Tiles have dense ids `0..tile_count()`: the north pole is 0, then the ten diamonds' `f x f`
//! tiles row by row, then the south pole. Neighbors come in a fixed order going round the tile;
//! `tile_at` and `neighbors` take constant time.

mod atlas;
mod climate;
mod editor;
mod edits;
mod fine;
mod fog;
pub(crate) mod grid;
mod map_type;
mod project;
mod props;
mod raycast;
mod rules;
mod stats;
mod terrain;

pub use editor::{GlobeChange, GlobeEditor, GlobeStroke};
pub use fog::{GLOBE_FOG_MAGIC, GLOBE_FOG_VERSION, GlobeFog};
pub use grid::{GlobeGrid, GlobeNeighbors, GlobeSize, GlobeTile, MAX_GLOBE_FREQUENCY};
pub use props::GlobeProp;
pub use raycast::GlobeRayHit;
pub use rules::{GLOBE_SIGHT_SAMPLES, GlobePath, GlobeTileInfo};
pub use stats::{GlobeLandmass, GlobeStats, POLAR_LATITUDE};
pub use terrain::{GlobeChunk, GlobeMesh, GlobePoint, GlobeTerrain};
