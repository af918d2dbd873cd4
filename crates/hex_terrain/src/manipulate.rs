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
        // The range's bounds are chosen, then mapped once: selects rather than branches, as
        // heights near a threshold go either way.
        let (in_min, in_max, out_min, out_max) = if h < s {
            (0.0, s, 0.0, s - t)
        } else if h < m {
            (s, m, s + t, m - t)
        } else {
            (m, 1.0, m + t, 1.0)
        };
        linear(h, in_min, in_max, out_min, out_max)
    }

    /// Height of a border vertex between tiles of different kinds: the threshold between them;
    /// sea next to mountain (with or without land) has no height in both ranges and takes the
    /// middle of the land range, halfway between the thresholds.
    #[must_use]
    #[inline]
    pub fn border(&self, lowest: TileKind, highest: TileKind) -> f32 {
        KindHeights::of(self).border(lowest, highest)
    }

    /// Pulls an inner vertex (ring `1..n`) of a tile of `kind` towards its range.
    #[must_use]
    #[inline]
    pub fn pull(&self, h: f32, kind: TileKind, mode: PullMode) -> f32 {
        let (lo, hi) = self.range(kind);
        self.pull_into(h, lo, hi, mode)
    }

    /// [`Thresholds::pull`] into the range `lo..=hi` (of the vertex's tile kind).
    #[must_use]
    #[inline]
    pub(crate) fn pull_into(&self, h: f32, lo: f32, hi: f32, mode: PullMode) -> f32 {
        match mode {
            // `f32::clamp`'s comparisons, without its check of the bounds (a branch that would
            // keep a batch of vertices from vectorising).
            PullMode::Clamp => {
                if h < lo {
                    lo
                } else if h > hi {
                    hi
                } else {
                    h
                }
            }
            PullMode::Thesis => {
                let (below, above) = ((lo + h) * 0.5, (hi + h) * 0.5);
                if h < lo {
                    below
                } else if h > hi {
                    above
                } else {
                    h
                }
            }
        }
    }
}

/// The heights manipulation selects among, as values: each kind's [`Thresholds::range`] and the
/// border heights of [`Thresholds::border`]. A loop over many vertices selects among them;
/// reading the thresholds' fields inside it instead, the compiler read them lane by lane, as
/// gathers.
#[derive(Clone, Copy)]
struct KindHeights {
    /// Sea's, land's and mountain's ranges.
    ranges: [(f32, f32); 3],
    sea_land: f32,
    land_mountain: f32,
    /// Sea next to mountain: the middle of the land range.
    middle: f32,
}

impl KindHeights {
    #[inline(always)]
    fn of(t: &Thresholds) -> Self {
        Self {
            ranges: TileKind::ALL.map(|kind| t.range(kind)),
            sea_land: t.sea,
            land_mountain: t.mountain,
            middle: (t.sea + t.mountain) * 0.5,
        }
    }

    /// [`Thresholds::range`], selected (no `match`, so that it vectorises).
    #[inline(always)]
    fn range(&self, kind: TileKind) -> (f32, f32) {
        let [sea, land, mountain] = self.ranges;
        if kind == TileKind::Sea {
            sea
        } else if kind == TileKind::Land {
            land
        } else {
            mountain
        }
    }

    #[inline(always)]
    fn border(&self, lowest: TileKind, highest: TileKind) -> f32 {
        if lowest == TileKind::Sea && highest == TileKind::Land {
            self.sea_land
        } else if lowest == TileKind::Land && highest == TileKind::Mountain {
            self.land_mountain
        } else {
            self.middle
        }
    }
}

