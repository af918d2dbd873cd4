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
}

impl Plates {
    /// How many plates a map of `tiles` tiles has: 4 on a Civilization Duel map (about 1,100
    /// tiles), 32 on a Huge one (about 7,000), in proportion between.
    #[must_use]
    pub fn count(tiles: usize) -> usize {
        (tiles / 80).clamp(6, 96)
    }

    /// Draws `count` plates from `next` (numbers in `[0, 1)`), on a map `rows` tall.
    pub fn draw(count: usize, wraps: bool, aspect: f64, rows: usize, mut next: impl FnMut() -> f64) -> Self {
        let plates = (0..count)
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
        Self { plates, waves, wobble, passes, wraps, aspect, width: RIDGE_WIDTH * row }
    }

    /// The ridge at `(u, v)`: 1 on the line between two plates drifting toward each other (less
    /// as they drift less head on), falling to 0 a ridge width away; 0 between plates drifting
    /// apart or alongside, and in the passes.
    #[must_use]
    pub fn ridge(&self, u: f64, v: f64) -> f64 {
        let wave = |w: &Wave| w.amplitude * libm::sin(2.0 * PI * (w.ku * u + w.kv * v) + w.phase);
        let bend = |waves: &[Wave; WAVES]| waves.iter().map(wave).sum::<f64>();
        // Where the passes' waves sum low the ridge sinks: no ridge below PASS_LOW, all of it
        // above PASS_HIGH (about a fifth of a range's length is pass).
        let s = self.passes.iter().map(wave).sum::<f64>() / 3.0;
        let open = ((s - PASS_LOW) / (PASS_HIGH - PASS_LOW)).clamp(0.0, 1.0);
        if open == 0.0 {
            return 0.0;
        }
        let open = open * open * (3.0 - 2.0 * open);
        let (u, v) =
            (u + bend(&self.waves[0]) + wave(&self.wobble[0]), v + bend(&self.waves[1]) + wave(&self.wobble[1]));
        // The two nearest plates, as offsets from the point (the short way round).
        let (mut first, mut second) = ((f64::INFINITY, [0.0; 2], 0), (f64::INFINITY, [0.0; 2], 0));
        for (i, plate) in self.plates.iter().enumerate() {
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
