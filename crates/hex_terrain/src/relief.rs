//! Relief (after manipulation): mountain tiles rise to a peak and hills swell, inside their
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

use crate::hash;
use crate::kind::TileKind;
use crate::terrain::Terrain;

impl Terrain {
    /// Applies relief to a manipulated height `h` (raw height `raw`) of lattice point `p` at
    /// `ring`, shared by tiles of `kinds`. The identity when the config's relief is off.
    #[inline]
    pub(crate) fn relief(&self, h: f32, raw: f32, p: Hex, ring: u32, kinds: &[TileKind]) -> f32 {
        let relief = &self.config.relief;
        let Some(&first) = kinds.first() else { return h };
        if !relief.any() || !self.config.manipulation.hex_unity || kinds.iter().any(|&k| k != first) {
            return h;
        }
        let n = self.lattice.subdivisions();
        let (lo, hi) = self.thresholds.range(first);
        let amount = match first {
            TileKind::Mountain => relief.peaks,
            TileKind::Land => {
                // Hills where the noise is in the upper half of the land range, fading in.
                let (s, m) = (self.thresholds.sea, self.thresholds.mountain);
                let x = ((raw - (s + m) * 0.5) / ((m - s) * 0.5)).clamp(0.0, 1.0);
                relief.hills * x * x * (3.0 - 2.0 * x)
            }
            TileKind::Sea => return h,
        };
        if amount <= 0.0 || hi <= lo {
            return h;
        }
        let q = self.wrap_point(p);
        let jitter = hash::unit(hash::hash(self.config.seed, &[i64::from(q.x), i64::from(q.y), 0x7e1e]));
        let profile = if ring < n {
            1.0 - ring as f32 / n as f32
        } else if first == TileKind::Mountain {
            // A saddle between mountains.
            0.35 * (1.0 - jitter)
        } else {
            return h;
        };
        let lift = amount * profile * (1.0 - relief.ridges * jitter);
        h.max(lo + (hi - lo) * lift.clamp(0.0, 1.0))
    }
}

#[cfg(test)]
mod tests;
