//! Shaping filters of thesis section 7.1: island and mediterranean falloff (Algorithm 6,
//! eq. 7.1), inland remap (7.1.4) and the gradient effect (eq. 7.2).

use crate::config::Shape;

/// The map's extent in world units, used to normalise positions for the filters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeBounds {
    /// Smallest world x of a tile center.
    pub min_x: f64,
    /// Largest world x of a tile center.
    pub max_x: f64,
    /// Smallest world z of a tile center.
    pub min_z: f64,
    /// Largest world z of a tile center.
    pub max_z: f64,
    /// One lattice step as a fraction of the x extent: the smallest `x` of eq. 7.2.
    pub min_u: f64,
}

impl ShapeBounds {
    /// Position normalised to `[0, 1]²` over the map (clamped outside it).
    #[must_use]
    pub fn normalise(&self, x: f64, z: f64) -> (f64, f64) {
        let norm = |v: f64, lo: f64, hi: f64| if hi > lo { ((v - lo) / (hi - lo)).clamp(0.0, 1.0) } else { 0.5 };
        (norm(x, self.min_x, self.max_x), norm(z, self.min_z, self.max_z))
    }
}

/// Eq. 7.1: `f(d) = d^a / (d^a + (b - b d)^a)`, 0 at the center, 1 at the edges.
///
/// The powers come from `libm` (a pure-Rust port of musl's), not `f64::powf`, which calls the
/// platform's C library and may round differently on another platform: a seed gives the same
/// island everywhere.
#[must_use]
pub fn falloff(d: f64, a: f64, b: f64) -> f64 {
    let da = libm::pow(d, a);
    let denom = da + libm::pow(b - b * d, a);
    if denom > 0.0 { da / denom } else { 1.0 }
}

/// Applies `shape` to normalised height `h` at world `(x, z)`; the result is in `[0, 1]`.
#[must_use]
pub fn apply(shape: &Shape, bounds: Option<&ShapeBounds>, h: f64, x: f64, z: f64) -> f64 {
    let Some(bounds) = bounds else { return h };
    let (u, v) = bounds.normalise(x, z);
    // Algorithm 6: distance to the nearer edge in the max norm, 0 at the center, 1 at the edge.
    let edge = || (2.0 * u - 1.0).abs().max((2.0 * v - 1.0).abs());
    let out = match *shape {
        Shape::None => h,
        Shape::Island { a, b } => h * (1.0 - falloff(edge(), f64::from(a), f64::from(b))),
        Shape::Mediterranean { a, b } => h * falloff(edge(), f64::from(a), f64::from(b)),
        Shape::Inland { min, max } => f64::from(min) + h * f64::from(max - min),
        // mapX / x * z / mapZ, with x and z measured from the map's west and south edges; x
        // starts one lattice step in, as the thesis' vertex index does, so it never divides by 0.
        Shape::Gradient => h * v / u.max(bounds.min_u),
    };
    out.clamp(0.0, 1.0)
}
