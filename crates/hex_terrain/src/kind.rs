//! Classification, the third stage: a tile's type (the thesis' three relief kinds) decided by
//! its center height, and the height range each kind's vertices keep after manipulation.

use hexx::Hex;

use crate::config::{ManipulationConfig, TerrainConfig};
use crate::geometry::Geometry;
use crate::heights::HeightField;
pub use crate::vocab::TileKind;

/// Thresholds and the height ranges of each tile type, in normalised height.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct Thresholds {
    /// Sea threshold.
    pub sea: f32,
    /// Mountain threshold.
    pub mountain: f32,
    /// Interpolation tolerance in effect (0 when interpolation is off).
    pub tolerance: f32,
}

impl Thresholds {
    /// Thresholds of a config, with the tolerance only when interpolation is on.
    #[must_use]
    pub fn new(terrain: &TerrainConfig, manipulation: &ManipulationConfig) -> Self {
        Self {
            sea: terrain.sea_threshold,
            mountain: terrain.mountain_threshold,
            tolerance: if manipulation.interpolation { terrain.interpolation_tolerance } else { 0.0 },
        }
    }

    /// Type of a tile whose center has raw (shaped, not interpolated) height `h`.
    #[must_use]
    #[inline]
    pub fn classify(&self, h: f32) -> TileKind {
        if h < self.sea {
            TileKind::Sea
        } else if h < self.mountain {
            TileKind::Land
        } else {
            TileKind::Mountain
        }
    }

    /// Height range every non-border vertex of a tile of `kind` lies in after manipulation.
    #[must_use]
    #[inline]
    pub fn range(&self, kind: TileKind) -> (f32, f32) {
        match kind {
            TileKind::Sea => (0.0, self.sea - self.tolerance),
            TileKind::Land => (self.sea + self.tolerance, self.mountain - self.tolerance),
            TileKind::Mountain => (self.mountain + self.tolerance, 1.0),
        }
    }
}

impl Thresholds {
    /// Type of a tile (by its center), whether or not it is in the map.
    #[must_use]
    #[inline]
    pub fn tile_kind(&self, geometry: &Geometry, heights: &HeightField, tile: Hex) -> TileKind {
        self.classify(heights.raw_height(geometry, geometry.lattice().tile_center(tile)))
    }

    /// Type of a tile if it belongs to the map.
    #[must_use]
    #[inline]
    pub fn map_tile_kind(&self, geometry: &Geometry, heights: &HeightField, tile: Hex) -> Option<TileKind> {
        geometry.contains(tile).then(|| self.tile_kind(geometry, heights, tile))
    }
}
