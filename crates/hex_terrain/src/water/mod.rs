//! Water: the network of rivers and lakes of a bounded map ([`hydrology`], built once with the
//! per-map tile table; rivers on tile edges in [`edges`]), the cover of river channels and lakes on each lattice point
//! ([`channels`], which the vertex chain carves by), and the water surface over a generated
//! chunk ([`surface`]).

pub mod channels;
mod corners;
mod descent;
pub mod edges;
pub mod hydrology;
pub mod surface;

pub use edges::{EdgeRivers, RiverEdge};
pub use hydrology::{Hydrology, RiverTile};
pub use surface::{WaterBuffers, water_surface};
