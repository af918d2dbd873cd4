//! Ray casts against a globe's surface as meshed: the first fine triangle a ray meets, and the
//! tile it belongs to. Answered from the stages (no chunk need be generated), in f64, with the
//! globe's center at the origin.
//!
//! The ray is followed only through the shell between the sphere of height 0 and the sphere of
//! the highest possible surface, half a tile at a time; the tiles under it and their neighbors
//! are tested triangle by triangle (Möller-Trumbore), in the order the ray reaches them, until no
//! tile still ahead can hold a nearer hit.

use std::collections::HashSet;

use super::GlobeTile;
use super::project::{self, Dir, hit};
use super::terrain::GlobeTerrain;

/// A ray hitting a globe's surface ([`GlobeTerrain::raycast`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GlobeRayHit {
    /// Where the ray meets the surface, from the globe's center, in world units.
    pub point: [f64; 3],
    /// Distance along the (normalised) ray.
    pub distance: f64,
    /// The tile whose fine triangle it meets.
    pub tile: GlobeTile,
}

impl GlobeTerrain {
    /// The first point within `max_distance` where a ray from `origin` (world units, from the
    /// globe's center) along `direction` (any length but zero) meets the surface as meshed, and
    /// its tile; `None` when it misses, or for a zero or non-finite ray or a NaN distance. Any
    /// `max_distance` is fine (`f64::MAX` for no limit).
    #[must_use]
    pub fn raycast(&self, origin: [f64; 3], direction: [f64; 3], max_distance: f64) -> Option<GlobeRayHit> {
        let len = project::dot(direction, direction).sqrt();
        if !len.is_finite() || len == 0.0 || max_distance.is_nan() || origin.iter().any(|v| !v.is_finite()) {
            return None;
        }
        let d = direction.map(|v| v / len);
        let terrain = &self.config().terrain;
        let inner = self.radius();
        // A vertex at the highest height may round an ulp above it.
        let outer = inner + f64::from(terrain.max_elevation) * (1.0 + 1e-9) + 1e-9;
        let (t0, t1) = shell(origin, d, inner, outer)?;
        let end = t1.min(max_distance);
        if t0 > end {
            return None;
        }
        let tiles = f64::from(self.grid().tile_count());
        let width = outer * (4.0 * std::f64::consts::PI / tiles).sqrt();
        let step = width / 2.0;
        let mut tested: HashSet<GlobeTile> = HashSet::new();
        let mut best: Option<GlobeRayHit> = None;
        let mut t = t0;
        loop {
            // No tile first met past the best hit and a tile beyond can hold a nearer one.
            if best.is_some_and(|b| t > b.distance + 2.0 * width) || t > end + step {
                break;
            }
            let at = [origin[0] + d[0] * t, origin[1] + d[1] * t, origin[2] + d[2] * t];
            if let Some(tile) = self.tile_at(at) {
                let neighbors = self.grid().neighbors(tile).expect("a tile of the globe");
                for &candidate in std::iter::once(&tile).chain(neighbors.as_slice()) {
                    if !tested.insert(candidate) {
                        continue;
                    }
                    for [a, b, c] in self.tile_triangles(candidate) {
                        if let Some(s) = hit(origin, d, a, b, c).filter(|&s| s >= 0.0 && s <= end)
                            && best.is_none_or(|h| s < h.distance)
                        {
                            let point = [origin[0] + d[0] * s, origin[1] + d[1] * s, origin[2] + d[2] * s];
                            best = Some(GlobeRayHit { point, distance: s, tile: candidate });
                        }
                    }
                }
            }
            t += step;
        }
        best
    }
}

/// Where a ray from `o` along unit `d` is between the spheres of radius `inner` and `outer`
/// round the origin: from where it enters the outer one (or 0 inside it) to where it reaches the
/// inner one or leaves the outer; `None` if it never enters.
fn shell(o: Dir, d: Dir, inner: f64, outer: f64) -> Option<(f64, f64)> {
    let b = project::dot(o, d);
    let c = project::dot(o, o);
    let enter = |r: f64| {
        let disc = b * b - (c - r * r);
        (disc >= 0.0).then(|| (-b - disc.sqrt(), -b + disc.sqrt()))
    };
    let (near, far) = enter(outer)?;
    if far < 0.0 {
        return None;
    }
    let start = near.max(0.0);
    let stop = match enter(inner) {
        Some((hit, _)) if hit >= start => hit,
        _ => far,
    };
    Some((start, stop))
}
