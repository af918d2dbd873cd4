//! Map types ([`MapType`]): the thesis' fBm shaped into an arrangement of land and sea that
//! meets measured targets. A filter of the height stage, in place of the section 7.1 shapes,
//! for bounded maps (wrapping or not).
//!
//! A type draws a **layout** from the seed: blobs of land (a continent is a core blob and a few
//! smaller ones around it, so its outline is not round), or of sea for the Inland Sea. The
//! blobs are summed on a grid of one node a tile, periodic east-west on a wrapping map, and read
//! back bilinearly: the **mask**, 1 on the layout's land and 0 on its sea. A point's value is
//!
//! ```text
//! value = mask(x, z) + roughness * (fbm(x, z) - mean) / deviation
//! ```
//!
//! with the fBm's mean and standard deviation over the map's tile centers, so the noise gives
//! every coast and island its shape whatever the noise config's amplitude. The value is then
//! remapped to a height by a monotone piecewise-linear curve whose knots are chosen from the
//! sorted values of the tile centers: the knot between sea and land leaves exactly the type's
//! share of the tiles below the sea threshold, the knot between land and mountains exactly the
//! config's share of the land above the mountain threshold. Tiles are classified by their
//! center as on any map, so hex unity keeps every tile easily recognisable.
//!
//! Everything is computed once, when the map is compiled, from the config alone: the height of
//! a point is then a pure function of the point (the grid, the noise's mean and deviation and
//! the knots are fixed numbers), so chunks are bit-identical at seams and chunked equals whole
//! on any thread. The tries (layouts, then sea shares either side of the level's) are
//! deterministic and bounded by [`MAX_TRIES`].

use std::f64::consts::PI;

use crate::config::{MapType, MapTypeConfig, SEA_SHARE_TOLERANCE};
use crate::geometry::Geometry;
use crate::hash::{hash, unit};

use super::ranges::Plates;
use super::targets::{self, MapTypeReport, TargetCheck, TileGraph};
use super::{HeightField, ShapeBounds};

/// Layouts a map type draws before it keeps its best try.
pub const MAX_LAYOUTS: u32 = 12;
/// Most tries a map type makes: every layout at the level's sea share and at shares
/// either side of it within [`SEA_SHARE_TOLERANCE`] ([`SEA_STEPS`]).
pub const MAX_TRIES: u32 = MAX_LAYOUTS * SEA_STEPS.len() as u32;

/// The sea shares a layout is tried at, as fractions of [`SEA_SHARE_TOLERANCE`] from the
/// level's: the level's first, then more and less sea (more sea parts continents that touch,
/// less joins an island to its continent).
pub const SEA_STEPS: [f64; 5] = [0.0, 0.45, -0.45, 0.9, -0.9];

/// Salt of the layouts' draws (so they are unlike the relief's or the props' from one seed).
const SALT: i64 = 0x4d41_5054;

/// A map type compiled for one map: the mask, the noise's normalisation and the remap.
#[derive(Debug, Clone)]
pub struct MapTypeField {
    frame: Frame,
    mask: Mask,
    /// The fBm's mean over the tile centers.
    mean: f64,
    /// The roughness over the fBm's standard deviation.
    noise_weight: f64,
    remap: Remap,
    report: MapTypeReport,
}

