//! The layout of a map type ([`super::map_type`]): where its land (or an Inland Sea's sea)
//! lies before the noise shapes the coasts. Blobs drawn from the seed, summed cluster by
//! cluster on a grid of one node a tile (periodic east-west on a wrapping map, faded toward the
//! poles), read back bilinearly: the mask, 1 on the layout's land and 0 on its sea; for mountain
//! ranges, the plates' ridges raise it.

use std::f64::consts::PI;

use crate::config::MapType;
use crate::geometry::Geometry;
use crate::hash::{hash, unit};

use super::ShapeBounds;
use super::ranges::Plates;

/// Salt of the layouts' draws (so they are unlike the relief's or the props' from one seed).
const SALT: i64 = 0x4d41_5054;

/// Where a world position lies on the map, normalised: `u` from west to east (periodic on a
/// wrapping map), `v` from the first row to the last.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Frame {
    min_x: f64,
    min_z: f64,
    /// World x of the map's width (its period on a wrapping map).
    span_x: f64,
    span_z: f64,
    wraps: bool,
    /// The map's width over its height: distances in `v` units are `(du * aspect, dv)`.
    aspect: f64,
}

impl Frame {
    /// The frame of a bounded map whose tile centers span `bounds`.
    pub(crate) fn new(geometry: &Geometry, bounds: &ShapeBounds) -> Self {
        let span_x = geometry.wrap().map_or(bounds.max_x - bounds.min_x, |w| w.width).max(1e-9);
        let span_z = (bounds.max_z - bounds.min_z).max(1e-9);
        Self {
            min_x: bounds.min_x,
            min_z: bounds.min_z,
            span_x,
            span_z,
            wraps: geometry.wrap().is_some(),
            aspect: span_x / span_z,
        }
    }

    /// `(u, v)` of a world position (of a canonical point on a wrapping map).
    #[inline]
    pub(crate) fn uv(&self, x: f64, z: f64) -> (f64, f64) {
        let u = (x - self.min_x) / self.span_x;
        let u = if self.wraps { u.rem_euclid(1.0) } else { u.clamp(0.0, 1.0) };
        (u, ((z - self.min_z) / self.span_z).clamp(0.0, 1.0))
    }

    /// The east-west difference `a - b` in `u`, the short way round on a wrapping map.
    fn du(&self, a: f64, b: f64) -> f64 {
        let d = a - b;
        if self.wraps { d - d.round() } else { d }
    }
}

/// A bump of land (or sea): `(1 - d² / r²)²` within radius `r` of its center, `d` in `v` units;
/// the blobs of one cluster (a continent) add up, clusters meet at the higher of the two.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Blob {
    cluster: u32,
    u: f64,
    v: f64,
    radius: f64,
}

/// How far from the north and south edges (in `v`) the land of a layout fades out into sea,
/// so continents keep off the poles and the polar rows are sea (as Civilization V's map scripts
/// keep them).
const POLAR_FADE: f64 = 0.12;

/// How far from the north and south edges (in `v`) the sea of the poles deepens, from nothing
/// to the layout's polar depth at the edge.
const POLAR_SINK: f64 = 0.16;

/// The layout's blobs summed on a grid, read bilinearly.
#[derive(Debug, Clone)]
pub(crate) struct Mask {
    nu: usize,
    nv: usize,
    wraps: bool,
    values: Vec<f64>,
}

impl Mask {
    /// Sums each cluster's `blobs` on a grid of `nu` by `nv` nodes, clamped to 1, takes the
    /// highest cluster at each node, fades the land out toward the poles down to `-polar_sea`
    /// at the first and last rows (deep enough that no noise raises land there), and inverts it
    /// for a sea layout (whose land reaches the poles). `blobs` come cluster by cluster.
    pub(crate) fn new(blobs: &[Blob], invert: bool, polar_sea: f64, frame: &Frame, nu: usize, nv: usize) -> Self {
        let mut mask = Self { nu, nv, wraps: frame.wraps, values: vec![0.0; nu * nv] };
        // One cluster's sum at a time, on the nodes it touched, then into the mask where higher.
        let mut cluster = vec![0.0; nu * nv];
        let mut touched: Vec<usize> = Vec::new();
        for (b, blob) in blobs.iter().enumerate() {
            mask.add_blob(blob, frame, &mut cluster, &mut touched);
            if blobs.get(b + 1).is_none_or(|next| next.cluster != blob.cluster) {
                for &k in &touched {
                    mask.values[k] = f64::max(mask.values[k], cluster[k].min(1.0));
                    cluster[k] = 0.0;
                }
                touched.clear();
            }
        }
        for j in 0..nv {
            let (_, v) = mask.node(0, j);
            let t = (v.min(1.0 - v) / POLAR_FADE).min(1.0);
            let fade = t * t * (3.0 - 2.0 * t);
            let sink = (1.0 - v.min(1.0 - v) / POLAR_SINK).max(0.0);
            for value in &mut mask.values[j * nu..(j + 1) * nu] {
                *value = if invert { 1.0 - *value } else { *value * fade - polar_sea * sink };
            }
        }
        mask
    }

