//! Map types on a globe: the flat map's [`MapType`]s (the same sea shares and landmass targets,
//! measured on the globe's tile graph) from a layout of spherical caps.
//!
//! A layout is drawn from the seed as on a flat map, on the sphere: continents are chains of core
//! caps with smaller caps around them, Continents' run north to south, Pangaea's along the
//! equator, Small Continents and the largest islands of an Archipelago spread by best candidate
//! (the others beside an island placed), an Inland Sea one sea cap ringed by land. Each cluster
//! sums its caps (`(1 - (chord / radius)^2)^2` inside a cap), clamped to 1; the mask is the
//! highest cluster. A point's value is
//!
//! ```text
//! value = mask(direction) + roughness * (fbm(direction) - mean) / deviation
//! ```
//!
//! with the fBm's mean and deviation over the tile centers, remapped by the flat map's
//! piecewise-linear curve whose knots leave exactly the type's share of the tiles below the sea
//! threshold and the config's share of the land above the mountain threshold. The layouts and sea
//! shares are tried as on a flat map (at most [`MAX_TRIES`](crate::MAX_TRIES)) and the best kept.
//! Then a point's height is a pure function of its direction: the caps, mean, deviation and knots
//! are fixed numbers, and each point reads only the caps that reach its diamond.
//!
//! On a globe a map type's rows are bands of latitude (`3 f + 1` of them, about a tile each,
//! pole to pole), and no row is an edge: no polar sea is forced (land may reach a pole, where the
//! climate makes it snow).

use std::f64::consts::PI;

use super::GlobeGrid;
use super::project::{self, Dir, from_lat_lon};
use crate::config::{MapType, MapTypeConfig, SEA_SHARE_TOLERANCE};
use crate::heights::graph::TileGraph;
use crate::heights::layout::Draw;
use crate::heights::map_type::{Remap, roughness, score};
use crate::heights::targets::{self, MapTypeReport};
use crate::heights::{MAX_LAYOUTS, SEA_STEPS};

/// Salt of the globe layouts' draws.
const SALT: i64 = 0x4750_4c59;

/// How far a core cap reaches beyond the radius of a cap of its land's area.
const CLUSTER_REACH: f64 = 1.3;

/// The island groups of an Archipelago: its largest islands, spread round the globe before the
/// others gather beside them.
const ARCHIPELAGO_GROUPS: usize = 10;

/// A cap of a layout: its cluster, center and radius (as a chord of the unit sphere).
#[derive(Debug, Clone, Copy)]
struct Cap {
    cluster: u32,
    center: Dir,
    chord: f64,
}

/// A map type compiled for one globe.
#[derive(Debug, Clone)]
pub(super) struct GlobeMapType {
    /// For each diamond, the caps reaching it, cluster by cluster.
    caps: Vec<Vec<Cap>>,
    /// Every cap, for the poles.
    all: Vec<Cap>,
    invert: bool,
    mean: f64,
    weight: f64,
    remap: Remap,
    report: MapTypeReport,
}

/// The chord of a cap of `area` steradians (at most the sphere's), times `reach`.
fn chord_of(area: f64, reach: f64) -> f64 {
    let angle = (1.0 - (area / (2.0 * PI)).min(2.0)).clamp(-1.0, 1.0).acos() * reach;
    2.0 * (angle.min(PI) / 2.0).sin()
}

/// The direction `angle` radians from `at` toward bearing `bearing` (0 north, east positive).
fn toward(at: Dir, bearing: f64, angle: f64) -> Dir {
    let north = [0.0, 1.0, 0.0];
    let east = project::cross(north, at);
    let east = if project::dot(east, east) < 1e-18 { [1.0, 0.0, 0.0] } else { project::normalize(east) };
    let up = project::cross(at, east);
    let (s, c) = (angle.sin(), angle.cos());
    let dir = [
        east[0] * bearing.sin() + up[0] * bearing.cos(),
        east[1] * bearing.sin() + up[1] * bearing.cos(),
        east[2] * bearing.sin() + up[2] * bearing.cos(),
    ];
    project::normalize([at[0] * c + dir[0] * s, at[1] * c + dir[1] * s, at[2] * c + dir[2] * s])
}