/// Maps `x` from `[in_min, in_max]` to `[out_min, out_max]` (Algorithm 4).
#[inline]
fn linear(x: f32, in_min: f32, in_max: f32, out_min: f32, out_max: f32) -> f32 {
    let mapped = out_min + (x - in_min) * (out_max - out_min) / (in_max - in_min);
    if in_max <= in_min { out_min } else { mapped }
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

/// The lowest and highest of the kinds of the in-map tiles sharing a vertex (`None` when no
/// tile of the map holds it).
#[must_use]
#[inline]
pub fn span(kinds: &[TileKind]) -> Option<(TileKind, TileKind)> {
    let (&first, rest) = kinds.split_first()?;
    Some(rest.iter().fold((first, first), |(lo, hi), &k| (lo.min(k), hi.max(k))))
}

/// Applies the enabled stages to a vertex with raw height `raw`.
///
/// `ring`/`n` locate it in its tile; `span` is the lowest and highest kind of the in-map tiles
/// sharing it ([`span`]; an inner vertex has one tile, a border vertex up to three; `None`
/// outside the map). The one-vertex case of [`manipulate_lanes`], so the same bits.
#[must_use]
#[inline(always)]
pub fn manipulate(
    thresholds: &Thresholds,
    config: &ManipulationConfig,
    raw: f32,
    ring: u32,
    n: u32,
    span: Option<(TileKind, TileKind)>,
) -> Manipulated {
    let Some((lo, hi)) = span else {
        return Manipulated { height: thresholds.interpolate(raw), moved: false };
    };
    let (mut height, mut moved) = ([0.0], [false]);
    let v = Lanes { raw: &[raw], ring: &[ring], lo: &[lo], hi: &[hi] };
    manipulate_lanes(thresholds, config, n, &v, &mut height, &mut moved);
    Manipulated { height: height[0], moved: moved[0] }
}

/// `L` vertices for [`manipulate_lanes`], an array a quantity: raw heights, rings and the
/// lowest and highest kind of the tiles sharing each (all in the map).
#[derive(Debug, Clone, Copy)]
pub struct Lanes<'a, const L: usize> {
    /// Raw heights.
    pub raw: &'a [f32; L],
    /// Rings in their tiles (`n` on a border).
    pub ring: &'a [u32; L],
    /// Lowest kind of the tiles sharing each vertex.
    pub lo: &'a [TileKind; L],
    /// Highest kind of the tiles sharing each vertex.
    pub hi: &'a [TileKind; L],
}

/// [`manipulate`] of `L` vertices in the map at once, into `height` and `moved`. Every case is
/// computed and one selected, each step a loop over the lanes, so that it vectorises; every
/// lane does the operations of the one-vertex case in the same order.
#[inline(always)]
pub fn manipulate_lanes<const L: usize>(
    thresholds: &Thresholds,
    config: &ManipulationConfig,
    n: u32,
    v: &Lanes<'_, L>,
    height: &mut [f32; L],
    moved: &mut [bool; L],
) {
    let mut h = [0.0_f32; L];
    for (h, &raw) in h.iter_mut().zip(v.raw) {
        *h = thresholds.interpolate(raw);
    }
    let heights = KindHeights::of(thresholds);
    for l in 0..L {
        let (h, lo, hi, ring) = (h[l], v.lo[l], v.hi[l], v.ring[l]);
        let (a, b) = heights.range(lo);
        // An inner vertex has one tile (`lo == hi`): hex unity pulls it into that tile's range.
        let pulled = thresholds.pull_into(h, a, b, config.pull);
        let inner = if config.hex_unity && ring > 0 { pulled } else { h };
        // A border vertex between tiles of one kind: edge correction clamps it into the range
        // (`f32::clamp`'s comparisons, without its check of the bounds).
        let clamped = if h < a {
            a
        } else if h > b {
            b
        } else {
            h
        };
        let one_kind = if config.edge_correction { clamped } else { h };
        let between = if config.hex_unity { heights.border(lo, hi) } else { h };
        height[l] = if ring < n {
            inner
        } else if lo == hi {
            one_kind
        } else {
            between
        };
    }
    for ((moved, &height), &h) in moved.iter_mut().zip(height.iter()).zip(&h) {
        *moved = height != h;
    }
}

#[cfg(test)]
mod tests;
