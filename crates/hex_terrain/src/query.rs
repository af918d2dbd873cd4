//! Surface queries: the tile under a world position, a tile's center on the surface, the
//! surface height as meshed, and ray casts against the real surface. All are answered from the
//! config, so they hold for tiles whose chunk was never generated.

use hexx::{Hex, Vec2};

use crate::terrain::Terrain;

/// A ray hitting the terrain surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayHit {
    /// World position of the hit.
    pub point: [f32; 3],
    /// Distance along the (normalised) ray.
    pub distance: f32,
    /// The tile under the hit.
    pub tile: Hex,
}

impl Terrain {
    /// The tile under world `(x, z)`.
    #[must_use]
    pub fn tile_at(&self, x: f32, z: f32) -> Hex {
        self.layout.world_pos_to_hex(Vec2::new(x, z))
    }

    /// World position of a tile's center on the surface.
    #[must_use]
    pub fn tile_center(&self, tile: Hex) -> [f32; 3] {
        let p = self.lattice.tile_center(tile);
        let [x, z] = self.lattice.world(p);
        [x as f32, self.vertex_elevation(p), z as f32]
    }

    /// World height of the surface (as meshed) at world `(x, z)`.
    #[must_use]
    pub fn surface_height(&self, x: f32, z: f32) -> f32 {
        let (tri, w) = self.lattice.triangle_at(f64::from(x), f64::from(z));
        let h: f64 = tri.iter().zip(w).map(|(&p, w)| w * f64::from(self.vertex_elevation(p))).sum();
        h as f32
    }

    /// First hit of a ray on the surface within `max_distance`, marching at a fraction of a
    /// lattice step and refining by bisection.
    #[must_use]
    pub fn raycast(&self, origin: [f32; 3], direction: [f32; 3], max_distance: f32) -> Option<RayHit> {
        let len = (direction[0].powi(2) + direction[1].powi(2) + direction[2].powi(2)).sqrt();
        if len.is_nan() || len <= 0.0 || !max_distance.is_finite() || origin.iter().any(|v| !v.is_finite()) {
            return None;
        }
        let d = direction.map(|v| v / len);
        let at = |t: f32| [origin[0] + d[0] * t, origin[1] + d[1] * t, origin[2] + d[2] * t];
        let above = |t: f32| {
            let p = at(t);
            p[1] - self.surface_height(p[0], p[2])
        };
        // Skip down to the highest possible surface quickly when looking from far above.
        let top = self.config.terrain.max_elevation;
        let mut t0 = 0.0;
        if origin[1] > top && d[1] < 0.0 {
            t0 = (origin[1] - top) / -d[1];
        }
        let step = (self.config.layout.hex_size / self.lattice.subdivisions() as f32 * 0.5).max(1e-4);
        let mut prev = above(t0);
        if prev < 0.0 {
            return None;
        }
        let mut t = t0;
        while t < max_distance {
            let next = (t + step).min(max_distance);
            let h = above(next);
            if h <= 0.0 {
                let (mut lo, mut hi) = (t, next);
                for _ in 0..24 {
                    let mid = 0.5 * (lo + hi);
                    if above(mid) > 0.0 { lo = mid } else { hi = mid }
                }
                let point = at(hi);
                return Some(RayHit { point, distance: hi, tile: self.tile_at(point[0], point[2]) });
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
}
