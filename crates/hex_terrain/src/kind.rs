//! Tile types: the thesis' three relief kinds, decided by a tile's center height, and the
//! height range each kind's vertices keep after manipulation.

use serde::{Deserialize, Serialize};

use crate::config::{ManipulationConfig, TerrainConfig};

/// The type of a tile, decided by the height of its center.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[repr(u8)]
pub enum TileKind {
    /// Center below the sea threshold.
    Sea = 0,
    /// Center between the thresholds.
    Land = 1,
    /// Center at or above the mountain threshold.
    Mountain = 2,
}

impl TileKind {
    /// All kinds, lowest first.
    pub const ALL: [Self; 3] = [Self::Sea, Self::Land, Self::Mountain];

    /// Lower-case name.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Sea => "sea",
            Self::Land => "land",
            Self::Mountain => "mountain",
        }
    }
}

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
