//! Relief, the step of the vertex chain after manipulation: mountain tiles rise to a peak and hills swell, inside their
//! tile type's height range, so a mountain reads as a mountain and not as a grey plateau.
//!
//! Manipulation leaves a mountain tile's inner vertices wherever the noise put them, clamped
//! into the mountain range; with the gentle noise of a strategy map that is a flat top just
//! above the threshold. Relief raises an inner vertex to at least a profile that falls from the
//! tile's center (ring 0) to its border (ring `n`): `lo + (hi - lo) · peaks · (1 - ring / n)`,
//! lowered per vertex by up to `ridges` of itself from a hash of the (canonical) lattice point,
//! which breaks the cone into ridges and gullies. Border vertices shared only by mountains rise
//! to a saddle between the peaks (a `ridges`-jittered fraction of the peak height), so
//! neighboring mountains join into ranges. Land tiles whose noise lies in the upper part of the
//! land range swell by `hills` the same way (a hill, lower and rounder).
//!
//! Relief shapes tiles inside the ranges hex unity puts them in, so it needs hex unity: with hex
//! unity off (the raw map of the thesis' figures and sharpness baseline) it does nothing.
//!
//! Every change is `max(height, profile)` with `profile` inside `[lo, hi]` of the vertex's
//! kind, so a vertex inside its range stays inside it; border vertices between kinds are not
//! touched (hex unity keeps them on the threshold). A vertex's profile depends on its position,
//! ring and the kinds around it only: chunks agree at their seams.

use hexx::Hex;

use crate::config::MapConfig;
use crate::geometry::Geometry;
use crate::hash;
use crate::kind::Thresholds;
use crate::vocab::TileKind;

/// The relief of a map: how high peaks, ridges and hills rise (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Relief {
    peaks: f32,
    ridges: f32,
    hills: f32,
    /// Relief is on (some peaks or hills, and hex unity).
    active: bool,
    thresholds: Thresholds,
    seed: u32,
    subdivisions: u32,
}

impl Relief {
    /// The relief of a validated config.
    #[must_use]
    pub fn new(config: &MapConfig, thresholds: Thresholds) -> Self {
        let r = &config.relief;
        Self {
            peaks: r.peaks,
            ridges: r.ridges,
            hills: r.hills,
            active: r.any() && config.manipulation.hex_unity,
            thresholds,
            seed: config.seed,
            subdivisions: config.subdivisions(),
        }
    }

    /// Whether relief lifts anything (else [`Relief::apply`] returns the height it is given).
    #[must_use]
    pub(crate) fn is_active(&self) -> bool {
        self.active
    }

    /// Applies relief to a manipulated height `h` (raw height `raw`) of lattice point `p` at
    /// `ring`, shared by tiles of `kinds`. The identity when the config's relief is off.
    #[must_use]
    #[inline]
    pub fn apply(&self, geometry: &Geometry, h: f32, raw: f32, p: Hex, ring: u32, kinds: &[TileKind]) -> f32 {
        let Some(&first) = kinds.first() else { return h };
        if !self.active || kinds.iter().any(|&k| k != first) {
            return h;
        }
        let n = self.subdivisions;
        let (lo, hi) = self.thresholds.range(first);
        let amount = match first {
            TileKind::Mountain => self.peaks,
            TileKind::Land => {
                // Hills where the noise is in the upper half of the land range, fading in.
                let (s, m) = (self.thresholds.sea, self.thresholds.mountain);
                let x = ((raw - (s + m) * 0.5) / ((m - s) * 0.5)).clamp(0.0, 1.0);
                self.hills * x * x * (3.0 - 2.0 * x)
            }
            TileKind::Sea => return h,
        };
        if amount <= 0.0 || hi <= lo {
            return h;
        }
        let q = geometry.wrap_point(p);
        let jitter = hash::unit(hash::hash(self.seed, &[i64::from(q.x), i64::from(q.y), 0x7e1e]));
        let profile = if ring < n {
            1.0 - ring as f32 / n as f32
        } else if first == TileKind::Mountain {
            // A saddle between mountains.
            0.35 * (1.0 - jitter)
        } else {
            return h;
        };
        let lift = amount * profile * (1.0 - self.ridges * jitter);
        h.max(lo + (hi - lo) * lift.clamp(0.0, 1.0))
    }
}

#[cfg(test)]
mod tests;
