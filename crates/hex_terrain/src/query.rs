//! Surface queries, read from the pipeline: the tile under a world position, a tile's center on the surface, the
//! surface height as meshed, and ray casts against the real surface. All are answered from the
//! stages, so they hold for tiles whose chunk was never generated.
//!
//! Positions are f64 world coordinates, so the answers stay exact far from the world's origin
//! (an f32 coordinate a million units out is only good to an eighth of a unit). On a wrapping
//! map the tiles they return are the map's own ([`Geometry::wrap_tile`](crate::geometry::Geometry::wrap_tile)) and the heights those of
//! the map's surface placed again: a position one map width east is the same place.

use hexx::Hex;

use crate::pipeline::Pipeline;

/// A ray hitting the terrain surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayHit {
    /// World position of the hit.
    pub point: [f64; 3],
    /// Distance along the (normalised) ray.
    pub distance: f64,
    /// The tile under the hit (the map's own tile on a wrapping map).
    pub tile: Hex,
}

/// Most marching steps of one `raycast`, each to the next lattice line the ray crosses (a
/// few a lattice step): a ray that stays inside the relief is followed for about 2^17 hex
/// sizes at the default ring count.
pub const MAX_RAY_STEPS: u32 = 1 << 20;

/// World position of a tile's center on the surface (for a tile past a wrapping map's edge,
/// where it is drawn there); `None` for a tile past the world
/// ([`Geometry::in_world`](crate::geometry::Geometry::in_world)).
#[must_use]
pub fn tile_center(pipeline: &Pipeline, tile: Hex) -> Option<[f64; 3]> {
    if !pipeline.geometry().in_world(tile) {
        return None;
    }
    let lattice = pipeline.geometry().lattice();
    let p = lattice.tile_center(tile);
    let [x, z] = lattice.world(p);
    Some([x, f64::from(pipeline.vertex_elevation(p)), z])
}

/// World height of the surface (as meshed) at world `(x, z)`; `None` past the world. On a
/// wrapping map, any finite `x` answers: the position is reduced to the map's period first
/// ([`Geometry::wrap_position`](crate::geometry::Geometry::wrap_position)).
#[must_use]
pub fn surface_height(pipeline: &Pipeline, x: f64, z: f64) -> Option<f64> {
    interpolate(pipeline, x, z, |p| pipeline.vertex_elevation(p))
}

/// The surface height at world `(x, z)` from the elevations of the lattice triangle's corners
/// under it, which `elevation` gives; `None` past the world.
fn interpolate(pipeline: &Pipeline, x: f64, z: f64, mut elevation: impl FnMut(Hex) -> f32) -> Option<f64> {
    let geometry = pipeline.geometry();
    let (x, z) = geometry.wrap_position(x, z);
    // The three corners of the triangle are at most one tile from the tile under it.
    geometry.unwrapped_tile_at(x, z)?;
    let (tri, w) = geometry.lattice().triangle_at(x, z);
    Some(tri.iter().zip(w).map(|(&p, w)| w * f64::from(elevation(p))).sum())
}

/// The last few lattice vertices' elevations a ray march asked for.
#[derive(Default)]
struct Corners {
    points: [Option<(Hex, f32)>; 12],
    next: usize,
}

impl Corners {
    fn elevation(&mut self, pipeline: &Pipeline, p: Hex) -> f32 {
        if let Some((_, h)) = self.points.iter().flatten().find(|(q, _)| *q == p) {
            return *h;
        }
        let h = pipeline.vertex_elevation(p);
        self.points[self.next] = Some((p, h));
        self.next = (self.next + 1) % self.points.len();
        h
    }
}

/// Upward unit normal of the surface (as meshed: the flat lattice triangle under the point) at
/// world `(x, z)`; `None` past the world.
#[must_use]
pub fn surface_normal(pipeline: &Pipeline, x: f64, z: f64) -> Option<[f64; 3]> {
    let geometry = pipeline.geometry();
    let (x, z) = geometry.wrap_position(x, z);
    geometry.unwrapped_tile_at(x, z)?;
    let (tri, _) = geometry.lattice().triangle_at(x, z);
    let [a, b, c] = tri.map(|p| {
        let [wx, wz] = geometry.lattice().world(p);
        [wx, f64::from(pipeline.vertex_elevation(p)), wz]
    });
    let (u, v) = ([b[0] - a[0], b[1] - a[1], b[2] - a[2]], [c[0] - a[0], c[1] - a[1], c[2] - a[2]]);
    let n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    let sign = if n[1] < 0.0 { -1.0 } else { 1.0 };
    (len > 0.0).then(|| n.map(|v| sign * v / len))
}

