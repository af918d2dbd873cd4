//! Manipulation, the first step of the vertex chain (thesis sections 5.5-5.6, 6.4): interpolation opens a gap around each
//! threshold (Algorithm 4), hex unity pulls inner vertices into their tile's range and puts
//! border vertices between kinds on the threshold (Algorithm 3), and edge/corner correction
//! clamps border vertices shared by tiles of one kind. After it, every non-border vertex of a
//! tile lies inside its kind's height range.

use crate::config::{ManipulationConfig, PullMode};
use crate::kind::{Thresholds, TileKind};

impl Thresholds {
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