    /// Adds `blob` to `cluster` at the nodes within its radius, noting the nodes first touched.
    fn add_blob(&self, blob: &Blob, frame: &Frame, cluster: &mut [f64], touched: &mut Vec<usize>) {
        let (nu, nv) = (self.nu, self.nv);
        let rows = (nv - 1) as f64;
        let j0 = ((blob.v - blob.radius) * rows).floor().max(0.0) as usize;
        let j1 = (((blob.v + blob.radius) * rows).ceil().max(0.0) as usize).min(nv - 1);
        let span = (blob.radius / frame.aspect * self.columns()).ceil() as i64 + 1;
        let center = (blob.u * self.columns()).round() as i64;
        // Columns once each: wrapped on a wrapping map (at most one period), clipped otherwise.
        let columns: Vec<usize> = if self.wraps {
            (center - span..=center + span).take(nu).map(|k| k.rem_euclid(nu as i64) as usize).collect()
        } else {
            (center - span..=center + span).filter_map(|k| usize::try_from(k).ok()).filter(|&i| i < nu).collect()
        };
        for j in j0..=j1 {
            for &i in &columns {
                let (u, v) = self.node(i, j);
                let (du, dv) = (frame.du(u, blob.u) * frame.aspect, v - blob.v);
                let t = 1.0 - (du * du + dv * dv) / (blob.radius * blob.radius);
                if t > 0.0 {
                    if cluster[j * nu + i] == 0.0 {
                        touched.push(j * nu + i);
                    }
                    cluster[j * nu + i] += t * t;
                }
            }
        }
    }

    /// Node intervals across the map: one a column, and one more on a wrapping map (its last
    /// node's neighbor is the first).
    fn columns(&self) -> f64 {
        if self.wraps { self.nu as f64 } else { (self.nu - 1) as f64 }
    }

    /// Where node `(i, j)` lies.
    fn node(&self, i: usize, j: usize) -> (f64, f64) {
        (i as f64 / self.columns(), j as f64 / (self.nv - 1) as f64)
    }

    /// Raises the land along the plates' ridges, by `height` at most; `on_land`: in proportion
    /// to the layout's land (a ridge under its sea stays there).
    pub(crate) fn add_ridges(&mut self, plates: &Plates, height: f64, on_land: bool) {
        let us: Vec<f64> = (0..self.nu).map(|i| self.node(i, 0).0).collect();
        let vs: Vec<f64> = (0..self.nv).map(|j| self.node(0, j).1).collect();
        let waves = plates.wave_grid(&us, &vs);
        for (j, (row, &v)) in self.values.chunks_mut(self.nu).zip(&vs).enumerate() {
            for (i, (value, &u)) in row.iter_mut().zip(&us).enumerate() {
                let land = if on_land { value.clamp(0.0, 1.0) } else { 1.0 };
                // Under the layout's sea a ridge adds nothing: no need to find its plates.
                if land > 0.0 {
                    *value += height * land * plates.ridge_on(&waves, (i, j), (u, v));
                }
            }
        }
    }

    /// Lowers the mask by `by` at the four nodes around `(u, v)`, so its value there falls by
    /// `by` (the bilinear weights sum to 1).
    pub(crate) fn lower_at(&mut self, u: f64, v: f64, by: f64) {
        let ((i0, i1, j0, j1), _) = self.cell(u, v);
        for (i, j) in [(i0, j0), (i1, j0), (i0, j1), (i1, j1)] {
            self.values[j * self.nu + i] -= by;
        }
    }

