//! Perlin fBm height source (thesis section 5.1, Algorithm 2).
//!
//! [`FastPerlin`] is [`noise::Perlin`]'s 2D noise (same permutation table, same gradients, same
//! fade curve; a test holds it bit-identical to `noise`) computed branch-free, with the
//! gradients of each of the 256x256 lattice cells' four corners packed in one byte of one flat
//! table, so that [`Fbm::sample_batch`] vectorises over several points.
//!
//! A batch runs on a [`Kernel`] picked once, at run time, from what the CPU has: the portable
//! loops, or the AVX2 or AVX-512 kernel (modules `avx2`, `avx512`) on x86-64. Every kernel does
//! the same IEEE operations in the same order (no fused multiply-add), so each gives the same
//! bits for the same point.
//! The periodic noise of east-west wrapping maps is `fbm/periodic.rs`.

use noise::{NoiseFn, Perlin};

use crate::config::NoiseConfig;

#[cfg(target_arch = "x86_64")]
mod avx2;
#[cfg(target_arch = "x86_64")]
mod avx512;
mod periodic;
mod solid;
#[cfg(target_arch = "x86_64")]
mod solid_vbmi;

use periodic::{PeriodicCells, reduce};
pub(crate) use solid::SolidFbm;

const TABLE: usize = 256;
const SCALE_2D: f64 = 2.0 / std::f64::consts::SQRT_2;
/// Coordinates are clamped to `[-2^52, 2^52]` before they are split into a cell and an offset:
/// beyond it an f64 has no fraction left, and inside it the cell fits an integer exactly on
/// every kernel (an `i64` here, an f64 floor in the AVX2 kernel), so all kernels agree on every input,
/// infinities and NaN included (NaN clamps to `2^52`).
const LIMIT: f64 = 4_503_599_627_370_496.0;
/// The solid (f32) noise's [`LIMIT`]: beyond `2^23` an f32 has no fraction left, and inside it
/// the cell fits an `i32` exactly.
const SOLID_LIMIT: f32 = 8_388_608.0;
/// `2 / sqrt(3)`: `noise`'s scale from the 3D gradient sum's range to `[-1, 1]`.
const SCALE_3D: f32 = 1.154_700_5;

/// The floats the noise is computed in: f64 on flat maps, f32 on the globe.
trait Float:
    Copy
    + PartialOrd
    + From<u8>
    + std::ops::Add<Output = Self>
    + std::ops::Sub<Output = Self>
    + std::ops::Mul<Output = Self>
{
}

impl Float for f32 {}
impl Float for f64 {}

/// `a < b ? a : b`: x86's `minpd` (the second operand when either is NaN), written out so that
/// the portable loops and the SIMD kernels treat NaN alike.
#[inline(always)]
fn min_x86<T: Float>(a: T, b: T) -> T {
    if a < b { a } else { b }
}

/// `a > b ? a : b`: x86's `maxpd`.
#[inline(always)]
fn max_x86<T: Float>(a: T, b: T) -> T {
    if a > b { a } else { b }
}

/// `v` clamped to `[0, 1]` (NaN gives 1).
#[inline(always)]
fn clamp01<T: Float>(v: T) -> T {
    max_x86(min_x86(v, T::from(1)), T::from(0))
}

/// The noise cell of a coordinate and the offset in it. `noise` floors with "truncate, minus one
/// at or below zero", so an exact integer at or below zero lands in the cell below it; so does
/// this.
#[inline(always)]
fn split(v: f64) -> (i64, f64) {
    let v = max_x86(min_x86(v, LIMIT), -LIMIT);
    let c = if v <= 0.0 { v as i64 - 1 } else { v as i64 };
    (c, clamp01(v - c as f64))
}

/// `noise`'s `PermutationTable::new(seed)`: `0..=255` shuffled by an `XorShiftRng` seeded with
/// 1 and the seed's little-endian bytes three times.
fn permutation(seed: u32) -> [u8; TABLE] {
    use rand::SeedableRng;
    use rand::seq::SliceRandom;

    let mut bytes = [0_u8; 16];
    bytes[0] = 1;
    for i in 1..4 {
        bytes[i * 4..i * 4 + 4].copy_from_slice(&seed.to_le_bytes());
    }
    let mut rng = rand_xorshift::XorShiftRng::from_seed(bytes);
    let mut table: [u8; TABLE] = std::array::from_fn(|i| i as u8);
    table.shuffle(&mut rng);
    table
}

