//! Solid (3D) fBm, for the globe: [`noise::Perlin`]'s 3D noise (the same permutation table,
//! hash, twelve gradients, fade curve and interpolation; a test holds it to `noise` itself)
//! computed branch-free over a batch of points, so that the loops vectorise.
//!
//! A batch runs either as plain loops compiled for the build's target, or as the same loops
//! compiled for AVX-512 (module `wide`) when the CPU has it; the compiler does the same IEEE
//! operations in the same order in both (Rust never fuses a multiply and an add), so each gives
//! the same bits for the same point.

use super::{LANES, TABLE, clamp01, lerp, max_x86, min_x86, permutation, quintic, split};
use crate::config::NoiseConfig;

/// `2 / sqrt(3)`: `noise`'s scale from the 3D gradient sum's range to `[-1, 1]`.
const SCALE_3D: f64 = 1.154_700_538_379_251_5;

/// `noise`'s gradient of each hash `h & 15` as one of the twelve cube edges `0..12`: hashes 12
/// to 15 repeat the edges 0, 1, 9 and 11. Edge `e` is `(u, v)` with `u` the point's `x` for
/// `e < 8` (else `y`) and `v` its `y` for `e < 4` (else `z`), `u` negated when `e & 1` and `v`
/// when `e & 2`: `noise`'s twelve sums, term for term.
const EDGES: [u8; 16] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 0, 1, 9, 11];

/// fBm over 3D Perlin noise, normalised to `[0, 1]` like the flat map's [`super::Fbm`]:
/// `(sum(amp_i * perlin(p * freq_i)) + 1) / 2`, the amplitudes summing to 1.
#[derive(Clone)]
pub(crate) struct SolidFbm {
    permutation: [u32; TABLE],
    /// The last step of the hash, `permutation[i] & 15`, as its edge ([`EDGES`]).
    edges: [u32; TABLE],
    /// `(frequency, amplitude)` per octave.
    octaves: Vec<(f64, f64)>,
    wide: bool,
}

impl std::fmt::Debug for SolidFbm {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SolidFbm").field("octaves", &self.octaves).field("wide", &self.wide).finish_non_exhaustive()
    }
}

impl SolidFbm {
    /// The fBm of `noise::Perlin::new(seed)`, its octaves' frequencies times `per_unit` (noise
    /// units per unit of the points it is given).
    pub(crate) fn new(seed: u32, config: &NoiseConfig, per_unit: f64) -> Self {
        let octaves =
            super::Fbm::new(seed, config).octaves().iter().map(|&(freq, amp)| (freq * per_unit, amp)).collect();
        let table = permutation(seed);
        Self {
            permutation: table.map(u32::from),
            edges: table.map(|p| u32::from(EDGES[usize::from(p & 15)])),
            octaves,
            wide: wide_supported(),
        }
    }

    /// The fBm at `LANES` points at once.
    pub(crate) fn sample_batch(&self, points: &[[f64; 3]; LANES], out: &mut [f64; LANES]) {
        #[cfg(target_arch = "x86_64")]
        if self.wide {
            return wide::sample_batch(self, points, out);
        }
        self.lanes(points, out);
    }

    /// The same fBm on the build's target alone, for the test that compares.
    #[cfg(test)]
    fn narrow(&self) -> Self {
        Self { wide: false, ..self.clone() }
    }

    #[inline(always)]
    fn lanes(&self, points: &[[f64; 3]; LANES], out: &mut [f64; LANES]) {
        let mut total = [0.0_f64; LANES];
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
    fn noise(&self, x: f64, y: f64, z: f64) -> f64 {
        let (cx, dx) = split(x);
        let (cy, dy) = split(y);
        let (cz, dz) = split(z);
        let p = |i: i64| i64::from(self.permutation[(i & 0xff) as usize]);
        // `noise`'s hash of a corner: P[P[P[x] ^ y] ^ z], each coordinate taken mod 256.
        let (x0, x1) = (p(cx), p(cx + 1));
        let (y0, y1) = (cy & 0xff, (cy + 1) & 0xff);
        let (z0, z1) = (cz & 0xff, (cz + 1) & 0xff);
        let (h00, h01, h10, h11) = (p(x0 ^ y0), p(x0 ^ y1), p(x1 ^ y0), p(x1 ^ y1));
        let gradient = |xy: i64, z: i64, px: f64, py: f64, pz: f64| {
            let e = self.edges[((xy ^ z) & 0xff) as usize];
            let u = if e < 8 { px } else { py };
            let v = if e < 4 { py } else { pz };
            let u = if e & 1 == 1 { -u } else { u };
            let v = if e & 2 == 2 { -v } else { v };
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

/// Whether the CPU runs the batch compiled for AVX-512.
fn wide_supported() -> bool {
    #[cfg(target_arch = "x86_64")]
    return wide::supported();
    #[cfg(not(target_arch = "x86_64"))]
    false
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

    pub(super) fn sample_batch(fbm: &SolidFbm, points: &[[f64; 3]; LANES], out: &mut [f64; LANES]) {
        debug_assert!(supported());
        // SAFETY: `fbm.wide` is set only when `supported` found these features on this CPU.
        unsafe { batch(fbm, points, out) }
    }

    #[target_feature(enable = "avx512f,avx512dq,avx512vl")]
    fn batch(fbm: &SolidFbm, points: &[[f64; 3]; LANES], out: &mut [f64; LANES]) {
        fbm.lanes(points, out);
    }
}

#[cfg(test)]
mod tests {
    use noise::{NoiseFn, Perlin};

    use super::*;

    /// The fBm computed with `noise::Perlin` itself.
    fn reference(seed: u32, config: &NoiseConfig, p: [f64; 3]) -> f64 {
        let perlin = Perlin::new(seed);
        let fbm = super::super::Fbm::new(seed, config);
        let sum: f64 = fbm.octaves().iter().map(|&(f, a)| a * perlin.get([p[0] * f, p[1] * f, p[2] * f])).sum();
        ((sum + 1.0) * 0.5).clamp(0.0, 1.0)
    }

    /// Batches equal `noise`'s own noise (term for term, so to the bit), on the build's
    /// target and on AVX-512 alike, for several seeds, over points spread across cells,
    /// negative coordinates and exact integers included.
    #[test]
    fn solid_fbm_is_noises_perlin_on_every_kernel() {
        let config = NoiseConfig { octaves: 6, persistence: 0.5, lacunarity: 2.0, scale: 40.0 };
        for seed in [0, 1, 3, 255, 2024, u32::MAX] {
            let fbm = SolidFbm::new(seed, &config, 1.0);
            let mut state = u64::from(seed) | 1;
            let mut next = move || {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                (state % 20_000) as f64 / 37.0 - 270.0
            };
            for batch in 0..200 {
                let mut points: [[f64; 3]; LANES] = std::array::from_fn(|_| [next(), next(), next()]);
                if batch == 0 {
                    points[0] = [0.0, 0.0, 0.0];
                    points[1] = [-3.0, 5.0, -256.0];
                    points[2] = [255.5, -0.25, 1e6];
                }
                let (mut wide, mut narrow) = ([0.0; LANES], [0.0; LANES]);
                fbm.sample_batch(&points, &mut wide);
                fbm.narrow().sample_batch(&points, &mut narrow);
                for l in 0..LANES {
                    assert_eq!(wide[l].to_bits(), narrow[l].to_bits(), "seed {seed} at {:?}", points[l]);
                    let expected = reference(seed, &config, points[l]);
                    assert_eq!(narrow[l].to_bits(), expected.to_bits(), "seed {seed} at {:?}", points[l]);
                }
            }
        }
    }
}