impl MapTypeField {
    /// Builds the map type of `config` for a bounded map: draws layouts and sea shares until one
    /// meets every target (or keeps the best of [`MAX_TRIES`]). `heights` is the map's height
    /// field without a map type (its fBm is sampled at the tile centers).
    pub(crate) fn build(
        config: &MapTypeConfig,
        seed: u32,
        geometry: &Geometry,
        heights: &HeightField,
        bounds: &ShapeBounds,
        thresholds: (f32, f32),
    ) -> Self {
        let frame = Frame::new(geometry, bounds);
        let tiles: Vec<_> = geometry.tiles().collect();
        let n = tiles.len();
        let centers: Vec<_> = tiles.iter().map(|&t| geometry.lattice().tile_center(t)).collect();
        let mut source = vec![0.0; n];
        heights.source_heights(geometry, &centers, &mut source);
        let uv: Vec<(f64, f64)> = centers
            .iter()
            .map(|&c| {
                let [x, z] = geometry.lattice().world(geometry.wrap_point(c));
                frame.uv(x, z)
            })
            .collect();
        let mean = source.iter().sum::<f64>() / n.max(1) as f64;
        let variance = source.iter().map(|s| (s - mean) * (s - mean)).sum::<f64>() / n.max(1) as f64;
        let noise_weight = roughness(config.kind) / variance.sqrt().max(1e-9);
        let noise: Vec<f64> = source.iter().map(|s| (s - mean) * noise_weight).collect();
        let graph = tile_graph(geometry);
        let land_share = 1.0 - config.sea_share();
        let (nu, nv) = geometry
            .bounds()
            .map_or((2, 2), |b| ((b.max[0] - b.min[0]).max(2) as usize, (b.max[1] - b.min[1]).max(2) as usize));

        let mut best: Option<(Candidate, (usize, f64))> = None;
        let mut tries = 0;
        'layouts: for layout in 0..MAX_LAYOUTS {
            let blobs = draw_layout(config.kind, seed, layout, &frame, land_share, n);
            let mut mask = Mask::new(&blobs, config.kind == MapType::InlandSea, &frame, nu, nv);
            if config.ranges {
                // Drawn apart from the blobs, so a layout's land is the same with ranges or not.
                let mut draw = Draw { seed, layout, count: 1 << 40 };
                let plates = Plates::draw(Plates::count(n), frame.wraps, frame.aspect, nv, || draw.next());
                // Fractal has no layout: its ridges rise wherever they run (island arcs at sea).
                mask.add_ridges(&plates, RIDGE_HEIGHT, config.kind != MapType::Fractal);
            }
            let values: Vec<f64> = uv.iter().zip(&noise).map(|(&(u, v), z)| mask.at(u, v) + z).collect();
            let mut sorted = values.clone();
            sorted.sort_unstable_by(f64::total_cmp);
            let level = config.sea_share();
            for sea_share in SEA_STEPS.map(|step| level + step * SEA_SHARE_TOLERANCE) {
                tries += 1;
                let remap = Remap::new(&sorted, sea_share, f64::from(config.mountains), thresholds);
                let heights: Vec<f32> = values.iter().map(|&v| remap.height(v) as f32).collect();
                let sea: Vec<bool> = heights.iter().map(|&h| h < thresholds.0).collect();
                let mountain: Vec<bool> = heights.iter().map(|&h| h >= thresholds.1).collect();
                let checks = targets::measure(config, &graph, &sea, &mountain);
                let score = score(&checks);
                let candidate = Candidate { layout, sea_share, mask: mask.clone(), remap, checks };
                if best.as_ref().is_none_or(|(_, s)| score.0 < s.0 || (score.0 == s.0 && score.1 < s.1)) {
                    best = Some((candidate, score));
                }
                if score.0 == 0 {
                    break 'layouts;
                }
            }
        }
        let (kept, _) = best.expect("at least one try");
        let report = MapTypeReport {
            kind: config.kind,
            tries,
            layout: kept.layout,
            sea_share: kept.sea_share,
            checks: kept.checks,
        };
        Self { frame, mask: kept.mask, mean, noise_weight, remap: kept.remap, report }
    }

    /// The normalised height of a point whose fBm is `source`, at world `(x, z)` (of its
    /// canonical point on a wrapping map), in `[0, 1]`.
    #[must_use]
    #[inline]
    pub fn apply(&self, source: f64, x: f64, z: f64) -> f64 {
        let (u, v) = self.frame.uv(x, z);
        let value = self.mask.at(u, v) + (source - self.mean) * self.noise_weight;
        self.remap.height(value).clamp(0.0, 1.0)
    }

    /// What came of the type: its targets measured, and the tries it took.
    #[must_use]
    pub fn report(&self) -> &MapTypeReport {
        &self.report
    }
}

/// One try, kept while it is the best.
struct Candidate {
    layout: u32,
    sea_share: f64,
    mask: Mask,
    remap: Remap,
    checks: Vec<TargetCheck>,
}

/// Targets missed, then how far (shares and counts alike: the tie-break only).
fn score(checks: &[TargetCheck]) -> (usize, f64) {
    let missed = checks.iter().filter(|c| !c.met()).count();
    let by = checks.iter().map(TargetCheck::miss).filter(|m| m.is_finite()).sum();
    (missed, by)
}

