//! `hex_terrain_game`: 3D hexagonal tiled terrain for Bevy strategy games.
//!
//! This facade re-exports the plugin ([`bevy_hex_terrain`]) and the engine-agnostic core
//! ([`hex_terrain`]); `use hex_terrain_game::prelude::*` brings in what a game needs.

pub use bevy_hex_terrain::*;

/// The plugin's prelude.
pub mod prelude {
    pub use bevy_hex_terrain::prelude::*;
}

pub mod render_figures;
pub mod screenshot;