    /// The grid cell holding `(u, v)`: its columns `i0, i1` and rows `j0, j1`, and where in it
    /// `(u, v)` lies (0 at `i0` or `j0`, 1 at `i1` or `j1`).
    #[inline]
    fn cell(&self, u: f64, v: f64) -> ((usize, usize, usize, usize), (f64, f64)) {
        let gu = u * self.columns();
        let gv = v * (self.nv - 1) as f64;
        let (fu, fv) = (gu.floor(), gv.floor());
        let j0 = (fv as usize).min(self.nv - 1);
        let j1 = (j0 + 1).min(self.nv - 1);
        let (i0, i1) = if self.wraps {
            let i0 = (fu as usize) % self.nu;
            (i0, (i0 + 1) % self.nu)
        } else {
            let i0 = (fu as usize).min(self.nu - 1);
            (i0, (i0 + 1).min(self.nu - 1))
        };
        ((i0, i1, j0, j1), (gu - fu, gv - fv))
    }

    /// The mask at `(u, v)`, bilinear between the grid's nodes.
    #[inline]
    pub(crate) fn at(&self, u: f64, v: f64) -> f64 {
        let ((i0, i1, j0, j1), (tu, tv)) = self.cell(u, v);
        let row = |j: usize| self.values[j * self.nu + i0] * (1.0 - tu) + self.values[j * self.nu + i1] * tu;
        row(j0) * (1.0 - tv) + row(j1) * tv
    }
}

/// The draws of one layout: numbers in `[0, 1)` from the seed, a salt, the layout and a
/// counter (a flat map's layouts and a globe's use salts of their own).
pub(crate) struct Draw {
    seed: u32,
    salt: i64,
    layout: u32,
    count: i64,
}

impl Draw {
    /// The draws of layout `layout` of `seed` under `salt`, from the counter `count`.
    pub(crate) fn new(seed: u32, salt: i64, layout: u32, count: i64) -> Self {
        Self { seed, salt, layout, count }
    }

    /// The next number in `[0, 1)`.
    pub(crate) fn next(&mut self) -> f64 {
        self.count += 1;
        f64::from(unit(hash(self.seed, &[self.salt, i64::from(self.layout), self.count])))
    }

