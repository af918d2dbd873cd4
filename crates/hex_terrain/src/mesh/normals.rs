//! Smooth vertex normals from the height grid: each vertex's normal is the area-weighted sum of
//! the six lattice triangles around it, computed eight vertices at a time.

use super::grid::{AROUND, Points};
use super::job::Job;
use super::parallel::BATCH;

/// Vertices whose normals are computed together.
pub(super) const NORMAL_LANES: usize = 8;

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

    /// Unit normal at a vertex of height `h0`; the same inputs give the same bits in every chunk.
    #[cfg(test)]
    pub fn normal(&self, h0: f32, height: impl Fn(usize) -> f32) -> [f32; 3] {
        let mut around = [[0.0; NORMAL_LANES]; 6];
        for (k, a) in around.iter_mut().enumerate() {
            a[0] = height(k);
        }
        let mut out = [[0.0; 3]; NORMAL_LANES];
        self.normals(&[h0; NORMAL_LANES], &around, &mut out);
        out[0]
    }

    /// [`NormalCoefficients::normal`] of [`NORMAL_LANES`] vertices at once (heights `h0`, the
    /// k-th neighbors' heights in `around[k]`), lane by lane so that it vectorises; every lane
    /// does the same operations in the same order, so a vertex gets the same bits in any lane.
    #[inline(always)]
    fn normals(&self, h0: &[f32; NORMAL_LANES], around: &[[f32; NORMAL_LANES]; 6], out: &mut [[f32; 3]; NORMAL_LANES]) {
        let (mut nx, mut nz) = ([0.0_f32; NORMAL_LANES], [0.0_f32; NORMAL_LANES]);
        for ((heights, x), z) in around.iter().zip(self.x).zip(self.z) {
            for l in 0..NORMAL_LANES {
                let d = heights[l] - h0[l];
                nx[l] += d * x;
                nz[l] += d * z;
            }
        }
        let y2 = self.y * self.y;
        for l in 0..NORMAL_LANES {
            let len = (nx[l] * nx[l] + y2 + nz[l] * nz[l]).sqrt();
            out[l] =
                if len > 0.0 && len.is_finite() { [nx[l] / len, self.y / len, nz[l] / len] } else { [0.0, 1.0, 0.0] };
        }
    }
}

impl Job<'_> {
    /// The normals pass: every neighbor of an owned point is an owned or a halo point, so its
    /// height is in the grid. Eight points in consecutive slots of one row read eight
    /// consecutive heights per direction.
    pub(super) fn normals_pass(&self, points: &Points, heights: &[f32], normals: &mut [[f32; 3]]) {
        let (step_a, step_b) = self.lattice.steps();
        let around: [[f32; 2]; 6] = AROUND.map(|d| {
            let (i, j) = (f64::from(d.x), f64::from(d.y));
            [(i * step_a[0] + j * step_b[0]) as f32, (i * step_a[1] + j * step_b[1]) as f32]
        });
        let coefficients = NormalCoefficients::new(&around);
        let (grid, width) = (&points.grid, points.grid.shape.width);
        self.split.for_each_chunk(normals, BATCH, 1, |c, normals| {
            let mut h0 = [0.0; NORMAL_LANES];
            let mut around = [[0.0; NORMAL_LANES]; 6];
            let mut out = [[0.0; 3]; NORMAL_LANES];
            for (g, normals) in normals.chunks_mut(NORMAL_LANES).enumerate() {
                let first = c * BATCH + g * NORMAL_LANES;
                let slot = points.slot_of(first);
                let last = first + NORMAL_LANES - 1;
                if normals.len() == NORMAL_LANES
                    && points.slot_of(last) == slot + NORMAL_LANES - 1
                    && slot / width == (slot + NORMAL_LANES - 1) / width
                {
                    h0.copy_from_slice(&heights[slot..slot + NORMAL_LANES]);
                    for (a, d) in around.iter_mut().zip(grid.around(points.lattice[first])) {
                        let s = slot.wrapping_add_signed(d);
                        a.copy_from_slice(&heights[s..s + NORMAL_LANES]);
                    }
                } else {
                    for l in 0..normals.len() {
                        let slot = points.slot_of(first + l);
                        h0[l] = heights[slot];
                        for (a, d) in around.iter_mut().zip(grid.around(points.lattice[first + l])) {
                            a[l] = heights[slot.wrapping_add_signed(d)];
                        }
                    }
                }
                coefficients.normals(&h0, &around, &mut out);
                normals.copy_from_slice(&out[..normals.len()]);
            }
        });
    }
}
