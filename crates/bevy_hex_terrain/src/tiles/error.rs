//! What a write of the tile states refuses, on a flat map and on a globe.

use hex_terrain::TileRect;
use hex_terrain::hexx::Hex;
use hex_terrain::save::MAX_OWNERS;

/// A write [`TileStates`](super::TileStates) or [`GlobeTileStates`](crate::GlobeTileStates) refused; the state is unchanged.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TileStateError {
    /// The tile is not on the (bounded) map.
    #[error("tile ({}, {}) is outside the map: columns {}..{} and rows {}..{} (offset coordinates) are allowed, it is at column {} row {}", .tile.x, .tile.y, .bounds.min[0], .bounds.max[0], .bounds.min[1], .bounds.max[1], .offset[0], .offset[1])]
    OutsideMap {
        /// The tile.
        tile: Hex,
        /// Its offset coordinate.
        offset: [i32; 2],
        /// The map's tiles.
        bounds: TileRect,
    },
    /// The tile is not one of the globe's ([`GlobeTileStates`](crate::GlobeTileStates)).
    #[error("tile {tile} is not on the globe: its tiles are 0..{tiles} (none before the globe has loaded)")]
    NotOnGlobe {
        /// The tile's id.
        tile: u32,
        /// How many tiles the globe has.
        tiles: u32,
    },
    /// An owner past the last player [`MAX_OWNERS`] allows.
    #[error("owner {owner} is out of range: owners are players 0..{MAX_OWNERS} (None for nobody)")]
    OwnerOutOfRange {
        /// The player given.
        owner: u32,
    },
    /// A player the fog of war shown ([`TileStates::show_fog`](super::TileStates::show_fog)) does not have.
    #[error("player {player}: the fog has players 0..{players}")]
    NoSuchPlayer {
        /// The player given.
        player: u32,
        /// How many players the fog has.
        players: u32,
    },
    /// An overlay color with a NaN or infinite component.
    #[error("overlay color {color:?} is not finite: every component must be a number in 0..=1")]
    OverlayNotFinite {
        /// The color given.
        color: [f32; 4],
    },
}
