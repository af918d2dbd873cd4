//! Solid (3D) fBm, for the globe: [`noise::Perlin`]'s 3D noise (the same permutation table,
//! hash, twelve gradients, fade curve and interpolation) in f32, computed branch-free over a
//! batch of points, so that the loops vectorise.
//!
//! A batch runs on the fastest of three kernels the CPU has: plain loops compiled for the
//! build's target, the same loops compiled for AVX-512 (module `wide`), or the hand-written
//! AVX-512 VBMI kernel (`solid_vbmi.rs`, the hash looked up in registers). Each does the same
//! IEEE operations in the same order (Rust never fuses a multiply and an add), so each gives
//! the same bits for the same point; a test compares them.

use super::{LANES, SCALE_3D, SOLID_LIMIT, TABLE, clamp01, lerp, max_x86, min_x86, permutation, quintic};
use crate::config::NoiseConfig;

/// `noise`'s gradient of each hash `h & 15` as one of the twelve cube edges: hashes 12 to 15
/// repeat the edges 0, 1, 9 and 11. Edge `e`'s sum is `u + v`, `u` the point's `x` for `e < 8`
/// (else `y`), `v` its `y` for `e < 4` (else `z`), `u` negated when `e & 1` and `v` when
/// `e & 2`; stored as its code ([`code`]).
const EDGES: [u8; 16] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 0, 1, 9, 11];

/// An edge's code: bit 0 negates `u`, bit 1 negates `v`, bit 2 takes `u` from `y`, bit 3 takes
/// `v` from `z`.
const fn code(edge: u8) -> u8 {
    (edge & 3) | ((edge >= 8) as u8) << 2 | ((edge >= 4) as u8) << 3
}

/// The noise cell of a coordinate and the offset in it, floored as `noise` floors ("truncate,
/// minus one at or below zero": an exact integer at or below zero lands in the cell below).
#[inline(always)]
fn split(v: f32) -> (i32, f32) {
    let v = max_x86(min_x86(v, SOLID_LIMIT), -SOLID_LIMIT);
    let c = if v <= 0.0 { v as i32 - 1 } else { v as i32 };
    (c, clamp01(v - c as f32))
}

/// fBm over 3D Perlin noise, normalised to `[0, 1]` like the flat map's [`super::Fbm`]:
/// `(sum(amp_i * perlin(p * freq_i)) + 1) / 2`, the amplitudes summing to 1.
///
/// `noise::Perlin`'s 3D noise (its permutation table, hash, twelve gradients, fade curve and
/// interpolation) computed in f32, within `1e-5` of `noise`'s f64 at a globe's points (a test
/// holds it there): a 3D octave costs twice a 2D one, and f32 lanes halve it again.
#[derive(Clone)]
pub(crate) struct SolidFbm {
    permutation: [u32; TABLE],
    /// The last step of the hash, `permutation[i] & 15`, as its edge's [`code`].
    codes: [u32; TABLE],
    /// The same two tables as bytes, for the VBMI kernel.
    permutation_bytes: [u8; TABLE],
    code_bytes: [u8; TABLE],
    /// `(frequency, amplitude)` per octave.
    octaves: Vec<(f32, f32)>,
    kernel: SolidKernel,
}

/// What a [`SolidFbm`] batch runs on: only ever a kernel this CPU has.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum SolidKernel {
    Portable,
    /// The portable loops compiled for AVX-512 (module `wide`).
    Avx512,
    /// `solid_vbmi.rs`.
    Vbmi,
}

impl SolidKernel {
    /// Every kernel this CPU has, the fastest first.
    fn supported() -> Vec<Self> {
        let mut out = Vec::new();
        #[cfg(target_arch = "x86_64")]
        {
            if super::solid_vbmi::supported() {
                out.push(Self::Vbmi);
            }
            if wide::supported() {
                out.push(Self::Avx512);
            }
        }
        out.push(Self::Portable);
        out
    }
}

impl std::fmt::Debug for SolidFbm {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SolidFbm").field("octaves", &self.octaves).field("kernel", &self.kernel).finish_non_exhaustive()
    }
}

impl SolidFbm {
    /// The fBm of `noise::Perlin::new(seed)`, its octaves' frequencies times `per_unit` (noise
    /// units per unit of the points it is given).
    pub(crate) fn new(seed: u32, config: &NoiseConfig, per_unit: f64) -> Self {
        let octaves = super::Fbm::new(seed, config)
            .octaves()
            .iter()
            .map(|&(freq, amp)| ((freq * per_unit) as f32, amp as f32))
            .collect();
        let table = permutation(seed);
        let codes = table.map(|p| code(EDGES[usize::from(p & 15)]));
        Self {
            permutation: table.map(u32::from),
            codes: codes.map(u32::from),
            permutation_bytes: table,
            code_bytes: codes,
            octaves,
            kernel: SolidKernel::supported()[0],
        }
    }