/// How much the fBm shapes a type's coasts, in units of the mask's step from sea to land per
/// standard deviation of the noise. Fractal is the noise alone (its mask is empty).
fn roughness(kind: MapType) -> f64 {
    match kind {
        MapType::Pangaea | MapType::InlandSea => 0.25,
        MapType::Continents | MapType::SmallContinents => 0.2,
        MapType::Archipelago => 0.18,
        MapType::Fractal => 1.0,
    }
}

/// Tiles of the map by row, with their wrapped neighbors and whether they lie on its edge.
fn tile_graph(geometry: &Geometry) -> TileGraph {
    let Some(rect) = geometry.bounds() else { return TileGraph { neighbors: Vec::new(), edge: Vec::new() } };
    let width = rect.max[0] - rect.min[0];
    let index = |[col, row]: [i32; 2]| ((row - rect.min[1]) * width + (col - rect.min[0])) as u32;
    let wraps = geometry.wrap().is_some();
    let mut neighbors = Vec::with_capacity(rect.len());
    let mut edge = Vec::with_capacity(rect.len());
    for tile in geometry.tiles() {
        let [col, row] = geometry.offset_of(tile);
        let around = geometry.wrapped_neighbors(tile);
        neighbors.push(around.map(|nb| geometry.contains(nb).then(|| index(geometry.offset_of(nb)))));
        edge.push(
            row == rect.min[1] || row == rect.max[1] - 1 || (!wraps && (col == rect.min[0] || col == rect.max[0] - 1)),
        );
    }
    TileGraph { neighbors, edge }
}