    /// The next number in `[lo, hi)`.
    pub(crate) fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// How far a continent's core blob reaches beyond the radius of a disc of its land's area:
/// the coast runs where the summed blobs are about half, inside their radius.
const CLUSTER_REACH: f64 = 1.3;

/// A continent (or island, or sea): a core blob at `(u, v)` holding about `area` (in `v` units
/// squared) and `satellites` smaller blobs around it, spread `stretch` times as far north-south
/// as east-west.
fn cluster(
    draw: &mut Draw,
    frame: &Frame,
    blobs: &mut Vec<Blob>,
    (u, v): (f64, f64),
    area: f64,
    satellites: u32,
    stretch: f64,
) {
    let id = blobs.last().map_or(0, |b| b.cluster + 1);
    cores(draw, frame, blobs, id, (u, v), area, satellites, stretch);
}

/// A core blob of cluster `id` and its satellites, as [`cluster`] draws them: a continent of
/// several cores calls it once a core.
#[allow(clippy::too_many_arguments)]
fn cores(
    draw: &mut Draw,
    frame: &Frame,
    blobs: &mut Vec<Blob>,
    id: u32,
    (u, v): (f64, f64),
    area: f64,
    satellites: u32,
    stretch: f64,
) {
    let core = (area / PI).sqrt() * CLUSTER_REACH;
    blobs.push(Blob { cluster: id, u, v, radius: core });
    for _ in 0..satellites {
        let angle = draw.range(0.0, 2.0 * PI);
        let reach = core * draw.range(0.3, 0.7);
        let radius = core * draw.range(0.4, 0.65);
        let du = reach * libm::cos(angle) / frame.aspect / stretch.sqrt();
        let dv = reach * libm::sin(angle) * stretch.sqrt();
        let u = if frame.wraps { (u + du).rem_euclid(1.0) } else { (u + du).clamp(0.0, 1.0) };
        blobs.push(Blob { cluster: id, u, v: (v + dv).clamp(0.0, 1.0), radius });
    }
}

/// How far north or south of the Pangaea chain's line each core lies, in turn (a share of the
/// map's height): the supercontinent reaches the cold rows at its ends, as Civilization's does.
const PANGAEA_ZIGZAG: (f64, f64) = (0.08, 0.16);

/// The share of Continents layouts with three continents rather than two.
const THREE_CONTINENTS: f64 = 0.3;

/// The largest islands of an Archipelago, spread over the map before the others gather beside
/// them.
const ARCHIPELAGO_SPREAD: usize = 10;

/// Draws of a place beside an island for each smaller island of an Archipelago.
const ARCHIPELAGO_DRAWS: usize = 8;

/// The blobs of layout `layout` of a type (land, or the sea of an Inland Sea).
pub(crate) fn draw(kind: MapType, seed: u32, layout: u32, frame: &Frame, land_share: f64, tiles: usize) -> Vec<Blob> {
    let mut draw = Draw::new(seed, SALT, layout, 0);
    let area = frame.aspect; // the map's area in v units squared
    let land = land_share * area;
    // East-west: around the map's middle (a wrapping map's too, so the picture a player first
    // sees is not cut by the seam), inside the margins of a bounded one.
    let across = |draw: &mut Draw, at: f64, jitter: f64| {
        if frame.wraps {
            (at + draw.range(-jitter, jitter)).rem_euclid(1.0)
        } else {
            (at + draw.range(-jitter, jitter)).clamp(0.05, 0.95)
        }
    };
    let mut blobs = Vec::new();
    match kind {
        MapType::Fractal => {}
        MapType::Pangaea => {
            // A chain of cores east to west, each in turn north and south of the chain's line,
            // so the supercontinent spans most of the map's width and bends toward the poles
            // (its coast is still one).
            let count = 4;
            let (west, east) = (across(&mut draw, 0.17, 0.03), across(&mut draw, 0.83, 0.03));
            let (mid, tilt) = (draw.range(0.45, 0.55), draw.range(-0.08, 0.08));
            let north = draw.next() < 0.5;
            for k in 0..count {
                let t = (f64::from(k) + 0.5) / f64::from(count);
                let side = if (k % 2 == 0) == north { -1.0 } else { 1.0 };
                let v = mid + tilt * (t - 0.5) * 2.0 + side * draw.range(PANGAEA_ZIGZAG.0, PANGAEA_ZIGZAG.1);
                let u = west + (east - west) * t;
                // One continent: the cores are one cluster, summed.
                cores(&mut draw, frame, &mut blobs, 0, (u, v), land / f64::from(count) * 1.15, 3, 0.8);
            }
        }
        MapType::Continents => {
            // Two continents, or three on some seeds, as far from each other as from the map's
            // edge (or the seam), of sizes that differ a little; each a chain of cores north to
            // south, so it spans most of the map's height.
            let count = if draw.next() < THREE_CONTINENTS { 3 } else { 2 };
            let shares: Vec<f64> = (0..count).map(|_| draw.range(0.85, 1.15)).collect();
            let total: f64 = shares.iter().sum();
            for (k, share) in shares.into_iter().enumerate() {
                let at = (k as f64 + 0.5) / f64::from(count);
                let at = if frame.wraps { at } else { 0.04 + 0.92 * at };
                let at = across(&mut draw, at, 0.04);
                let slant = draw.range(-0.05, 0.05);
                let id = blobs.last().map_or(0, |b: &Blob| b.cluster + 1);
                let area = land * share / total;
                for (j, v) in [0.3, 0.5, 0.7].into_iter().enumerate() {
                    let v = v + draw.range(-0.05, 0.05);
                    let u = at + slant * (j as f64 - 1.0) + draw.range(-0.02, 0.02);
                    let u = if frame.wraps { u.rem_euclid(1.0) } else { u.clamp(0.05, 0.95) };
                    cores(&mut draw, frame, &mut blobs, id, (u, v), area / 3.0 * 1.15, 2, 1.4);
                }
            }
        }
        MapType::SmallContinents => {
            // Spread by best candidate (of a few draws, the one farthest from those placed), of
            // sizes that differ, so they lie on no grid.
            let count = if draw.next() < 0.5 { 5 } else { 6 };
            let mut centers: Vec<(f64, f64)> = Vec::new();
            let sizes: Vec<f64> = (0..count).map(|_| draw.range(0.75, 1.25)).collect();
            let total: f64 = sizes.iter().sum();
            for size in sizes {
                let at = best_candidate(&mut draw, frame, &centers, (0.1, 0.9), (0.22, 0.78));
                centers.push(at);
                let stretch = draw.range(0.7, 1.5);
                cluster(&mut draw, frame, &mut blobs, at, land * size / total, 4, stretch);
            }
        }
        MapType::Archipelago => {
            // Islands of many sizes, a few large and many small (the k-th about (k + 3)^-0.6
            // of the land), the large ones spread first.
            let count = (tiles / 180).clamp(14, 40);
            let weights: Vec<f64> = (0..count).map(|k| (k as f64 + 3.0).powf(-0.6)).collect();
            let total: f64 = weights.iter().sum();
            // The large ones spread; each smaller one beside an island placed, so they form
            // chains and groups rather than dots evenly strewn.
            let mut placed: Vec<((f64, f64), f64)> = Vec::new();
            for (k, weight) in weights.into_iter().enumerate() {
                let area = land * weight / total;
                let radius = (area / PI).sqrt() * CLUSTER_REACH;
                let at = if k < ARCHIPELAGO_SPREAD {
                    let centers: Vec<(f64, f64)> = placed.iter().map(|p| p.0).collect();
                    best_candidate(&mut draw, frame, &centers, (0.05, 0.95), (0.2, 0.8))
                } else {
                    // Beside an island placed, clear of every other: of a few draws, the one
                    // with the most room.
                    let mut best = ((0.5, 0.5), f64::NEG_INFINITY);
                    for _ in 0..ARCHIPELAGO_DRAWS {
                        let (near, r) = placed[(draw.next() * placed.len() as f64) as usize];
                        let angle = draw.range(0.0, 2.0 * PI);
                        let reach = (r + radius) * draw.range(1.5, 2.2);
                        let u = near.0 + reach * libm::cos(angle) / frame.aspect;
                        let u = if frame.wraps { u.rem_euclid(1.0) } else { u.clamp(0.05, 0.95) };
                        let at = (u, (near.1 + reach * libm::sin(angle)).clamp(0.18, 0.82));
                        let room = placed
                            .iter()
                            .map(|&((pu, pv), pr)| {
                                let (du, dv) = (frame.du(at.0, pu) * frame.aspect, at.1 - pv);
                                (du * du + dv * dv).sqrt() - (pr + radius) * 1.4
                            })
                            .fold(f64::INFINITY, f64::min);
                        if room > best.1 {
                            best = (at, room);
                        }
                        if room >= 0.0 {
                            break;
                        }
                    }
                    best.0
                };
                placed.push((at, radius));
                cluster(&mut draw, frame, &mut blobs, at, area, 2, 1.0);
            }
        }
        MapType::InlandSea => {
            let center = (across(&mut draw, 0.5, 0.03), draw.range(0.47, 0.53));
            cluster(&mut draw, frame, &mut blobs, center, (1.0 - land_share) * area, 4, 0.9);
        }
    }
    blobs
}

/// Mitchell's best candidate: of a few draws (`u` within `us` on a map that does not wrap,
/// `v` within `vs`), the one farthest from every center placed, so places spread without a
/// grid.
fn best_candidate(
    draw: &mut Draw,
    frame: &Frame,
    centers: &[(f64, f64)],
    us: (f64, f64),
    vs: (f64, f64),
) -> (f64, f64) {
    let mut at = (0.5, 0.5);
    let mut farthest = -1.0;
    for _ in 0..16 {
        let candidate = (if frame.wraps { draw.next() } else { draw.range(us.0, us.1) }, draw.range(vs.0, vs.1));
        let nearest = centers
            .iter()
            .map(|&(u, v)| {
                let du = frame.du(candidate.0, u) * frame.aspect;
                du * du + (candidate.1 - v) * (candidate.1 - v)
            })
            .fold(f64::INFINITY, f64::min);
        if nearest > farthest {
            (at, farthest) = (candidate, nearest);
        }
    }
    at
}

/// The tectonic plates of layout `layout` (for mountain ranges), drawn apart from its blobs so
/// a layout's land is the same with ranges or without.
pub(crate) fn plates(seed: u32, layout: u32, frame: &Frame, tiles: usize, rows: usize) -> Plates {
    let mut draw = Draw::new(seed, SALT, layout, 1 << 40);
    Plates::draw(Plates::count(tiles), frame.wraps, frame.aspect, rows, || draw.next())
}