    /// The fBm at `LANES` points at once.
    pub(crate) fn sample_batch(&self, points: &[[f64; 3]; LANES], out: &mut [f64; LANES]) {
        let at = points.map(|p| p.map(|c| c as f32));
        let mut sum = [0.0; LANES];
        self.batch(&at, &mut sum);
        for (o, s) in out.iter_mut().zip(sum) {
            *o = f64::from(s);
        }
    }

    fn batch(&self, points: &[[f32; 3]; LANES], out: &mut [f32; LANES]) {
        match self.kernel {
            #[cfg(target_arch = "x86_64")]
            SolidKernel::Vbmi => {
                super::solid_vbmi::batch(&self.permutation_bytes, &self.code_bytes, &self.octaves, points, out);
            }
            #[cfg(target_arch = "x86_64")]
            SolidKernel::Avx512 => wide::batch(self, points, out),
            _ => self.lanes(points, out),
        }
    }

    /// The same fBm on another kernel this CPU has, for the test that compares.
    #[cfg(test)]
    fn on(&self, kernel: SolidKernel) -> Self {
        Self { kernel, ..self.clone() }
    }

    #[inline(always)]
    fn lanes(&self, points: &[[f32; 3]; LANES], out: &mut [f32; LANES]) {
        let mut total = [0.0_f32; LANES];
        for &(freq, amp) in &self.octaves {
            for l in 0..LANES {
                let [x, y, z] = points[l];
                total[l] += amp * self.noise(x * freq, y * freq, z * freq);
            }
        }
        for l in 0..LANES {
            out[l] = clamp01((total[l] + 1.0) * 0.5);
        }
    }

    /// `noise::Perlin`'s 3D noise at one point, branch-free.
    #[inline(always)]
    fn noise(&self, x: f32, y: f32, z: f32) -> f32 {
        let (cx, dx) = split(x);
        let (cy, dy) = split(y);
        let (cz, dz) = split(z);
        let p = |i: i32| self.permutation[(i & 0xff) as usize] as i32;
        // `noise`'s hash of a corner: P[P[P[x] ^ y] ^ z], each coordinate taken mod 256.
        let (x0, x1) = (p(cx), p(cx + 1));
        let (y0, y1) = (cy & 0xff, (cy + 1) & 0xff);
        let (z0, z1) = (cz & 0xff, (cz + 1) & 0xff);
        let (h00, h01, h10, h11) = (p(x0 ^ y0), p(x0 ^ y1), p(x1 ^ y0), p(x1 ^ y1));
        let gradient = |xy: i32, z: i32, px: f32, py: f32, pz: f32| {
            let c = self.codes[((xy ^ z) & 0xff) as usize];
            let u = if c & 4 == 0 { px } else { py };
            let v = if c & 8 == 0 { py } else { pz };
            let u = if c & 1 == 0 { u } else { -u };
            let v = if c & 2 == 0 { v } else { -v };
            u + v
        };
        let g000 = gradient(h00, z0, dx, dy, dz);
        let g100 = gradient(h10, z0, dx - 1.0, dy, dz);
        let g010 = gradient(h01, z0, dx, dy - 1.0, dz);
        let g110 = gradient(h11, z0, dx - 1.0, dy - 1.0, dz);
        let g001 = gradient(h00, z1, dx, dy, dz - 1.0);
        let g101 = gradient(h10, z1, dx - 1.0, dy, dz - 1.0);
        let g011 = gradient(h01, z1, dx, dy - 1.0, dz - 1.0);
        let g111 = gradient(h11, z1, dx - 1.0, dy - 1.0, dz - 1.0);
        let (sx, sy, sz) = (quintic(dx), quintic(dy), quintic(dz));
        let result = lerp(
            lerp(lerp(g000, g001, sz), lerp(g010, g011, sz), sy),
            lerp(lerp(g100, g101, sz), lerp(g110, g111, sz), sy),
            sx,
        ) * SCALE_3D;
        max_x86(min_x86(result, 1.0), -1.0)
    }
}

/// The batch compiled for AVX-512.
///
/// Why `unsafe` here (the workspace denies it everywhere else): a function compiled for
/// features beyond the build's target is unsafe to call; the one call is guarded by the run-time
/// check that the CPU has the features (`supported`).
#[cfg(target_arch = "x86_64")]
#[allow(unsafe_code)]
mod wide {
    use super::{LANES, SolidFbm};

    /// Whether this CPU has AVX-512F, DQ (f64 to i64 conversions in vectors) and VL.
    pub(super) fn supported() -> bool {
        std::arch::is_x86_feature_detected!("avx512f")
            && std::arch::is_x86_feature_detected!("avx512dq")
            && std::arch::is_x86_feature_detected!("avx512vl")
    }

    pub(super) fn batch(fbm: &SolidFbm, points: &[[f32; 3]; LANES], out: &mut [f32; LANES]) {
        debug_assert!(supported());
        // SAFETY: the fbm picks this kernel only when `supported` found these features here.
        unsafe { lanes(fbm, points, out) }
    }