/// First hit of a ray on the surface within `max_distance`, marching from one lattice line the
/// ray crosses to the next (the surface is flat on each lattice triangle, so no hit lies between
/// two such points unseen) and refining by bisection. Any `max_distance` is fine (`f32::MAX` for no limit): the
/// march covers only the part of the ray between the highest and the lowest possible surface,
/// and gives up after [`MAX_RAY_STEPS`] steps or where the ray leaves the world. On a wrapping
/// map the ray's origin is first moved by whole periods next to the map (exactly), and the hit
/// moved back, so a ray a billion units east hits what one over the map does.
#[must_use]
pub fn raycast(pipeline: &Pipeline, origin: [f64; 3], direction: [f64; 3], max_distance: f64) -> Option<RayHit> {
    let len = (direction[0].powi(2) + direction[1].powi(2) + direction[2].powi(2)).sqrt();
    if !len.is_finite() || len <= 0.0 || max_distance.is_nan() || origin.iter().any(|v| !v.is_finite()) {
        return None;
    }
    let geometry = pipeline.geometry();
    // March in f64, so a step stays a step however far along the ray.
    let d = direction.map(|v| v / len);
    let (x, _) = geometry.wrap_position(origin[0], origin[2]);
    let shift = origin[0] - x;
    let o = [x, origin[1], origin[2]];
    let at = |t: f64| [o[0] + d[0] * t, o[1] + d[1] * t, o[2] + d[2] * t];
    // Consecutive samples (a lattice line apart, then the bisection) fall in the same few
    // triangles: their vertices' heights are kept, not evaluated again.
    let cache = std::cell::RefCell::new(Corners::default());
    let above = |t: f64| {
        let p = at(t);
        let mut cache = cache.borrow_mut();
        interpolate(pipeline, p[0], p[2], |q| cache.elevation(pipeline, q)).map(|h| p[1] - h)
    };
    // The surface lies between 0 and the maximum elevation: skip down to the top quickly
    // when looking from far above, and stop below the bottom. The top is raised by a margin:
    // a vertex at the maximum elevation may round an f32 ulp above it (and the interpolation
    // an f64 ulp more), and a march that starts inside the surface misses it.
    let top = f64::from(pipeline.max_elevation()) * (1.0 + 8.0 * f64::from(f32::EPSILON)) + 1e-12;
    if o[1] > top && d[1] >= 0.0 {
        return None;
    }
    let t0 = if o[1] > top { (o[1] - top) / -d[1] } else { 0.0 };
    let mut end = max_distance;
    if d[1] < 0.0 {
        end = end.min(o[1].max(0.0) / -d[1] + 1.0);
    }
    // The surface is flat on each lattice triangle, so along the ray the height above it is
    // linear between two crossings of lattice lines (the lines of constant i, j and i + j of the
    // lattice coordinates): the march goes from crossing to crossing, and a ray that grazes a
    // peak between two crossings cannot be missed.
    let (sa, sb) = geometry.lattice().steps();
    let det = sa[0] * sb[1] - sb[0] * sa[1];
    let lattice = |x: f64, z: f64| [(x * sb[1] - z * sb[0]) / det, (sa[0] * z - sa[1] * x) / det];
    let (f0, df) = (lattice(o[0], o[2]), lattice(d[0], d[2]));
    let lines = [(f0[0], df[0]), (f0[1], df[1]), (f0[0] + f0[1], df[0] + df[1])];
    let next_line = |t: f64| {
        let mut best = f64::INFINITY;
        for &(g0, dg) in &lines {
            if dg.abs() < 1e-12 {
                continue;
            }
            let v = g0 + dg * t;
            let mut k = if dg > 0.0 { v.floor() + 1.0 } else { v.ceil() - 1.0 };
            let mut tk = (k - g0) / dg;
            if tk <= t {
                // Rounding put `t` just short of the line it stands on: the one after.
                k += dg.signum();
                tk = (k - g0) / dg;
            }
            best = best.min(tk);
        }
        best
    };
    let mut prev = above(t0)?;
    if prev < 0.0 {
        return None;
    }
    let mut t = t0;
    for _ in 0..MAX_RAY_STEPS {
        if t >= end {
            break;
        }
        let next = next_line(t).min(end);
        // No progress (or NaN): the ray has left what f64 can follow.
        if next.partial_cmp(&t) != Some(std::cmp::Ordering::Greater) {
            break;
        }
        let h = above(next)?;
        if h <= 0.0 {
            let (mut lo, mut hi) = (t, next);
            for _ in 0..32 {
                let mid = 0.5 * (lo + hi);
                if above(mid).is_some_and(|h| h > 0.0) { lo = mid } else { hi = mid }
            }
            let [px, py, pz] = at(hi);
            let tile = geometry.tile_at(px, pz)?;
            return Some(RayHit { point: [px + shift, py, pz], distance: hi, tile });
        }
        prev = h;
        t = next;
        // A ray going up and already above every possible height never comes back.
        if d[1] >= 0.0 && at(t)[1] > top && prev > 0.0 {
            return None;
        }
    }
    None
}
