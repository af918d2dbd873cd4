//! Perlin fBm height source (thesis section 5.1, Algorithm 2).
//!
//! [`FastPerlin`] computes exactly the same numbers as [`noise::Perlin`]'s 2D noise (same
//! permutation table, same gradients, same floating-point operations in the same order; a test
//! compares them bit for bit) without its generic vector plumbing and with the gradient index of
//! each of the 256x256 lattice cells read from one flat table.

use noise::{NoiseFn, Perlin};

use crate::config::NoiseConfig;

const TABLE: usize = 256;
const SCALE_2D: f64 = 2.0 / std::f64::consts::SQRT_2;

/// 2D Perlin noise equal to `noise::Perlin::new(seed)` on `[f64; 2]` points.
#[derive(Clone)]
pub struct FastPerlin {
    /// Gradient index (0..4) of every cell corner `(x & 255, y & 255)`, row-major in `x`.
    gradients: Box<[u8]>,
}

impl std::fmt::Debug for FastPerlin {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("FastPerlin { .. }")
    }
}

impl FastPerlin {
    /// Builds the gradient table of `noise::Perlin::new(seed)`.
    ///
    /// `noise` keeps its permutation table private, so the table is read back from the noise
    /// itself: just past a lattice corner the noise equals the corner's gradient term alone
    /// (the fade curve is ~1e-8 there), and the four gradients give four distinct values.
    #[must_use]
    pub fn new(seed: u32) -> Self {
        let reference = Perlin::new(seed);
        let (dx, dy) = (1.0 / 1024.0, 1.0 / 512.0);
        // Gradient terms times the scale: (dx + dy), (-dx + dy), (dx - dy), (-dx - dy).
        let split = (dx + dy + (dy - dx)) * 0.5 * SCALE_2D;
        let mut gradients = vec![0_u8; TABLE * TABLE].into_boxed_slice();
        for x in 0..TABLE {
            for y in 0..TABLE {
                let v = reference.get([x as f64 + dx, y as f64 + dy]);
                gradients[x * TABLE + y] = if v > split {
                    0
                } else if v > 0.0 {
                    1
                } else if v > -split {
                    2
                } else {
                    3
                };
            }
        }
        Self { gradients }
    }

    /// Noise at `(x, y)`, in `[-1, 1]`.
    #[must_use]
    #[inline]
    pub fn get(&self, x: f64, y: f64) -> f64 {
        // `noise` floors with "truncate, minus one at or below zero", so an exact integer at or
        // below zero lands in the cell below it; reproduce that to stay bit-identical.
        let cx = if x <= 0.0 { x as isize - 1 } else { x as isize };
        let cy = if y <= 0.0 { y as isize - 1 } else { y as isize };
        let dx = x - cx as f64;
        let dy = y - cy as f64;
        let (ix0, iy0) = ((cx & 0xff) as usize, (cy & 0xff) as usize);
        let (ix1, iy1) = ((ix0 + 1) & 0xff, (iy0 + 1) & 0xff);
        let g = &self.gradients;
        let grad = |index: usize, px: f64, py: f64| match g[index] & 3 {
            0 => px + py,
            1 => -px + py,
            2 => px - py,
            _ => -px - py,
        };
        let g00 = grad(ix0 * TABLE + iy0, dx, dy);
        let g10 = grad(ix1 * TABLE + iy0, dx - 1.0, dy);
        let g01 = grad(ix0 * TABLE + iy1, dx, dy - 1.0);
        let g11 = grad(ix1 * TABLE + iy1, dx - 1.0, dy - 1.0);
        let sx = quintic(dx);
        let sy = quintic(dy);
        let result = lerp(lerp(g00, g01, sy), lerp(g10, g11, sy), sx) * SCALE_2D;
        result.clamp(-1.0, 1.0)
    }
}

#[inline(always)]
fn quintic(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    x * x * x * (x * (x * 6.0 - 15.0) + 10.0)
}

#[inline(always)]
fn lerp(a: f64, b: f64, t: f64) -> f64 {
    b * t + a * (1.0 - t)
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
        Self { perlin: FastPerlin::new(seed), octaves, inv_scale: 4.0 / config.scale }
    }

    /// Normalised height at a position measured in hex radii.
    #[must_use]
    #[inline]
    pub fn sample(&self, x: f64, z: f64) -> f64 {
        let (x, z) = (x * self.inv_scale, z * self.inv_scale);
        let mut total = 0.0;
        for &(freq, amp) in &self.octaves {
            total += amp * self.perlin.get(x * freq, z * freq);
        }
        ((total + 1.0) * 0.5).clamp(0.0, 1.0)
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
