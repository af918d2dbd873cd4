//! Tile types and the height manipulations that make them easy to recognise
//! (thesis sections 5.5-5.6, 6.4).

use serde::{Deserialize, Serialize};

use crate::config::{ManipulationConfig, PullMode, TerrainConfig};

/// The type of a tile, decided by the height of its centre.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[repr(u8)]
pub enum TileKind {
    /// Centre below the sea threshold.
    Sea = 0,
    /// Centre between the thresholds.
    Land = 1,
    /// Centre at or above the mountain threshold.
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

    /// Type of a tile whose centre has raw (shaped, not interpolated) height `h`.
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

    /// Algorithm 4 / eq. 5.6 with a gap on both sides of each threshold: sea `[0, s]` maps to
    /// `[0, s - t]`, land `[s, m]` to `[s + t, m - t]`, mountain `[m, 1]` to `[m + t, 1]`.
    /// The identity when the tolerance is 0.
    #[must_use]
    #[inline]
    pub fn interpolate(&self, h: f32) -> f32 {
        let t = self.tolerance;
        if t == 0.0 {
            return h;
        }
        let (s, m) = (self.sea, self.mountain);
        if h < s {
            linear(h, 0.0, s, 0.0, s - t)
        } else if h < m {
            linear(h, s, m, s + t, m - t)
        } else {
            linear(h, m, 1.0, m + t, 1.0)
        }
    }

    /// Height of a border vertex between tiles of different kinds: the threshold between them;
    /// sea next to mountain (with or without land) has no height in both ranges and takes the
    /// middle of the land range, halfway between the thresholds.
    #[must_use]
    #[inline]
    pub fn border(&self, lowest: TileKind, highest: TileKind) -> f32 {
        match (lowest, highest) {
            (TileKind::Sea, TileKind::Land) => self.sea,
            (TileKind::Land, TileKind::Mountain) => self.mountain,
            _ => (self.sea + self.mountain) * 0.5,
        }
    }

    /// Pulls an inner vertex (ring `1..n`) of a tile of `kind` towards its range.
    #[must_use]
    #[inline]
    pub fn pull(&self, h: f32, kind: TileKind, mode: PullMode) -> f32 {
        let (lo, hi) = self.range(kind);
        match mode {
            PullMode::Clamp => h.clamp(lo, hi),
            PullMode::Thesis => {
                if h < lo {
                    (lo + h) * 0.5
                } else if h > hi {
                    (hi + h) * 0.5
                } else {
                    h
                }
            }
        }
    }
}

/// Maps `x` from `[in_min, in_max]` to `[out_min, out_max]` (Algorithm 4).
#[inline]
fn linear(x: f32, in_min: f32, in_max: f32, out_min: f32, out_max: f32) -> f32 {
    if in_max <= in_min {
        return out_min;
    }
    out_min + (x - in_min) * (out_max - out_min) / (in_max - in_min)
}

/// What manipulation did to one vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Manipulated {
    /// Height after interpolation and hex unity.
    pub height: f32,
    /// Whether hex unity or edge/corner correction moved it (interpolation alone does not
    /// count, as in the thesis' tables).
    pub moved: bool,
}

/// Applies the enabled stages to a vertex with raw height `raw`.
///
/// `ring`/`n` locate it in its tile; `kinds` are the kinds of the in-map tiles sharing it (one
/// for an inner vertex, up to three on a border; none outside the map).
#[must_use]
#[inline(always)]
pub fn manipulate(
    thresholds: &Thresholds,
    config: &ManipulationConfig,
    raw: f32,
    ring: u32,
    n: u32,
    kinds: &[TileKind],
) -> Manipulated {
    let h = thresholds.interpolate(raw);
    let Some(&first) = kinds.first() else {
        return Manipulated { height: h, moved: false };
    };
    let out = if ring < n {
        if config.hex_unity && ring > 0 { thresholds.pull(h, first, config.pull) } else { h }
    } else {
        let (lo, hi) = kinds.iter().fold((first, first), |(lo, hi), &k| (lo.min(k), hi.max(k)));
        if lo == hi {
            if config.edge_correction {
                let (a, b) = thresholds.range(lo);
                h.clamp(a, b)
            } else {
                h
            }
        } else if config.hex_unity {
            thresholds.border(lo, hi)
        } else {
            h
        }
    };
    Manipulated { height: out, moved: out != h }
}

#[cfg(test)]
mod tests;
