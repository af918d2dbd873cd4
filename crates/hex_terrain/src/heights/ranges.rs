//! Mountain ranges of a map type ([`MapTypeConfig::ranges`](crate::MapTypeConfig::ranges)):
//! tectonic plates, as Civilization V's map scripts grow them (from 4 plates on its smallest
//! map to 32 on its largest). Plates are points of the map, each drifting its own way; where
//! two plates meet head on, a ridge rises along the line between them, highest on the line and
//! gone [`RIDGE_WIDTH`] rows away. The lines are bent by a few periodic waves, long ones and
//! short ones, so a range winds as real ones do rather than running straight along a row of
//! tiles, and broken by passes about every [`PASS_SPACING`] tiles, where the ridge sinks (as
//! Civilization V's `FractalWorld.lua` leaves gaps in its ridge lines).
//!
//! A ridge is a pure function of the point and the plates (which the seed draws), periodic
//! east-west on a wrapping map.

use std::f64::consts::PI;

/// How far from the line between two plates their ridge reaches, in rows of tiles.
pub const RIDGE_WIDTH: f64 = 0.7;

/// Waves bending the plates' lines.
const WAVES: usize = 3;

/// A plate near a point: the squared distance, the offset from the point, the plate's index.
type Nearest = (f64, [f64; 2], usize);

/// Every wave of a [`Plates`]: bends, wobbles and passes.
const ALL_WAVES: usize = 2 * WAVES + 2 + 3;

/// The waves of a [`Plates`] on a grid ([`Plates::wave_grid`]): each wave's amplitude, and its
/// phase's sine and cosine along each column and each row.
pub(crate) struct WaveGrid {
    amplitudes: [f64; ALL_WAVES],
    columns: Vec<[(f64, f64); ALL_WAVES]>,
    rows: Vec<[(f64, f64); ALL_WAVES]>,
}

/// About how far apart (in tiles) the passes of a range lie: the wavelength of the waves whose
/// sum opens them.
pub const PASS_SPACING: f64 = 9.0;

/// The wavelength (in tiles) of the short waves bending a range, and how far (in tiles) they
/// move it either way.
const WOBBLE: (f64, f64) = (9.0, 1.0);

/// The passes' waves' mean below which a range has a pass, and above which none.
const PASS_LOW: f64 = -0.35;
const PASS_HIGH: f64 = 0.1;

/// One plate: where it lies and where it drifts.
#[derive(Debug, Clone, Copy)]
struct Plate {
    u: f64,
    v: f64,
    /// Its drift, a unit vector in `(u * aspect, v)` space.
    drift: [f64; 2],
}

/// A wave bending the lines: `amplitude * sin(2π (ku u + kv v) + phase)`, added to `u` or `v`.
#[derive(Debug, Clone, Copy)]
struct Wave {
    ku: f64,
    kv: f64,
    phase: f64,
    amplitude: f64,
}

/// The plates of a layout.
#[derive(Debug, Clone)]
pub struct Plates {
    plates: Vec<Plate>,
    /// Waves added to `u` and to `v` before the nearest plates are found.
    waves: [[Wave; WAVES]; 2],
    /// Short waves added to `u` and to `v` too, [`WOBBLE`] long.
    wobble: [Wave; 2],
    /// Waves whose sum opens the passes, [`PASS_SPACING`] long.
    passes: [Wave; 3],
    wraps: bool,
    /// Width over height of the map.
    aspect: f64,
    /// [`RIDGE_WIDTH`] in `v` units.
    width: f64,
    /// The plates that can be the two nearest to a point, by cell.
    lookup: Lookup,
}

/// Cells over the map (and a margin past a map that does not wrap, where bent points go), each
/// with the plates that can be the two nearest to a point in it: those no farther from the
/// cell's center than the second nearest plate is, plus the cell's diameter. A point's two
/// nearest plates found among its cell's are the two nearest of all (ties included: the lists
/// keep the plates' order).
#[derive(Debug, Clone)]
struct Lookup {
    wraps: bool,
    candidates: Vec<Vec<u16>>,
}

/// Cells of a [`Lookup`] across and down; the `u` and `v` it covers past the map.
const LOOKUP_CELLS: (usize, usize) = (24, 16);
const LOOKUP_MARGIN: f64 = 0.25;