    #[target_feature(enable = "avx512f,avx512dq,avx512vl")]
    fn lanes(fbm: &SolidFbm, points: &[[f32; 3]; LANES], out: &mut [f32; LANES]) {
        fbm.lanes(points, out);
    }
}

#[cfg(test)]
mod tests {
    use noise::{NoiseFn, Perlin};

    use super::*;

    /// The fBm computed with `noise::Perlin` itself, in f64.
    fn reference(perlin: &Perlin, octaves: &[(f64, f64)], p: [f64; 3]) -> f64 {
        let sum: f64 = octaves.iter().map(|&(f, a)| a * perlin.get([p[0] * f, p[1] * f, p[2] * f])).sum();
        ((sum + 1.0) * 0.5).clamp(0.0, 1.0)
    }

    /// A little xorshift stream of numbers in `[lo, hi)`.
    fn stream(seed: u64, lo: f64, hi: f64) -> impl FnMut() -> f64 {
        let mut state = seed | 1;
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            lo + (state >> 11) as f64 / (1u64 << 53) as f64 * (hi - lo)
        }
    }

    /// Every kernel gives the same bits, for several seeds, over points spread across cells,
    /// negative coordinates, exact integers, coordinates beyond f32's fraction, infinities and
    /// NaN included.
    #[test]
    fn solid_fbm_is_the_same_bits_on_every_kernel() {
        let config = NoiseConfig { octaves: 6, persistence: 0.5, lacunarity: 2.0, scale: 40.0 };
        for seed in [0, 1, 3, 255, 2024, u32::MAX] {
            let fbm = SolidFbm::new(seed, &config, 1.0);
            let mut next = stream(u64::from(seed), -270.0, 270.0);
            for batch in 0..200 {
                let mut points: [[f64; 3]; LANES] = std::array::from_fn(|_| [next(), next(), next()]);
                if batch == 0 {
                    points[0] = [0.0, 0.0, 0.0];
                    points[1] = [-3.0, 5.0, -256.0];
                    points[2] = [255.5, -0.25, 1e6];
                    points[3] = [f64::INFINITY, f64::NEG_INFINITY, f64::NAN];
                    points[4] = [-1e9, 3e7, -0.0];
                }
                let mut portable = [0.0; LANES];
                fbm.on(SolidKernel::Portable).sample_batch(&points, &mut portable);
                for kernel in SolidKernel::supported() {
                    let mut got = [0.0; LANES];
                    fbm.on(kernel).sample_batch(&points, &mut got);
                    for l in 0..LANES {
                        assert_eq!(
                            got[l].to_bits(),
                            portable[l].to_bits(),
                            "{kernel:?}, seed {seed} at {:?}",
                            points[l]
                        );
                    }
                }
                for l in 0..LANES {
                    assert!((0.0..=1.0).contains(&portable[l]), "seed {seed} at {:?}: {}", points[l], portable[l]);
                }
            }
        }
    }

    /// At a globe's points (on spheres from the smallest globe's radius to beyond the largest's,
    /// with the globe's noise scale and 8 octaves), the f32 fBm is within `1e-5` of `noise`'s
    /// own f64 Perlin summed the same way: f32 keeps 24 bits of a coordinate below 2^11, so an
    /// octave's offset in its cell is off by at most 2^-13 and its noise by a few times that,
    /// weighted by the octave's amplitude.
    #[test]
    fn solid_fbm_is_noises_perlin_within_1e_5_at_a_globes_points() {
        let config = NoiseConfig { octaves: 8, persistence: 0.5, lacunarity: 2.0, scale: 120.0 };
        let mut worst = 0.0_f64;
        for seed in [0, 3, 2024, u32::MAX] {
            let fbm = SolidFbm::new(seed, &config, 4.0 / config.scale);
            let (perlin, octaves) = (Perlin::new(seed), super::super::Fbm::new(seed, &config).octaves().to_vec());
            let mut next = stream(u64::from(seed) + 7, -1.0, 1.0);
            for radius in [1.0, 8.0, 30.0, 120.0, 400.0] {
                for _ in 0..2_000 {
                    let points: [[f64; 3]; LANES] = std::array::from_fn(|_| {
                        let d = [next(), next(), next()];
                        let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-9);
                        d.map(|c| c / len * radius)
                    });
                    let mut got = [0.0; LANES];
                    fbm.sample_batch(&points, &mut got);
                    for l in 0..LANES {
                        let expected = reference(&perlin, &octaves, points[l].map(|c| c * 4.0 / config.scale));
                        worst = worst.max((got[l] - expected).abs());
                    }
                }
            }
        }
        assert!(worst < 1e-5, "the f32 fBm strays {worst:e} from noise's");
        assert!(worst > 0.0, "f32 and f64 never differ: the comparison compares nothing");
    }
}
