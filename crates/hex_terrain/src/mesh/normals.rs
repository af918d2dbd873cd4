//! Smooth vertex normals from the height grid: each vertex's normal is the area-weighted sum of
//! the six lattice triangles around it, computed a vector of vertices at a time (sixteen on
//! AVX-512, eight elsewhere: module `lanes`).

use super::grid::{AROUND, Points};
use super::job::Job;
use super::lanes;
use super::parallel::BATCH;
use crate::heights::Kernel;

/// Coefficients of the smooth normal: the sum of the six lattice triangles' face normals
/// (area-weighted) around a vertex is `(Σ dₖ·x[k], y, Σ dₖ·z[k])`, with `dₖ` the height of the
/// k-th neighbor minus the vertex's, because every lattice offset is flat.
pub(super) struct NormalCoefficients {
    x: [f32; 6],
    y: f32,
    z: [f32; 6],
}

impl NormalCoefficients {
    /// Coefficients for the world `(x, z)` offsets of the six [`AROUND`] steps.
    pub fn new(around: &[[f32; 2]; 6]) -> Self {
        // Σ (e_{k+1} × e_k) with e_k = (ax_k, d_k, az_k), collected by d_k.
        let (mut x, mut z, mut y) = ([0.0_f32; 6], [0.0_f32; 6], 0.0_f32);
        for k in 0..6 {
            let (prev, next) = ((k + 5) % 6, (k + 1) % 6);
            x[k] = around[prev][1] - around[next][1];
            z[k] = around[next][0] - around[prev][0];
            y += around[next][1] * around[k][0] - around[next][0] * around[k][1];
        }
        Self { x, y, z }
    }

    /// Unit normal at one vertex of height `h0` whose k-th neighbor has height `height(k)`.
    /// [`NormalCoefficients::lanes`] does the same operations in the same order in every lane,
    /// so a vertex gets these bits in any lane, chunk and instruction set.
    #[inline(always)]
    pub fn normal(&self, h0: f32, height: impl Fn(usize) -> f32) -> [f32; 3] {
        let (mut nx, mut nz) = (0.0_f32, 0.0_f32);
        for (k, (&x, &z)) in self.x.iter().zip(&self.z).enumerate() {
            let d = height(k) - h0;
            nx += d * x;
            nz += d * z;
        }
        let len = (nx * nx + self.y * self.y + nz * nz).sqrt();
        if len > 0.0 && len.is_finite() { [nx / len, self.y / len, nz / len] } else { [0.0, 1.0, 0.0] }
    }

    /// [`NormalCoefficients::normal`] of `L` vertices in consecutive slots from `slot` (their
    /// neighbors `around[k]` slots away), lane by lane so that it vectorises.
    #[inline(always)]
    fn lanes<const L: usize>(&self, heights: &[f32], slot: usize, around: [isize; 6], out: &mut [[f32; 3]; L]) {
        let h0: &[f32; L] = heights[slot..slot + L].try_into().expect("L heights");
        let (mut nx, mut nz) = ([0.0_f32; L], [0.0_f32; L]);
        for ((&step, &x), &z) in around.iter().zip(&self.x).zip(&self.z) {
            let s = slot.wrapping_add_signed(step);
            let a: &[f32; L] = heights[s..s + L].try_into().expect("L heights");
            for l in 0..L {
                let d = a[l] - h0[l];
                nx[l] += d * x;
                nz[l] += d * z;
            }
        }
        let y2 = self.y * self.y;
        for l in 0..L {
            let len = (nx[l] * nx[l] + y2 + nz[l] * nz[l]).sqrt();
            out[l] =
                if len > 0.0 && len.is_finite() { [nx[l] / len, self.y / len, nz[l] / len] } else { [0.0, 1.0, 0.0] };
        }
    }
}

/// What the normals of a batch read: the points, their heights by slot and the coefficients.
pub(super) struct Batch<'a> {
    points: &'a Points,
    heights: &'a [f32],
    coefficients: &'a NormalCoefficients,
}

impl Batch<'_> {
    /// The normals of points `first..first + out.len()`: `L` at a time where `L` points sit in
    /// consecutive slots of one row (nearly everywhere), else one by one.
    #[inline(always)]
    fn normals<const L: usize>(&self, first: usize, out: &mut [[f32; 3]]) {
        let (points, heights) = (self.points, self.heights);
        let width = points.grid.shape.width;
        let mut groups = out.chunks_exact_mut(L);
        let mut i = first;
        for group in &mut groups {
            let slot = points.slot_of(i);
            let around = points.grid.around(points.lattice[i]);
            let group: &mut [[f32; 3]; L] = group.try_into().expect("L normals");
            if points.slot_of(i + L - 1) == slot + L - 1 && slot / width == (slot + L - 1) / width {
                self.coefficients.lanes(heights, slot, around, group);
            } else {
                for (l, normal) in group.iter_mut().enumerate() {
                    *normal = self.single(i + l);
                }
            }
            i += L;
        }
        for (l, normal) in groups.into_remainder().iter_mut().enumerate() {
            *normal = self.single(i + l);
        }
    }

    /// [`Batch::normals`] compiled for `kernel`, as many lanes as its vectors hold.
    pub(super) fn normals_on(&self, kernel: Kernel, first: usize, out: &mut [[f32; 3]]) {
        if lanes::f32_lanes(kernel) == 16 {
            lanes::run(
                kernel,
                #[inline(always)]
                || self.normals::<16>(first, out),
            );
        } else {
            lanes::run(
                kernel,
                #[inline(always)]
                || self.normals::<8>(first, out),
            );
        }
    }

    /// The normal of point `i`.
    #[inline(always)]
    fn single(&self, i: usize) -> [f32; 3] {
        let slot = self.points.slot_of(i);
        let around = self.points.grid.around(self.points.lattice[i]);
        self.coefficients.normal(self.heights[slot], |k| self.heights[slot.wrapping_add_signed(around[k])])
    }
}

impl Job<'_> {
    /// The normals pass: every neighbor of an owned point is an owned or a halo point, so its
    /// height is in the grid. A vector of points in consecutive slots of one row reads a vector
    /// of consecutive heights per direction.
    pub(super) fn normals_pass(&self, points: &Points, heights: &[f32], normals: &mut [[f32; 3]]) {
        let (step_a, step_b) = self.lattice.steps();
        let around: [[f32; 2]; 6] = AROUND.map(|d| {
            let (i, j) = (f64::from(d.x), f64::from(d.y));
            [(i * step_a[0] + j * step_b[0]) as f32, (i * step_a[1] + j * step_b[1]) as f32]
        });
        let coefficients = NormalCoefficients::new(&around);
        let batch = Batch { points, heights, coefficients: &coefficients };
        self.split.for_each_chunk(normals, BATCH, 1, |c, normals| batch.normals_on(self.kernel, c * BATCH, normals));
    }
}

#[cfg(test)]
mod tests;