/// Where a world position lies on the map, normalised: `u` from west to east (periodic on a
/// wrapping map), `v` from the first row to the last.
#[derive(Debug, Clone, Copy)]
struct Frame {
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
    fn new(geometry: &Geometry, bounds: &ShapeBounds) -> Self {
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

    #[inline]
    fn uv(&self, x: f64, z: f64) -> (f64, f64) {
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
struct Blob {
    cluster: u32,
    u: f64,
    v: f64,
    radius: f64,
}

/// How much a ridge of [`Plates`] raises the land (in units of the mask's step from sea to
/// land), so the highest land, the mountains, lies along the ridges.
const RIDGE_HEIGHT: f64 = 2.0;

/// How far from the north and south edges (in `v`) the land of a layout fades out, so
/// continents keep off the poles.
const POLAR_FADE: f64 = 0.1;

/// The layout's blobs summed on a grid, read bilinearly.
#[derive(Debug, Clone)]
struct Mask {
    nu: usize,
    nv: usize,
    wraps: bool,
    values: Vec<f64>,
}

impl Mask {
    /// Sums each cluster's `blobs` on a grid of `nu` by `nv` nodes, clamped to 1, takes the
    /// highest cluster at each node, fades the land out toward the poles, and inverts it for a
    /// sea layout. `blobs` come cluster by cluster.
    fn new(blobs: &[Blob], invert: bool, frame: &Frame, nu: usize, nv: usize) -> Self {
        let wraps = frame.wraps;
        let node_u = |i: usize| if wraps { i as f64 / nu as f64 } else { i as f64 / (nu - 1) as f64 };
        let node_v = |j: usize| j as f64 / (nv - 1) as f64;
        let mut values = vec![0.0; nu * nv];
        let mut cluster = vec![0.0; nu * nv];
        let mut touched: Vec<usize> = Vec::new();
        // A cluster's sum, clamped, into the mask where it is higher.
        fn flush(cluster: &mut [f64], touched: &mut Vec<usize>, values: &mut [f64]) {
            for &k in touched.iter() {
                values[k] = f64::max(values[k], cluster[k].min(1.0));
                cluster[k] = 0.0;
            }
            touched.clear();
        }
        for (b, blob) in blobs.iter().enumerate() {
            if b > 0 && blobs[b - 1].cluster != blob.cluster {
                flush(&mut cluster, &mut touched, &mut values);
            }
            // Only the nodes within the blob's radius.
            let (rv, ru) = (blob.radius, blob.radius / frame.aspect);
            let j0 = ((blob.v - rv) * (nv - 1) as f64).floor().max(0.0) as usize;
            let j1 = (((blob.v + rv) * (nv - 1) as f64).ceil().max(0.0) as usize).min(nv - 1);
            let scale = if wraps { nu as f64 } else { (nu - 1) as f64 };
            let span = (ru * scale).ceil() as i64 + 1;
            let center = (blob.u * scale).round() as i64;
            for j in j0..=j1 {
                let dv = node_v(j) - blob.v;
                for k in center - span..=center + span {
                    let i = if wraps {
                        k.rem_euclid(nu as i64) as usize
                    } else if (0..nu as i64).contains(&k) {
                        k as usize
                    } else {
                        continue;
                    };
                    if wraps && k - (center - span) >= nu as i64 {
                        // The blob spans the whole period: each node once.
                        continue;
                    }
                    let du = frame.du(node_u(i), blob.u) * frame.aspect;
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
        flush(&mut cluster, &mut touched, &mut values);
        for j in 0..nv {
            let pole = node_v(j).min(1.0 - node_v(j));
            let t = (pole / POLAR_FADE).min(1.0);
            let fade = t * t * (3.0 - 2.0 * t);
            for value in &mut values[j * nu..(j + 1) * nu] {
                *value = if invert { 1.0 - *value } else { *value * fade };
            }
        }
        Self { nu, nv, wraps, values }
    }

    /// Where node `(i, j)` lies.
    fn node(&self, i: usize, j: usize) -> (f64, f64) {
        let u = if self.wraps { i as f64 / self.nu as f64 } else { i as f64 / (self.nu - 1) as f64 };
        (u, j as f64 / (self.nv - 1) as f64)
    }

    /// Raises the land along the plates' ridges, by `height` at most; `on_land`: in proportion
    /// to the layout's land (a ridge under its sea stays there).
    fn add_ridges(&mut self, plates: &Plates, height: f64, on_land: bool) {
        for j in 0..self.nv {
            for i in 0..self.nu {
                let (u, v) = self.node(i, j);
                let value = &mut self.values[j * self.nu + i];
                let land = if on_land { value.clamp(0.0, 1.0) } else { 1.0 };
                *value += height * land * plates.ridge(u, v);
            }
        }
    }

    #[inline]
    fn at(&self, u: f64, v: f64) -> f64 {
        let gu = if self.wraps { u * self.nu as f64 } else { u * (self.nu - 1) as f64 };
        let gv = v * (self.nv - 1) as f64;
        let (fu, fv) = (gu.floor(), gv.floor());
        let (tu, tv) = (gu - fu, gv - fv);
        let j0 = (fv as usize).min(self.nv - 1);
        let j1 = (j0 + 1).min(self.nv - 1);
        let (i0, i1) = if self.wraps {
            let i0 = (fu as usize) % self.nu;
            (i0, (i0 + 1) % self.nu)
        } else {
            let i0 = (fu as usize).min(self.nu - 1);
            (i0, (i0 + 1).min(self.nu - 1))
        };
        let row = |j: usize| self.values[j * self.nu + i0] * (1.0 - tu) + self.values[j * self.nu + i1] * tu;
        row(j0) * (1.0 - tv) + row(j1) * tv
    }
}

/// The monotone piecewise-linear curve from a value to a height: the lowest tile's value to 0,
/// the sea knot to the sea threshold, the mountain knot to the mountain threshold, the highest
/// tile's value to 1.
#[derive(Debug, Clone, Copy)]
struct Remap {
    lo: f64,
    sea: f64,
    mountain: f64,
    hi: f64,
    sea_height: f64,
    mountain_height: f64,
}

impl Remap {
    /// The knots that leave `sea_share` of the tiles (values `sorted`) below the sea threshold
    /// and `mountains` of the rest above the mountain threshold.
    fn new(sorted: &[f64], sea_share: f64, mountains: f64, (sea, mountain): (f32, f32)) -> Self {
        let n = sorted.len();
        let between = |k: usize| (sorted[k - 1] + sorted[k]) / 2.0;
        let (lo, hi) = (sorted[0], sorted[n - 1]);
        let sea_count = ((sea_share * n as f64).round() as usize).clamp(1, n.saturating_sub(1).max(1));
        let sea_knot = if n > 1 { between(sea_count) } else { lo };
        let land = n - sea_count;
        let mountain_count = ((mountains * land as f64).round() as usize).min(land);
        let spread = (hi - lo).max(1e-9);
        let mountain_knot = if mountain_count == 0 { hi + spread } else { between(n - mountain_count) };
        Self {
            lo: lo - spread * 1e-6,
            sea: sea_knot,
            mountain: mountain_knot,
            hi: hi.max(mountain_knot) + spread * 1e-6,
            sea_height: f64::from(sea),
            mountain_height: f64::from(mountain),
        }
    }

    #[inline]
    fn height(&self, value: f64) -> f64 {
        let slope = |dh: f64, dv: f64| dh / dv.max(1e-12);
        if value < self.sea {
            self.sea_height + (value - self.sea) * slope(self.sea_height, self.sea - self.lo)
        } else if value < self.mountain {
            self.sea_height
                + (value - self.sea) * slope(self.mountain_height - self.sea_height, self.mountain - self.sea)
        } else {
            self.mountain_height + (value - self.mountain) * slope(1.0 - self.mountain_height, self.hi - self.mountain)
        }
    }
}

/// The draws of one layout: numbers in `[0, 1)` from the seed, the layout and a counter.
struct Draw {
    seed: u32,
    layout: u32,
    count: i64,
}

impl Draw {
    fn next(&mut self) -> f64 {
        self.count += 1;
        f64::from(unit(hash(self.seed, &[SALT, i64::from(self.layout), self.count])))
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
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

/// The blobs of layout `layout` of a type (land, or the sea of an Inland Sea).
fn draw_layout(kind: MapType, seed: u32, layout: u32, frame: &Frame, land_share: f64, tiles: usize) -> Vec<Blob> {
    let mut draw = Draw { seed, layout, count: 0 };
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
            let center = (across(&mut draw, 0.5, 0.05), draw.range(0.45, 0.55));
            cluster(&mut draw, frame, &mut blobs, center, land, 7, 0.8);
        }
        MapType::Continents => {
            // As far from each other as from the map's edge (or the seam).
            for u in if frame.wraps { [0.25, 0.75] } else { [0.26, 0.74] } {
                let center = (across(&mut draw, u, 0.03), draw.range(0.44, 0.56));
                cluster(&mut draw, frame, &mut blobs, center, land / 2.0, 5, 1.4);
            }
        }
        MapType::SmallContinents => {
            let count = if draw.next() < 0.5 { 5 } else { 6 };
            let skip = if count == 5 { (draw.next() * 6.0) as usize } else { 6 };
            for cell in (0..6).filter(|&c| c != skip) {
                let (col, row) = ((cell % 3) as f64, (cell / 3) as f64);
                let at = if frame.wraps { (col + 0.5) / 3.0 } else { 0.1 + 0.8 * (col + 0.5) / 3.0 };
                let center = (across(&mut draw, at, 0.04), 0.3 + 0.4 * row + draw.range(-0.04, 0.04));
                cluster(&mut draw, frame, &mut blobs, center, land / f64::from(count), 4, 1.0);
            }
        }
        MapType::Archipelago => {
            let count = (tiles / 60).clamp(20, 64);
            let island = land / count as f64;
            let mut centers: Vec<(f64, f64)> = Vec::new();
            for _ in 0..count {
                // Mitchell's best candidate: of a few draws, the one farthest from every island
                // placed, so the islands spread evenly without a grid.
                let mut at = (0.5, 0.5);
                let mut farthest = -1.0;
                for _ in 0..16 {
                    let candidate =
                        (if frame.wraps { draw.next() } else { draw.range(0.05, 0.95) }, draw.range(0.12, 0.88));
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
                centers.push(at);
                cluster(&mut draw, frame, &mut blobs, at, island, 2, 1.0);
            }
        }
        MapType::InlandSea => {
            let center = (across(&mut draw, 0.5, 0.03), draw.range(0.47, 0.53));
            cluster(&mut draw, frame, &mut blobs, center, (1.0 - land_share) * area, 4, 0.9);
        }
    }
    blobs
}