/// A core cap of cluster `id` holding about `area` and `satellites` smaller caps around it,
/// spread `stretch` times as far north-south as east-west.
fn cores(draw: &mut Draw, caps: &mut Vec<Cap>, id: u32, at: Dir, area: f64, satellites: u32, stretch: f64) {
    let chord = chord_of(area, CLUSTER_REACH);
    caps.push(Cap { cluster: id, center: at, chord });
    let angle = 2.0 * (chord / 2.0).asin();
    for _ in 0..satellites {
        let bearing = draw.range(0.0, 2.0 * PI);
        let reach = angle * draw.range(0.3, 0.7);
        // Stretched: farther along north-south bearings.
        let reach = reach * (stretch.sqrt() * bearing.cos().abs() + bearing.sin().abs() / stretch.sqrt());
        caps.push(Cap { cluster: id, center: toward(at, bearing, reach), chord: chord * draw.range(0.4, 0.65) });
    }
}

/// Of a few draws (latitudes within `lat` radians), the direction farthest from every center
/// placed.
fn best_candidate(draw: &mut Draw, centers: &[Dir], lat: f64) -> Dir {
    let mut best = ([1.0, 0.0, 0.0], f64::NEG_INFINITY);
    for _ in 0..16 {
        let at = from_lat_lon((draw.range(-1.0, 1.0) * lat.sin()).asin(), draw.range(0.0, 2.0 * PI));
        let nearest = centers.iter().map(|&c| -project::dot(c, at)).fold(f64::INFINITY, f64::min);
        if nearest > best.1 {
            best = (at, nearest);
        }
    }
    best.0
}

