//! Noise periodic in x, for east-west wrapping maps: each octave's period is a whole number of
//! its noise cells, and the period's last column of cells takes its east corners from column 0,
//! so the noise joins across the period without a seam ([`FastPerlin::get_periodic`], and the
//! table [`PeriodicCells`] a wrapping [`Fbm`](super::Fbm) reads, one load an evaluation).

use super::{FastPerlin, LIMIT, TABLE, clamp01, interpolate, max_x86, min_x86, split};

/// Packed cell of column `cells - 1` (a period's last) whose east corners are column 0's west
/// ones, for row `row`.
#[inline(always)]
fn seam_cell(table: &[u8; TABLE * TABLE], cells: i64, row: usize) -> u8 {
    let last = table[(((cells - 1) & 0xff) as usize) << 8 | row];
    (last & 0b0011_0011) | ((table[row] & 0b0011_0011) << 2)
}

impl FastPerlin {
    /// Noise periodic in `x` with a period of `cells` noise cells (at least 1): equal to
    /// [`FastPerlin::get`] for `x` in `[0, cells - 1)`, and the corner east of the period's last
    /// cell is its first, so the noise joins across `x = cells` without a seam. `y` is as
    /// [`FastPerlin::get`]'s.
    #[must_use]
    #[inline]
    pub fn get_periodic(&self, x: f64, y: f64, cells: i64) -> f64 {
        let cells = cells.max(1);
        let xw = reduce(x, cells as f64, 1.0 / cells as f64);
        let (cx, dx) = periodic_split(xw, cells);
        let (cy, dy) = split(y);
        let row = (cy & 0xff) as usize;
        let cell = if cx == cells - 1 {
            seam_cell(&self.cells, cells, row)
        } else {
            self.cells[((cx & 0xff) as usize) << 8 | row]
        };
        interpolate(cell, dx, dy)
    }
}

/// The cells a wrapping map's fBm reads: the planar packed cells, then for each octave the 256
/// rows of its period's last column with their east corners taken from column 0, so an
/// evaluation picks one index and makes one load.
#[derive(Clone)]
pub(super) struct PeriodicCells {
    /// The period in noise units at frequency 1, and its inverse.
    pub(super) period: f64,
    pub(super) inv_period: f64,
    /// Per octave, the period in noise cells.
    pub(super) cells: Vec<i64>,
    /// Fixed-size, and indexed by masked values, so no index needs a bounds check (which would
    /// stop the lanes from vectorising).
    pub(super) table: Box<[u8; PERIODIC_TABLE]>,
}

/// Octaves [`PeriodicCells`] has room for: the most a config may ask.
pub(super) const PERIODIC_OCTAVES: usize = crate::config::MAX_OCTAVES as usize;
/// Bytes of [`PeriodicCells::table`].
const PERIODIC_TABLE: usize = TABLE * TABLE + PERIODIC_OCTAVES * TABLE;

impl std::fmt::Debug for PeriodicCells {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PeriodicCells")
            .field("period", &self.period)
            .field("cells", &self.cells)
            .finish_non_exhaustive()
    }
}

impl PeriodicCells {
    pub(super) fn new(perlin: &FastPerlin, period: f64, cells: Vec<i64>) -> Self {
        let mut table = Box::new([0_u8; PERIODIC_TABLE]);
        table[..TABLE * TABLE].copy_from_slice(&perlin.cells[..]);
        for (o, &c) in cells.iter().enumerate().take(PERIODIC_OCTAVES) {
            for row in 0..TABLE {
                table[TABLE * TABLE + o * TABLE + row] = seam_cell(&perlin.cells, c, row);
            }
        }
        Self { period, inv_period: 1.0 / period, cells, table }
    }

    /// Octave `octave`'s noise at `xw` in `[0, cells]` (already reduced).
    #[inline(always)]
    pub(super) fn lane(&self, octave: usize, cells: i64, xw: f64, y: f64) -> f64 {
        let (cx, dx) = periodic_split(xw, cells);
        let (cy, dy) = split(y);
        let row = (cy & 0xff) as usize;
        let planar = ((cx & 0xff) as usize) << 8 | row;
        let seam = TABLE * TABLE + (octave % PERIODIC_OCTAVES) * TABLE + row;
        let cell = self.table[if cx == cells - 1 { seam } else { planar }];
        interpolate(cell, dx, dy)
    }
}

/// The cell of `xw` (in `[0, cells]` once reduced) clamped to the period's cells, and the offset
/// in it.
#[inline(always)]
fn periodic_split(xw: f64, cells: i64) -> (i64, f64) {
    // The cast saturates beyond i64 (an infinity) and gives 0 for NaN, as the SIMD kernels'
    // clamped floor does.
    let cx = (xw as i64).clamp(0, cells - 1);
    (cx, clamp01(xw - cx as f64))
}

/// `x` modulo `period`, in `[0, period)` (up to rounding), without a library call.
#[inline(always)]
pub(super) fn reduce(x: f64, period: f64, inv_period: f64) -> f64 {
    let t = max_x86(min_x86(x * inv_period, LIMIT), -LIMIT);
    let q = if t < 0.0 { t as i64 - 1 } else { t as i64 };
    let xw = x - q as f64 * period;
    let xw = if xw >= period { xw - period } else { xw };
    if xw < 0.0 { xw + period } else { xw }
}