impl Lookup {
    fn new(plates: &[Plate], wraps: bool, aspect: f64) -> Self {
        let (cu, cv) = LOOKUP_CELLS;
        let mut candidates = Vec::with_capacity(cu * cv);
        for j in 0..cv {
            for i in 0..cu {
                let ((u0, u1), (v0, v1)) = (Self::span(wraps, i, cu), Self::span(false, j, cv));
                let (uc, vc) = ((u0 + u1) / 2.0, (v0 + v1) / 2.0);
                let half = (((u1 - u0) / 2.0 * aspect).powi(2) + ((v1 - v0) / 2.0).powi(2)).sqrt();
                let d: Vec<f64> = plates
                    .iter()
                    .map(|p| {
                        let mut du = p.u - uc;
                        if wraps {
                            du -= du.round();
                        }
                        ((du * aspect).powi(2) + (p.v - vc).powi(2)).sqrt()
                    })
                    .collect();
                let mut sorted = d.clone();
                sorted.sort_by(f64::total_cmp);
                let reach = sorted.get(1).copied().unwrap_or(f64::INFINITY) + 2.0 * half + 1e-9;
                candidates.push((0..plates.len()).filter(|&k| d[k] <= reach).map(|k| k as u16).collect());
            }
        }
        Self { wraps, candidates }
    }

    /// Where cell `k` of `n` lies in `u` (periodic when `wraps`) or `v` (with the margin).
    fn span(wraps: bool, k: usize, n: usize) -> (f64, f64) {
        let (lo, hi) = if wraps { (0.0, 1.0) } else { (-LOOKUP_MARGIN, 1.0 + LOOKUP_MARGIN) };
        let step = (hi - lo) / n as f64;
        (lo + step * k as f64, lo + step * (k + 1) as f64)
    }

    /// The cell of `(u, v)`; `None` past the cells.
    fn cell(&self, u: f64, v: f64) -> Option<usize> {
        let (cu, cv) = LOOKUP_CELLS;
        let index = |x: f64, wraps: bool, n: usize| {
            let (lo, hi) = if wraps { (0.0, 1.0) } else { (-LOOKUP_MARGIN, 1.0 + LOOKUP_MARGIN) };
            let x = if wraps { x.rem_euclid(1.0) } else { x };
            let t = (x - lo) / (hi - lo) * n as f64;
            (t >= 0.0 && t < n as f64).then_some(t as usize)
        };
        Some(index(v, false, cv)? * cu + index(u, self.wraps, cu)?)
    }
}

impl Plates {
    /// How many plates a map of `tiles` tiles has: one for every 80 tiles, 14 on a Civilization
    /// Duel map (1,144 tiles), 87 on a Huge one (6,996). More than Civilization V's 4 to 32,
    /// so that ranges a tile wide and broken by passes hold the mountains' share.
    #[must_use]
    pub fn count(tiles: usize) -> usize {
        (tiles / 80).clamp(6, 96)
    }

    /// Draws `count` plates from `next` (numbers in `[0, 1)`), on a map `rows` tall.
    pub fn draw(count: usize, wraps: bool, aspect: f64, rows: usize, mut next: impl FnMut() -> f64) -> Self {
        let plates: Vec<Plate> = (0..count)
            .map(|_| {
                let (u, v) = (next(), 0.1 + 0.8 * next());
                let angle = 2.0 * PI * next();
                Plate { u, v, drift: [libm::cos(angle), libm::sin(angle)] }
            })
            .collect();
        let mut wave = |amplitude: f64| Wave {
            // Whole waves across the map (periodic on a wrapping one), one to three.
            ku: (1.0 + (next() * 3.0).floor()) * if next() < 0.5 { 1.0 } else { -1.0 },
            kv: 1.0 + (next() * 3.0).floor(),
            phase: 2.0 * PI * next(),
            amplitude,
        };
        let waves = [[wave(0.03), wave(0.02), wave(0.01)], [wave(0.04), wave(0.025), wave(0.015)]];
        let row = 1.0 / (rows.max(2) - 1) as f64;
        // A wave `length` tiles long in a direction drawn, with whole waves across a wrapping
        // map's width.
        let mut short = |length: f64, amplitude: f64| {
            let angle = 2.0 * PI * next();
            let cycles = 1.0 / (length * row);
            let ku = (cycles * libm::cos(angle) * aspect).round();
            Wave {
                ku: if wraps { ku } else { cycles * libm::cos(angle) * aspect },
                kv: cycles * libm::sin(angle),
                phase: 2.0 * PI * next(),
                amplitude,
            }
        };
        let wobble = [short(WOBBLE.0, WOBBLE.1 * row / aspect), short(WOBBLE.0, WOBBLE.1 * row)];
        let passes = [short(PASS_SPACING, 1.0), short(PASS_SPACING, 1.0), short(PASS_SPACING, 1.0)];
        let lookup = Lookup::new(&plates, wraps, aspect);
        Self { plates, waves, wobble, passes, wraps, aspect, width: RIDGE_WIDTH * row, lookup }
    }