/// 2D Perlin noise equal to `noise::Perlin::new(seed)` on `[f64; 2]` points.
#[derive(Clone)]
pub struct FastPerlin {
    /// For every cell `(x & 255, y & 255)` (row-major in `x`), the gradient codes (0..4) of its
    /// four corners packed in one byte: `(x, y)` in bits 0-1, `(x+1, y)` in 2-3, `(x, y+1)` in
    /// 4-5, `(x+1, y+1)` in 6-7. One load per evaluation instead of four.
    cells: Box<[u8; TABLE * TABLE]>,
}

impl std::fmt::Debug for FastPerlin {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("FastPerlin { .. }")
    }
}

impl FastPerlin {
    /// Builds the gradient table of `noise::Perlin::new(seed)`.
    ///
    /// `noise` keeps its permutation table private, so it is made here the way `noise` makes
    /// it (`PermutationTable::new`: a `rand_xorshift` generator seeded from the seed's bytes
    /// shuffling `0..=255` with `rand` 0.8's `shuffle`, the same crates `noise` uses), and a
    /// corner's gradient is `noise`'s hash of it: `table[table[x] ^ y] & 3`. A test reads the
    /// gradients back from `noise::Perlin` itself, for many seeds, and compares.
    #[must_use]
    pub fn new(seed: u32) -> Self {
        let table = permutation(seed);
        let gradient = |x: usize, y: usize| table[usize::from(table[x]) ^ y] & 3;
        let mut cells = Box::new([0_u8; TABLE * TABLE]);
        for x in 0..TABLE {
            for y in 0..TABLE {
                let (x1, y1) = ((x + 1) % TABLE, (y + 1) % TABLE);
                cells[x * TABLE + y] =
                    gradient(x, y) | gradient(x1, y) << 2 | gradient(x, y1) << 4 | gradient(x1, y1) << 6;
            }
        }
        Self { cells }
    }

    /// Noise at `(x, y)`, in `[-1, 1]`, within 1e-6 of `noise::Perlin::new(seed).get([x, y])`.
    #[must_use]
    #[inline]
    pub fn get(&self, x: f64, y: f64) -> f64 {
        self.lane(x, y)
    }

    /// One evaluation, branch-free so that a loop over several points vectorises.
    #[inline(always)]
    fn lane(&self, x: f64, y: f64) -> f64 {
        let (cx, dx) = split(x);
        let (cy, dy) = split(y);
        interpolate(self.cells[(((cx & 0xff) << 8) | (cy & 0xff)) as usize], dx, dy)
    }
}

/// The noise inside one cell from its packed corner gradients and the offset in it.
#[inline(always)]
fn interpolate(cell: u8, dx: f64, dy: f64) -> f64 {
    // Gradient code c: (1 - 2 (c & 1), 1 - 2 ((c >> 1) & 1)) is (1,1), (-1,1), (1,-1), (-1,-1).
    let grad = |shift: u8, px: f64, py: f64| {
        let c = cell >> shift;
        (1.0 - 2.0 * f64::from(c & 1)) * px + (1.0 - 2.0 * f64::from((c >> 1) & 1)) * py
    };
    let g00 = grad(0, dx, dy);
    let g10 = grad(2, dx - 1.0, dy);
    let g01 = grad(4, dx, dy - 1.0);
    let g11 = grad(6, dx - 1.0, dy - 1.0);
    let sx = quintic(dx);
    let sy = quintic(dy);
    let result = lerp(lerp(g00, g01, sy), lerp(g10, g11, sy), sx) * SCALE_2D;
    max_x86(min_x86(result, 1.0), -1.0)
}

#[inline(always)]
fn quintic<T: Float>(x: T) -> T {
    x * x * x * (x * (x * T::from(6) - T::from(15)) + T::from(10))
}

#[inline(always)]
fn lerp<T: Float>(a: T, b: T, t: T) -> T {
    b * t + a * (T::from(1) - t)
}

/// Points sampled together by [`Fbm::sample_batch`].
pub const LANES: usize = 8;

/// The instruction set [`Fbm::sample_batch`] runs on. Every kernel gives the same bits for the
/// same point (they do the same IEEE operations in the same order, with no fused multiply-add),
/// so a map is the same whichever one a machine picks; only the speed differs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Kernel {
    /// Plain Rust loops over the batch, which the compiler vectorises for the build's target
    /// (SSE2 on a default x86-64 build): any CPU.
    Portable,
    /// x86-64 with AVX2: the batch as two vectors of four f64 lanes, interleaved.
    Avx2,
    /// x86-64 with AVX-512F: the batch as one vector of eight f64 lanes.
    Avx512,
}

