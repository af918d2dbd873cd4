//! Map types ([`MapType`]): the thesis' fBm shaped into an arrangement of land and sea that
//! meets measured targets. A filter of the height stage, in place of the section 7.1 shapes,
//! for bounded maps (wrapping or not).
//!
//! A type draws a **layout** from the seed: blobs of land (a continent is a core blob and a few
//! smaller ones around it, or a chain of such cores, so its outline is not round), or of sea for
//! the Inland Sea. The blobs are summed on a grid of one node a tile (two with ranges), periodic
//! east-west on a wrapping map, and read back bilinearly: the **mask**, 1 on the layout's land
//! and 0 on its sea, sinking below the sea toward the first and last rows. With ranges, the
//! plates' ridges raise it, and the ranges' knots are sunk to hills ([`untangle`]). A point's
//! value is
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

use crate::config::{MapType, MapTypeConfig, SEA_SHARE_TOLERANCE};
use crate::geometry::Geometry;

use super::knots;
use super::layout::{self, Frame, Mask};
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
        let graph = TileGraph::of(geometry);
        let land_share = 1.0 - config.sea_share();
        let level = config.sea_share();
        let (columns, rows) = geometry
            .bounds()
            .map_or((2, 2), |b| ((b.max[0] - b.min[0]).max(2) as usize, (b.max[1] - b.min[1]).max(2) as usize));
        // Ranges are narrow: their mask has RANGE_NODES nodes a tile each way, so its bilinear
        // reading keeps a ridge about a tile wide.
        let fine = if config.ranges { RANGE_NODES } else { 1 };
        let (nu, nv) = (columns * fine, (rows - 1) * fine + 1);

        let mut best: Option<(Candidate, (usize, f64))> = None;
        let mut tries = 0;
        'layouts: for layout in 0..MAX_LAYOUTS {
            let blobs = layout::draw(config.kind, seed, layout, &frame, land_share, n);
            // The noise spans a few of its deviations: the polar rows sink as far below the sea.
            let polar_sea = POLAR_DEVIATIONS * roughness(config.kind);
            let mut mask = Mask::new(&blobs, config.kind == MapType::InlandSea, polar_sea, &frame, nu, nv);
            if config.ranges {
                let plates = layout::plates(seed, layout, &frame, n, rows);
                // Fractal has no layout: its ridges rise wherever they run (island arcs at sea).
                mask.add_ridges(&plates, RIDGE_HEIGHT, config.kind != MapType::Fractal);
                let land = Land { uv: &uv, noise: &noise, graph: &graph, sea_share: level, thresholds };
                untangle(&mut mask, &land, f64::from(config.mountains));
            }
            let values: Vec<f64> = uv.iter().zip(&noise).map(|(&(u, v), z)| mask.at(u, v) + z).collect();
            let mut sorted = values.clone();
            sorted.sort_unstable_by(f64::total_cmp);
            for sea_share in SEA_STEPS.map(|step| level + step * SEA_SHARE_TOLERANCE) {
                tries += 1;
                let remap = Remap::new(&sorted, sea_share, f64::from(config.mountains), thresholds);
                let heights: Vec<f32> = values.iter().map(|&v| remap.height(v) as f32).collect();
                let sea: Vec<bool> = heights.iter().map(|&h| h < thresholds.0).collect();
                let mountain: Vec<bool> = heights.iter().map(|&h| h >= thresholds.1).collect();
                let checks = targets::measure(config, &graph, &sea, &mountain);
                let score = score(&checks);
                let ranges_only = checks.iter().filter(|c| !c.met()).all(|c| c.target.is_about_ranges());
                // The mask is copied only for a try that is the best so far.
                if best.as_ref().is_none_or(|(_, s)| score.0 < s.0 || (score.0 == s.0 && score.1 < s.1)) {
                    let candidate = Candidate { layout, sea_share, mask: mask.clone(), remap, checks };
                    best = Some((candidate, score));
                }
                if score.0 == 0 {
                    break 'layouts;
                }
                // Another sea share moves the coasts, not the ranges: a try that misses only
                // the ranges' targets goes on to the next layout.
                if ranges_only {
                    continue 'layouts;
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

/// What [`untangle`] reads of the map: each tile center's `(u, v)` and noise, the tile graph,
/// and the sea share and thresholds it classifies at.
struct Land<'a> {
    uv: &'a [(f64, f64)],
    noise: &'a [f64],
    graph: &'a TileGraph,
    sea_share: f64,
    thresholds: (f32, f32),
}

/// Rounds of [`untangle`] at most.
const UNTANGLE_ROUNDS: usize = 6;

/// Opens the knots of a layout's ranges, in at most [`UNTANGLE_ROUNDS`] rounds: where the
/// mountains (the highest `mountains` share of the land) form a blob (a mountain with 5 or 6
/// mountain neighbors) or run straight along a hex axis for more than [`MAX_STRAIGHT_RIDGE`](knots::MAX_STRAIGHT_RIDGE)
/// tiles, the mask under those tiles' centers sinks to hill height, so they become valleys and
/// passes; the share of mountains is kept by the remap, which raises the next highest land.
/// The mask only changes at grid nodes around the knots' centers (which no other tile center
/// reads, at [`RANGE_NODES`] nodes a tile), so every height stays a pure function of the point.
fn untangle(mask: &mut Mask, land: &Land<'_>, mountains: f64) {
    for _ in 0..UNTANGLE_ROUNDS {
        let values: Vec<f64> = land.uv.iter().zip(land.noise).map(|(&(u, v), z)| mask.at(u, v) + z).collect();
        let mut sorted = values.clone();
        sorted.sort_unstable_by(f64::total_cmp);
        let remap = Remap::new(&sorted, land.sea_share, mountains, land.thresholds);
        let mountain: Vec<bool> = values.iter().map(|&v| v >= remap.mountain).collect();
        let knots = knots::knots(land.graph, &|i| mountain[i]);
        if knots.is_empty() {
            return;
        }
        // Down to a quarter of the way from the sea's knot to the mountains'.
        let hill = remap.sea + 0.75 * (remap.mountain - remap.sea);
        for i in knots {
            let (u, v) = land.uv[i];
            mask.lower_at(u, v, values[i] - hill);
        }
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
pub(crate) fn score(checks: &[TargetCheck]) -> (usize, f64) {
    let missed = checks.iter().filter(|c| !c.met()).count();
    let by = checks.iter().map(TargetCheck::miss).filter(|m| m.is_finite()).sum();
    (missed, by)
}

/// How much the fBm shapes a type's coasts, in units of the mask's step from sea to land per
/// standard deviation of the noise. Fractal is the noise alone (its mask is empty).
pub(crate) fn roughness(kind: MapType) -> f64 {
    match kind {
        MapType::Pangaea | MapType::InlandSea => 0.25,
        MapType::Continents | MapType::SmallContinents => 0.2,
        MapType::Archipelago => 0.18,
        MapType::Fractal => 1.0,
    }
}

/// How deep the polar rows' sea lies, in deviations of the noise.
const POLAR_DEVIATIONS: f64 = 4.0;

/// Nodes of the mask a tile, each way, on a map with ranges.
const RANGE_NODES: usize = 2;

/// How much a ridge of [`Plates`] raises the land (in units of the mask's step from sea to
/// land), so the highest land, the mountains, lies along the ridges.
const RIDGE_HEIGHT: f64 = 4.0;

/// The monotone piecewise-linear curve from a value to a height: the lowest tile's value to 0,
/// the sea knot to the sea threshold, the mountain knot to the mountain threshold, the highest
/// tile's value to 1.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Remap {
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
    pub(crate) fn new(sorted: &[f64], sea_share: f64, mountains: f64, (sea, mountain): (f32, f32)) -> Self {
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
    pub(crate) fn height(&self, value: f64) -> f64 {
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
