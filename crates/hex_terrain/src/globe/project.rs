//! From the atlas to the sphere and back: the icosahedron's vertices, a diamond point's
//! direction, and the tile a direction falls in.
//!
//! A point `(u, v)` of a diamond (in units of its side) lies on one of its two faces, `O B D`
//! where `u >= v` and `O D C` where `v >= u`; its place on the face's plane is the affine mix of
//! the face's corners, warped toward the corners so that the tiles come out of nearly equal
//! area, and its direction is that place from the globe's center (a central projection). The
//! way back finds the face a direction passes through (the one whose plane it meets first, as
//! every face is at the same distance from the center), where it meets the plane, undoes the
//! warp, and rounds to the nearest lattice point: constant time, no search over tiles.

use super::atlas::Spot;

/// A unit vector, in f64.
pub(crate) type Dir = [f64; 3];

fn add(a: Dir, b: Dir) -> Dir {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

pub(crate) fn sub(a: Dir, b: Dir) -> Dir {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(crate) fn cross(a: Dir, b: Dir) -> Dir {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn scale(a: Dir, s: f64) -> Dir {
    [a[0] * s, a[1] * s, a[2] * s]
}

pub(crate) fn dot(a: Dir, b: Dir) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn normalize(a: Dir) -> Dir {
    scale(a, 1.0 / dot(a, a).sqrt())
}

/// The direction at latitude `lat` and longitude `lon` (radians): `y` is the globe's axis (north
/// up), longitude grows eastward, counterclockwise seen from above the north pole.
pub(crate) fn from_lat_lon(lat: f64, lon: f64) -> Dir {
    [lat.cos() * lon.cos(), lat.sin(), -lat.cos() * lon.sin()]
}

/// The icosahedron's vertices: `N`, `U0..U4`, `L0..L4`, `S`.
struct Vertices {
    north: Dir,
    upper: [Dir; 5],
    lower: [Dir; 5],
    south: Dir,
}

fn vertices() -> Vertices {
    let lat = 0.5f64.atan();
    let step = std::f64::consts::TAU / 5.0;
    Vertices {
        north: [0.0, 1.0, 0.0],
        upper: std::array::from_fn(|k| from_lat_lon(lat, step * k as f64)),
        lower: std::array::from_fn(|k| from_lat_lon(-lat, step * (k as f64 + 0.5))),
        south: [0.0, -1.0, 0.0],
    }
}

/// A diamond's corners `[O, B, C, D]` (see the atlas).
fn corners(v: &Vertices, d: u8) -> [Dir; 4] {
    let k = usize::from(d % 5);
    let next = (k + 1) % 5;
    if d < 5 {
        [v.upper[k], v.north, v.lower[k], v.upper[next]]
    } else {
        [v.lower[k], v.upper[next], v.south, v.lower[next]]
    }
}

/// One face of a diamond, with what the way back needs.
#[derive(Debug, Clone, Copy)]
struct Face {
    d: u8,
    /// `O B D` (false) or `O D C` (true).
    upper: bool,
    /// The face's corners in the order the warp reads them: `[O, B, D]` or `[O, C, D]`.
    corners: [Dir; 3],
    /// The face's unit normal, outward.
    normal: Dir,
}

/// The projection's tables: the diamonds' corners and the faces, built once per grid.
#[derive(Debug, Clone)]
pub(crate) struct Projection {
    diamonds: [[Dir; 4]; 10],
    faces: [Face; 20],
    /// The faces' distance from the center (the icosahedron's inradius over its circumradius).
    inradius: f64,
}

impl Projection {
    pub(crate) fn new() -> Self {
        let v = vertices();
        let diamonds: [[Dir; 4]; 10] = std::array::from_fn(|d| corners(&v, d as u8));
        let faces: [Face; 20] = std::array::from_fn(|n| {
            let d = (n / 2) as u8;
            let [o, b, c, dd] = diamonds[usize::from(d)];
            let upper = n % 2 == 1;
            let corners = if upper { [o, c, dd] } else { [o, b, dd] };
            let centroid = scale(add(add(corners[0], corners[1]), corners[2]), 1.0 / 3.0);
            Face { d, upper, corners, normal: normalize(centroid) }
        });
        let inradius = dot(faces[0].normal, faces[0].corners[0]);
        Self { diamonds, faces, inradius }
    }

    /// The direction of the point `(u, v)` of diamond `d`, both in `[0, 1]`.
    pub(crate) fn direction(&self, d: u8, u: f64, v: f64) -> Dir {
        normalize(self.toward(d, u, v))
    }

    /// A vector toward the point `(u, v)` of diamond `d` (its direction before it is
    /// normalised: [`normalize`] of it is [`Projection::direction`], bit for bit).
    pub(crate) fn toward(&self, d: u8, u: f64, v: f64) -> Dir {
        let [o, b, c, dd] = self.diamonds[usize::from(d)];
        // Barycentric weights on the face: the two steps along it, then the warp.
        let (corners, s, t) = if u >= v { ([o, b, dd], u - v, v) } else { ([o, c, dd], v - u, u) };
        // The warped weights' sum is left out: the direction is the same at any scale.
        let [w0, w1, w2] = [1.0 - s - t, s, t].map(bend);
        add(add(scale(corners[0], w0), scale(corners[1], w1)), scale(corners[2], w2))
    }

    /// Each diamond's cap: the direction of its middle and the angle from it that holds the
    /// whole diamond (its edges are great circles, so the cap through its farthest corner).
    pub(crate) fn diamond_caps(&self) -> Vec<(Dir, f64)> {
        (0..10u8)
            .map(|d| {
                let middle = self.direction(d, 0.5, 0.5);
                let angle = self.diamonds[usize::from(d)]
                    .iter()
                    .map(|&c| dot(middle, c).clamp(-1.0, 1.0).acos())
                    .fold(0.0, f64::max);
                (middle, angle + 1e-9)
            })
            .collect()
    }

    /// The diamond and the point `(u, v)` a unit direction passes through.
    pub(crate) fn locate(&self, dir: Dir) -> (u8, f64, f64) {
        let face = self
            .faces
            .iter()
            .max_by(|a, b| dot(dir, a.normal).total_cmp(&dot(dir, b.normal)))
            .expect("an icosahedron has faces");
        // Where the direction meets the face's plane, as weights of its corners.
        let q = scale(dir, self.inradius / dot(dir, face.normal));
        let [a, b, c] = face.corners;
        let (e1, e2, r) = (sub(b, a), sub(c, a), sub(q, a));
        let (g11, g12, g22) = (dot(e1, e1), dot(e1, e2), dot(e2, e2));
        let (r1, r2) = (dot(e1, r), dot(e2, r));
        let det = g11 * g22 - g12 * g12;
        let w1 = (g22 * r1 - g12 * r2) / det;
        let w2 = (g11 * r2 - g12 * r1) / det;
        let [_, s, t] = unwarp([1.0 - w1 - w2, w1, w2]);
        // Back to the diamond's frame: on `O B D`, `s = u - v` and `t = v`; on `O C D`,
        // `s = v - u` and `t = u`.
        let (u, v) = if face.upper { (t, s + t) } else { (s + t, t) };
        (face.d, u, v)
    }
}

/// The warp of a face's barycentric weights that evens out the tiles' areas: each weight bent,
/// then all renormalised (a direction takes the bent weights as they are: its length is
/// normalised anyway).
///
/// A central projection magnifies a face's middle more than its corners (by the cube of the
/// inradius, 0.50 on an icosahedron: corner tiles would be half the area of middle ones); the
/// warp moves the lattice toward the edges and corners: each weight `w` becomes
/// `w (1 + WARP (1 - w))` (its slope `1 + WARP` at 0, 1 at the face's corner), renormalised.
/// A weight of 0 stays 0, so a face's edges stay its edges, and an edge's points depend only on
/// the two weights along it: the faces on either side agree, and the seams hold.
fn bend(w: f64) -> f64 {
    w * (1.0 + WARP * (1.0 - w))
}

/// The inverse of `bend` on `[0, 1]` (a line below 0, for points just outside a face).
fn unbend(y: f64) -> f64 {
    if y <= 0.0 {
        y / (1.0 + WARP)
    } else {
        let b = 1.0 + WARP;
        2.0 * y / (b + (b * b - 4.0 * WARP * y.min(1.0)).max(0.0).sqrt())
    }
}

/// The inverse of the warp (see [`bend`]): the weights `w`, summing to 1, with `bend(w) = s p`
/// for the scale `s` Newton's method finds (the sum of the bent weights, between 1 and `1 + WARP`; five steps
/// reach the last bit).
fn unwarp(p: [f64; 3]) -> [f64; 3] {
    let mut s = 1.0 + WARP / 2.0;
    for _ in 0..6 {
        let w = p.map(|x| unbend(s * x));
        let slope: f64 = (0..3).map(|k| p[k] / (1.0 + WARP * (1.0 - 2.0 * w[k])).max(1e-9)).sum();
        s -= (w[0] + w[1] + w[2] - 1.0) / slope;
    }
    let w = p.map(|x| unbend(s * x));
    let sum = w[0] + w[1] + w[2];
    w.map(|x| x / sum)
}

/// How much the warp bends (0 is the plain central projection). At 0.3 the largest hexagon is
/// 1.035 times the smallest at frequency 8, 1.044 at 21, 1.054 at 64 (the plain projection:
/// 1.53, 1.81, 1.93); `tests/globe.rs` measures it.
const WARP: f64 = 0.3;

/// A spot's point in its diamond, in units of the diamond's side (the poles as the corner
/// `(1, 0)` of diamond 0 and `(0, 1)` of diamond 5).
pub(crate) fn spot_uv(f: u32, spot: Spot) -> (u8, f64, f64) {
    let n = f64::from(f);
    match spot {
        Spot::North => (0, 1.0, 0.0),
        Spot::South => (5, 0.0, 1.0),
        Spot::Diamond { d, i, j } => (d, f64::from(i) / n, f64::from(j) / n),
    }
}

/// Möller-Trumbore: the distance along unit `d` from `o` to triangle `a b c`, hit from either
/// side; `None` when the ray misses it or runs along its plane.
pub(crate) fn hit(o: Dir, d: Dir, a: Dir, b: Dir, c: Dir) -> Option<f64> {
    let (e1, e2) = (sub(b, a), sub(c, a));
    let p = cross(d, e2);
    let det = dot(e1, p);
    if det.abs() < 1e-18 {
        return None;
    }
    let inv = 1.0 / det;
    let s = sub(o, a);
    let u = dot(s, p) * inv;
    let q = cross(s, e1);
    let v = dot(d, q) * inv;
    let eps = 1e-12;
    ((-eps..=1.0 + eps).contains(&u) && v >= -eps && u + v <= 1.0 + eps).then(|| dot(e2, q) * inv)
}