impl Kernel {
    /// Every kernel, supported here or not.
    pub const ALL: [Kernel; 3] = [Kernel::Portable, Kernel::Avx2, Kernel::Avx512];

    /// The fastest kernel this CPU runs (checked at run time, once per process).
    #[must_use]
    pub fn detect() -> Self {
        [Kernel::Avx512, Kernel::Avx2].into_iter().find(|k| k.is_supported()).unwrap_or(Kernel::Portable)
    }

    /// Whether this CPU runs the kernel.
    #[must_use]
    pub fn is_supported(self) -> bool {
        match self {
            Kernel::Portable => true,
            #[cfg(target_arch = "x86_64")]
            Kernel::Avx2 => avx2::supported(),
            #[cfg(target_arch = "x86_64")]
            Kernel::Avx512 => avx512::supported(),
            #[cfg(not(target_arch = "x86_64"))]
            Kernel::Avx2 | Kernel::Avx512 => false,
        }
    }

    /// The kernel's name, as benchmarks print it.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Kernel::Portable => "portable",
            Kernel::Avx2 => "avx2",
            Kernel::Avx512 => "avx512",
        }
    }
}

/// Fractal Brownian motion over one Perlin function, normalised to `[0, 1]` by a fixed mapping.
///
/// Algorithm 2: `sum(amp_i * perlin(p * freq_i)) / sum(amp_i)`, with `amp` multiplied by the
/// persistence and `freq` by the lacunarity at each octave. `noise`'s Perlin lies in `[-1, 1]`;
/// `(v + 1) / 2` maps it to the thesis' `[0, 1]` without looking at any particular map, so any
/// chunk of the world gets the same heights as the whole.
#[derive(Debug, Clone)]
pub struct Fbm {
    perlin: FastPerlin,
    /// `(frequency, amplitude / sum of amplitudes)` per octave.
    octaves: Vec<(f64, f64)>,
    /// Noise units per hex radius.
    inv_scale: f64,
    /// On a wrapping map, the period and the cells the periodic noise reads.
    periods: Option<PeriodicCells>,
    /// What [`Fbm::sample_batch`] runs on: only ever a kernel this CPU supports.
    kernel: Kernel,
}

impl Fbm {
    /// fBm for a seed and validated noise parameters.
    #[must_use]
    pub fn new(seed: u32, config: &NoiseConfig) -> Self {
        let mut octaves = Vec::with_capacity(config.octaves as usize);
        let (mut freq, mut amp, mut total) = (1.0_f64, 1.0_f64, 0.0_f64);
        for _ in 0..config.octaves {
            octaves.push((freq, amp));
            total += amp;
            amp *= config.persistence;
            freq *= config.lacunarity;
        }
        for o in &mut octaves {
            o.1 /= total;
        }
        // The thesis' vertex step is a quarter of a hex radius (its 9x9 frame spans two hexes),
        // and its noise scale counts those steps.
        Self {
            perlin: FastPerlin::new(seed),
            octaves,
            inv_scale: 4.0 / config.scale,
            periods: None,
            kernel: Kernel::detect(),
        }
    }

    /// fBm periodic in x with a period of `width` hex radii, for a wrapping map.
    ///
    /// Each octave's frequency is rounded so that `width` holds a whole number of its noise
    /// cells (at least one), and that octave's noise is periodic over those cells
    /// ([`FastPerlin::get_periodic`]): the sum joins across the period without a seam, with the
    /// gradients, fade curve and statistics of the planar noise (no projection stretches it).
    /// The rounding changes an octave's frequency by at most half a cell over the map's width.
    #[must_use]
    pub fn wrapped(seed: u32, config: &NoiseConfig, width: f64) -> Self {
        let mut fbm = Self::new(seed, config);
        let cells_per_frequency = width * fbm.inv_scale;
        let mut periods = Vec::with_capacity(fbm.octaves.len());
        for (freq, _) in &mut fbm.octaves {
            let cells = (cells_per_frequency * *freq).round().clamp(1.0, (1_u64 << 52) as f64);
            *freq = cells / cells_per_frequency;
            periods.push(cells as i64);
        }
        fbm.periods = Some(PeriodicCells::new(&fbm.perlin, cells_per_frequency, periods));
        fbm
    }

