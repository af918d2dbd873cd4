//! What a stroke that could not be applied reports ([`EditError`]).

use hexx::Hex;

use super::MAX_BRUSH_RADIUS;
use crate::error::ConfigError;

/// A stroke that could not be applied; the map is unchanged.
///
/// Its `Debug` prints a tile as its two axial coordinates, so an error about any tile a caller
/// passed prints without overflow (hexx's `Debug` of a `Hex` computes its third coordinate).
#[derive(Clone, PartialEq, thiserror::Error)]
pub enum EditError {
    /// The stroke's tile is not on the map.
    #[error("tile ({}, {}) is not on the map", .0.x, .0.y)]
    OffMap(Hex),
    /// The stroke's tile is not one of the globe's: its id and the globe's tile count.
    #[error("tile {tile} is not on the globe: its tiles are 0..{tiles}")]
    OffGlobe {
        /// The tile's id.
        tile: u32,
        /// How many tiles the globe has.
        tiles: u32,
    },
    /// The tool's amount is not finite or outside its range.
    #[error("the tool's amount {value} is outside {allowed}")]
    Amount {
        /// The amount given.
        value: f32,
        /// What is allowed.
        allowed: &'static str,
    },
    /// The brush's range is above [`MAX_BRUSH_RADIUS`].
    #[error("the brush's range {radius} is above {}, the most a brush reaches", MAX_BRUSH_RADIUS)]
    Range {
        /// The range given.
        radius: u32,
    },
    /// The map has no rivers or lakes for the tool to work on.
    #[error("the {tool} tool needs {needs}")]
    Unsupported {
        /// The tool.
        tool: &'static str,
        /// The config fields it needs, in words.
        needs: &'static str,
    },
    /// No lake fits where the stroke digs: the lowest tile around it (`rim`) is within
    /// `rivers.min_lake_depth` of the sea threshold (`sea`), so a lake there would be sea.
    #[error("no lake fits here: the lowest tile around it is at {rim}, too close to the sea threshold {sea}")]
    NoLake {
        /// The raw center height of the lowest tile around the brush.
        rim: f32,
        /// The raw sea threshold.
        sea: f32,
    },
    /// The edited map is not a valid map (for example more than `MAX_EDITS` edited tiles).
    #[error(transparent)]
    Invalid(#[from] ConfigError),
}

impl std::fmt::Debug for EditError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::OffMap(tile) => f.debug_tuple("OffMap").field(&[tile.x, tile.y]).finish(),
            Self::OffGlobe { tile, tiles } => {
                f.debug_struct("OffGlobe").field("tile", tile).field("tiles", tiles).finish()
            }
            Self::Amount { value, allowed } => {
                f.debug_struct("Amount").field("value", value).field("allowed", allowed).finish()
            }
            Self::Range { radius } => f.debug_struct("Range").field("radius", radius).finish(),
            Self::Unsupported { tool, needs } => {
                f.debug_struct("Unsupported").field("tool", tool).field("needs", needs).finish()
            }
            Self::NoLake { rim, sea } => f.debug_struct("NoLake").field("rim", rim).field("sea", sea).finish(),
            Self::Invalid(e) => f.debug_tuple("Invalid").field(e).finish(),
        }
    }
}