    /// The ridge at `(u, v)`: 1 on the line between two plates drifting toward each other (less
    /// as they drift less head on), falling to 0 a ridge width away; 0 between plates drifting
    /// apart or alongside, and in the passes.
    #[cfg(test)]
    fn ridge(&self, u: f64, v: f64) -> f64 {
        let values = self.all_waves().map(|w| w.amplitude * libm::sin(2.0 * PI * (w.ku * u + w.kv * v) + w.phase));
        self.ridge_with(u, v, &values)
    }

    /// Every wave, in [`WaveGrid`]'s order: the bends of `u`, of `v`, the wobbles, the passes.
    fn all_waves(&self) -> [Wave; ALL_WAVES] {
        let [bu, bv] = self.waves;
        let [wu, wv] = self.wobble;
        let [p0, p1, p2] = self.passes;
        [bu[0], bu[1], bu[2], bv[0], bv[1], bv[2], wu, wv, p0, p1, p2]
    }

    /// The waves' values on a grid of columns at `us` and rows at `vs`: `sin(a + b)` as
    /// `sin a cos b + cos a sin b`, a sine and a cosine a column and a row each, so a node costs
    /// a few products ([`Plates::ridge_on`] reads them).
    pub(crate) fn wave_grid(&self, us: &[f64], vs: &[f64]) -> WaveGrid {
        let waves = self.all_waves();
        let columns = us.iter().map(|&u| waves.map(|w| libm::sincos(2.0 * PI * w.ku * u))).collect();
        let rows = vs.iter().map(|&v| waves.map(|w| libm::sincos(2.0 * PI * w.kv * v + w.phase))).collect();
        WaveGrid { amplitudes: waves.map(|w| w.amplitude), columns, rows }
    }

    /// The ridge at node `(i, j)` of `grid` (column `us[i]`, row `vs[j]`): [`Plates::ridge`] with
    /// the waves read from the grid.
    pub(crate) fn ridge_on(&self, grid: &WaveGrid, (i, j): (usize, usize), (u, v): (f64, f64)) -> f64 {
        let (c, r) = (&grid.columns[i], &grid.rows[j]);
        let values: [f64; ALL_WAVES] =
            std::array::from_fn(|k| grid.amplitudes[k] * (c[k].0 * r[k].1 + c[k].1 * r[k].0));
        self.ridge_with(u, v, &values)
    }

    /// The two nearest of the `candidates` plates to `(u, v)` (the first of equals), as their
    /// squared distance, their offset from the point (the short way round) and their index.
    fn nearest_two(&self, u: f64, v: f64, candidates: &[u16]) -> (Nearest, Nearest) {
        let (mut first, mut second) = ((f64::INFINITY, [0.0; 2], 0), (f64::INFINITY, [0.0; 2], 0));
        for &i in candidates {
            let (i, plate) = (usize::from(i), &self.plates[usize::from(i)]);
            let mut du = plate.u - u;
            if self.wraps {
                du -= du.round();
            }
            let offset = [du * self.aspect, plate.v - v];
            let d2 = offset[0] * offset[0] + offset[1] * offset[1];
            if d2 < first.0 {
                second = first;
                first = (d2, offset, i);
            } else if d2 < second.0 {
                second = (d2, offset, i);
            }
        }
        (first, second)
    }