    /// The same fBm on another kernel, or `None` if this CPU does not run it. The output is the
    /// same bits on every kernel: this is for tests and benchmarks that compare them.
    #[must_use]
    pub fn with_kernel(mut self, kernel: Kernel) -> Option<Self> {
        kernel.is_supported().then(|| {
            self.kernel = kernel;
            self
        })
    }

    /// The kernel [`Fbm::sample_batch`] runs on ([`Kernel::detect`] unless
    /// [`Fbm::with_kernel`] chose another).
    #[must_use]
    pub fn kernel(&self) -> Kernel {
        self.kernel
    }

    /// Per octave on a wrapping map, the period in noise cells; `None` for planar noise.
    #[must_use]
    pub fn periods(&self) -> Option<Vec<i64>> {
        self.periods.as_ref().map(|p| p.cells.clone())
    }

    /// Per octave, `(frequency, amplitude)`, the amplitudes normalised to sum to 1.
    #[must_use]
    pub fn octaves(&self) -> &[(f64, f64)] {
        &self.octaves
    }

    /// Normalised height at a position measured in hex radii.
    #[must_use]
    #[inline]
    pub fn sample(&self, x: f64, z: f64) -> f64 {
        let mut out = [0.0; LANES];
        let mut xs = [0.0; LANES];
        let mut zs = [0.0; LANES];
        xs[0] = x;
        zs[0] = z;
        self.sample_lanes::<1>(&xs, &zs, &mut out);
        out[0]
    }

    /// [`Fbm::sample`] at `LANES` points at once, octave by octave, so the per-point work
    /// vectorises. Every lane gets exactly the bits `sample` gives for its point.
    #[inline]
    pub fn sample_batch(&self, xs: &[f64; LANES], zs: &[f64; LANES], out: &mut [f64; LANES]) {
        match self.kernel {
            #[cfg(target_arch = "x86_64")]
            Kernel::Avx2 => avx2::sample_batch(self, xs, zs, out),
            #[cfg(target_arch = "x86_64")]
            Kernel::Avx512 => avx512::sample_batch(self, xs, zs, out),
            _ => self.sample_lanes::<LANES>(xs, zs, out),
        }
    }

    #[inline(always)]
    fn sample_lanes<const L: usize>(&self, xs: &[f64; LANES], zs: &[f64; LANES], out: &mut [f64; LANES]) {
        let mut total = [0.0_f64; L];
        let mut px = [0.0_f64; L];
        let mut pz = [0.0_f64; L];
        for l in 0..L {
            px[l] = xs[l] * self.inv_scale;
            pz[l] = zs[l] * self.inv_scale;
        }
        if let Some(periodic) = &self.periods {
            // One reduction a point: every octave's period is a whole number of its cells, so
            // x in [0, period) is in [0, cells] at every octave.
            for x in &mut px {
                *x = reduce(*x, periodic.period, periodic.inv_period);
            }
            for (o, (&(freq, amp), &cells)) in self.octaves.iter().zip(&periodic.cells).enumerate() {
                for l in 0..L {
                    total[l] += amp * periodic.lane(o, cells, px[l] * freq, pz[l] * freq);
                }
            }
        } else {
            for &(freq, amp) in &self.octaves {
                for l in 0..L {
                    total[l] += amp * self.perlin.lane(px[l] * freq, pz[l] * freq);
                }
            }
        }
        for l in 0..L {
            out[l] = clamp01((total[l] + 1.0) * 0.5);
        }
    }

    /// Samples many points (positions in hex radii), batching them by `LANES`.
    pub fn sample_many(&self, points: &[[f64; 2]], out: &mut [f64]) {
        let mut xs = [0.0; LANES];
        let mut zs = [0.0; LANES];
        let mut res = [0.0; LANES];
        for (chunk, dst) in points.chunks(LANES).zip(out.chunks_mut(LANES)) {
            for (l, p) in chunk.iter().enumerate() {
                xs[l] = p[0];
                zs[l] = p[1];
            }
            self.sample_batch(&xs, &zs, &mut res);
            dst.copy_from_slice(&res[..dst.len()]);
        }
    }

    /// The same fBm computed with `noise::Perlin` itself, for comparison and benchmarks.
    #[must_use]
    pub fn sample_reference(&self, reference: &Perlin, x: f64, z: f64) -> f64 {
        let (x, z) = (x * self.inv_scale, z * self.inv_scale);
        let mut total = 0.0;
        for &(freq, amp) in &self.octaves {
            total += amp * reference.get([x * freq, z * freq]);
        }
        ((total + 1.0) * 0.5).clamp(0.0, 1.0)
    }
}

#[cfg(test)]
mod tests;