/// The caps of layout `layout` of a type (land, or the sea of an Inland Sea), cluster by
/// cluster.
fn draw_layout(kind: MapType, seed: u32, layout: u32, land_share: f64, tiles: u32) -> Vec<Cap> {
    let mut draw = Draw::new(seed, SALT, layout, 0);
    let land = land_share * 4.0 * PI;
    let mut caps = Vec::new();
    let lon0 = draw.range(0.0, 2.0 * PI);
    match kind {
        MapType::Fractal => {}
        MapType::Pangaea => {
            // A chain of cores along the equator, each in turn north and south of it, spanning
            // about 150 degrees of longitude.
            let count = 4;
            let north = draw.next() < 0.5;
            for k in 0..count {
                let t = (f64::from(k) + 0.5) / f64::from(count) - 0.5;
                let side = if (k % 2 == 0) == north { -1.0 } else { 1.0 };
                let lat = side * draw.range(0.12, 0.28);
                let at = from_lat_lon(lat, lon0 + t * 2.6);
                cores(&mut draw, &mut caps, 0, at, land / f64::from(count) * 1.15, 3, 0.8);
            }
        }
        MapType::Continents => {
            // Two continents, or three on some seeds, spread round the globe, each a chain of
            // cores north to south spanning most of the latitudes.
            let count = if draw.next() < 0.3 { 3 } else { 2 };
            let shares: Vec<f64> = (0..count).map(|_| draw.range(0.85, 1.15)).collect();
            let total: f64 = shares.iter().sum();
            for (k, share) in shares.into_iter().enumerate() {
                let lon = lon0 + 2.0 * PI * k as f64 / f64::from(count) + draw.range(-0.15, 0.15);
                let slant = draw.range(-0.12, 0.12);
                for (j, lat) in [0.62, 0.0, -0.62].into_iter().enumerate() {
                    let lat = lat + draw.range(-0.08, 0.08);
                    let at = from_lat_lon(lat, lon + slant * (j as f64 - 1.0) + draw.range(-0.05, 0.05));
                    cores(&mut draw, &mut caps, k as u32, at, land * share / total / 3.0 * 1.15, 2, 1.4);
                }
            }
        }
        MapType::SmallContinents => {
            let count = if draw.next() < 0.5 { 5 } else { 6 };
            let sizes: Vec<f64> = (0..count).map(|_| draw.range(0.75, 1.25)).collect();
            let total: f64 = sizes.iter().sum();
            let mut centers = Vec::new();
            for (k, size) in sizes.into_iter().enumerate() {
                let at = best_candidate(&mut draw, &centers, 1.1);
                centers.push(at);
                let stretch = draw.range(0.7, 1.5);
                cores(&mut draw, &mut caps, k as u32, at, land * size / total, 4, stretch);
            }
        }
        MapType::Archipelago => {
            // Islands of many sizes (the k-th about (k + 3)^-0.6 of the land), the largest of
            // each group spread, each smaller one beside an island placed, clear of the others:
            // chains and groups rather than dots evenly strewn.
            let count = (tiles / 180).clamp(14, 40) as usize;
            let weights: Vec<f64> = (0..count).map(|k| (k as f64 + 3.0).powf(-0.6)).collect();
            let total: f64 = weights.iter().sum();
            let mut placed: Vec<(Dir, f64)> = Vec::new();
            for (k, weight) in weights.into_iter().enumerate() {
                let area = land * weight / total;
                let angle = 2.0 * (chord_of(area, CLUSTER_REACH) / 2.0).asin();
                let at = if k < ARCHIPELAGO_GROUPS {
                    let centers: Vec<Dir> = placed.iter().map(|p| p.0).collect();
                    best_candidate(&mut draw, &centers, 1.2)
                } else {
                    let mut best = ([1.0, 0.0, 0.0], f64::NEG_INFINITY);
                    for _ in 0..8 {
                        let (near, r) = placed[(draw.next() * placed.len() as f64) as usize];
                        let at = toward(near, draw.range(0.0, 2.0 * PI), (r + angle) * draw.range(1.5, 2.2));
                        let room = placed
                            .iter()
                            .map(|&(c, pr)| project::dot(c, at).clamp(-1.0, 1.0).acos() - (pr + angle) * 1.4)
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
                placed.push((at, angle));
                // Three satellites, stretched one way or the other: long islands and bent ones.
                let stretch = draw.range(0.5, 2.0);
                cores(&mut draw, &mut caps, k as u32, at, area, 3, stretch);
            }
        }
        MapType::InlandSea => {
            let at = from_lat_lon(draw.range(-0.1, 0.1), lon0);
            cores(&mut draw, &mut caps, 0, at, (1.0 - land_share) * 4.0 * PI, 4, 0.9);
        }
    }
    caps
}

/// The mask at a direction from the caps that may reach it (cluster by cluster).
fn mask(caps: &[Cap], invert: bool, dir: Dir) -> f64 {
    let (mut best, mut sum, mut cluster) = (0.0f64, 0.0f64, u32::MAX);
    for cap in caps {
        if cap.cluster != cluster {
            best = best.max(sum.min(1.0));
            (sum, cluster) = (0.0, cap.cluster);
        }
        let d = project::sub(dir, cap.center);
        let t = 1.0 - project::dot(d, d) / (cap.chord * cap.chord);
        if t > 0.0 {
            sum += t * t;
        }
    }
    let value = best.max(sum.min(1.0));
    if invert { 1.0 - value } else { value }
}

/// What [`GlobeMapType::build`] reads of the globe.
pub(super) struct TypeGround<'a> {
    pub(super) config: &'a MapTypeConfig,
    pub(super) seed: u32,
    pub(super) grid: &'a GlobeGrid,
    /// Each tile's center direction and fBm (in `[0, 1]`), by id.
    pub(super) centers: &'a [(Dir, f64)],
    /// Each diamond's middle and the angle from it that holds the diamond.
    pub(super) diamonds: &'a [(Dir, f64)],
    pub(super) thresholds: (f32, f32),
}

impl GlobeMapType {
    /// Draws layouts and sea shares until one meets every target (or keeps the best).
    pub(super) fn build(ground: &TypeGround<'_>) -> Self {
        let config = ground.config;
        let n = ground.centers.len();
        let mean = ground.centers.iter().map(|c| c.1).sum::<f64>() / n as f64;
        let variance = ground.centers.iter().map(|c| (c.1 - mean) * (c.1 - mean)).sum::<f64>() / n as f64;
        let weight = roughness(config.kind) / variance.sqrt().max(1e-9);
        let graph = graph(ground.grid);
        let level = config.sea_share();
        let invert = config.kind == MapType::InlandSea;
        let mut best: Option<(Self, (usize, f64))> = None;
        let mut tries = 0;
        'layouts: for layout in 0..MAX_LAYOUTS {
            let all = draw_layout(config.kind, ground.seed, layout, 1.0 - level, ground.grid.tile_count());
            let values: Vec<f64> =
                ground.centers.iter().map(|&(dir, fbm)| mask(&all, invert, dir) + (fbm - mean) * weight).collect();
            let mut sorted = values.clone();
            sorted.sort_unstable_by(f64::total_cmp);
            for sea_share in SEA_STEPS.map(|step| level + step * SEA_SHARE_TOLERANCE) {
                tries += 1;
                let remap = Remap::new(&sorted, sea_share, f64::from(config.mountains), ground.thresholds);
                let heights: Vec<f32> = values.iter().map(|&v| remap.height(v) as f32).collect();
                let sea: Vec<bool> = heights.iter().map(|&h| h < ground.thresholds.0).collect();
                let mountain: Vec<bool> = heights.iter().map(|&h| h >= ground.thresholds.1).collect();
                let checks = targets::measure(config, &graph, &sea, &mountain);
                let score = score(&checks);
                if best.as_ref().is_none_or(|(_, s)| score.0 < s.0 || (score.0 == s.0 && score.1 < s.1)) {
                    let report = MapTypeReport { kind: config.kind, tries, layout, sea_share, checks };
                    let caps = ground
                        .diamonds
                        .iter()
                        .map(|&(middle, angle)| {
                            all.iter()
                                .copied()
                                .filter(|cap| {
                                    let reach = 2.0 * (cap.chord.min(2.0) / 2.0).asin();
                                    project::dot(middle, cap.center).clamp(-1.0, 1.0).acos() <= angle + reach + 1e-9
                                })
                                .collect()
                        })
                        .collect();
                    let kept = Self { caps, all: all.clone(), invert, mean, weight, remap, report };
                    best = Some((kept, score));
                }
                if score.0 == 0 {
                    break 'layouts;
                }
            }
        }
        let (mut kept, _) = best.expect("at least one try");
        kept.report.tries = tries;
        kept
    }

    /// The normalised height of a point of diamond `diamond` (`None`: a pole) at `dir` whose
    /// fBm is `fbm`, in `[0, 1]`.
    pub(super) fn apply(&self, diamond: Option<u8>, dir: Dir, fbm: f64) -> f64 {
        let caps = diamond.map_or(&self.all, |d| &self.caps[usize::from(d)]);
        self.remap.height(mask(caps, self.invert, dir) + (fbm - self.mean) * self.weight).clamp(0.0, 1.0)
    }

    /// What came of the type.
    pub(super) fn report(&self) -> &MapTypeReport {
        &self.report
    }
}

/// The globe's tiles as a graph to measure targets on: each tile's neighbors going round (a
/// pentagon's sixth none), rows by latitude bands about a tile high, no edge.
fn graph(grid: &GlobeGrid) -> TileGraph {
    let rows = 3 * grid.frequency() + 1;
    let mut neighbors = Vec::with_capacity(grid.tile_count() as usize);
    let mut row = Vec::with_capacity(grid.tile_count() as usize);
    for t in grid.tiles() {
        let around = grid.neighbors(t).expect("a tile of the grid");
        let mut six = [None; 6];
        for (slot, &m) in six.iter_mut().zip(around.as_slice()) {
            *slot = Some(m.0);
        }
        neighbors.push(six);
        let lat = grid.center(t).expect("a tile of the grid")[1].clamp(-1.0, 1.0).asin();
        row.push((((PI / 2.0 - lat) / PI) * f64::from(rows - 1)).round() as u32);
    }
    TileGraph { edge: vec![false; neighbors.len()], neighbors, row, rows }
}