    /// The ridge at `(u, v)` from the waves' values there.
    fn ridge_with(&self, u: f64, v: f64, w: &[f64; ALL_WAVES]) -> f64 {
        // Where the passes' waves sum low the ridge sinks: no ridge below PASS_LOW, all of it
        // above PASS_HIGH (about a fifth of a range's length is pass).
        let s = (w[8] + w[9] + w[10]) / 3.0;
        let open = ((s - PASS_LOW) / (PASS_HIGH - PASS_LOW)).clamp(0.0, 1.0);
        if open == 0.0 {
            return 0.0;
        }
        let open = open * open * (3.0 - 2.0 * open);
        let (u, v) = (u + w[0] + w[1] + w[2] + w[6], v + w[3] + w[4] + w[5] + w[7]);
        let all: Vec<u16>;
        let candidates = match self.lookup.cell(u, v) {
            Some(k) => &self.lookup.candidates[k],
            None => {
                all = (0..self.plates.len() as u16).collect();
                &all
            }
        };
        let (first, second) = self.nearest_two(u, v, candidates);
        if !second.0.is_finite() {
            return 0.0;
        }
        // Distance to the line between them (their Voronoi edge) along the line joining them.
        let between = [second.1[0] - first.1[0], second.1[1] - first.1[1]];
        let apart = (between[0] * between[0] + between[1] * between[1]).sqrt().max(1e-12);
        let to_line = (second.0 - first.0) / (2.0 * apart);
        if to_line >= self.width {
            return 0.0;
        }
        // How head on they meet: the first plate's drift toward the second, less the second's.
        let (a, b) = (self.plates[first.2].drift, self.plates[second.2].drift);
        let toward = ((a[0] - b[0]) * between[0] + (a[1] - b[1]) * between[1]) / apart;
        let t = 1.0 - to_line / self.width;
        (0.4 + 0.6 * toward.clamp(0.0, 1.0)) * t * t * open
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Numbers in `[0, 1)` from a seed (an LCG: the test's own).
    fn numbers(mut state: u64) -> impl FnMut() -> f64 {
        move || {
            state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// The lookup's candidates hold the two nearest plates of every point, the same two as a
    /// search of every plate, on maps wrapping or not, of many plates or few, at points on the
    /// map and past it.
    #[test]
    fn the_lookup_finds_the_two_nearest_plates() {
        for (seed, count, wraps, aspect) in
            [(1, 6, true, 1.55), (2, 96, false, 1.6), (3, 40, true, 2.0), (4, 13, false, 1.0)]
        {
            let mut next = numbers(seed);
            let plates = Plates::draw(count, wraps, aspect, 54, &mut next);
            let all: Vec<u16> = (0..count as u16).collect();
            for _ in 0..20_000 {
                let (u, v) = (next() * 1.6 - 0.3, next() * 1.6 - 0.3);
                let Some(cell) = plates.lookup.cell(u, v) else { continue };
                let (a, b) = plates.nearest_two(u, v, &plates.lookup.candidates[cell]);
                let (c, d) = plates.nearest_two(u, v, &all);
                assert_eq!((a.2, b.2), (c.2, d.2), "at ({u}, {v})");
            }
        }
    }

    /// The ridge read from the grid's waves is the ridge with its waves computed at the point.
    #[test]
    fn the_grid_waves_equal_the_point_waves() {
        let mut next = numbers(9);
        let plates = Plates::draw(30, true, 1.55, 54, &mut next);
        let us: Vec<f64> = (0..168).map(|i| f64::from(i) / 168.0).collect();
        let vs: Vec<f64> = (0..107).map(|j| f64::from(j) / 106.0).collect();
        let grid = plates.wave_grid(&us, &vs);
        let mut ridges = 0;
        for (j, &v) in vs.iter().enumerate() {
            for (i, &u) in us.iter().enumerate() {
                let (a, b) = (plates.ridge_on(&grid, (i, j), (u, v)), plates.ridge(u, v));
                assert!((a - b).abs() < 1e-6, "at ({u}, {v}): {a} against {b}");
                ridges += usize::from(b > 0.0);
            }
        }
        assert!(ridges > 100, "{ridges} nodes on a ridge");
    }
}
