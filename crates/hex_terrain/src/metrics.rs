//! Sharpness metrics (thesis eq. 4.1 and eq. 7.3).

use std::collections::HashMap;

use hexx::Hex;

use crate::mesh::{ChunkMesh, Diagnostics, MeshBuffers};

/// The three lattice lines through a vertex.
const LINES: [Hex; 3] = [Hex::new(1, 0), Hex::new(0, 1), Hex::new(-1, 1)];

/// Discrete curvature (eq. 4.1) at every vertex whose six lattice neighbors are in the mesh:
/// the largest `|2 a2 - a1 - a3|` over the three lattice lines through it, in world units.
/// `None` for vertices on the mesh's outline. `lattice` holds the lattice coordinate of each
/// vertex of `buffers` ([`Diagnostics::lattice`]).
#[must_use]
pub fn curvatures(lattice: &[Hex], buffers: &MeshBuffers) -> Vec<Option<f32>> {
    let index: HashMap<Hex, usize> = lattice.iter().enumerate().map(|(i, &p)| (p, i)).collect();
    let h = |p: Hex| index.get(&p).map(|&i| buffers.positions[i][1]);
    lattice
        .iter()
        .map(|&p| {
            let a2 = h(p)?;
            let mut worst = 0.0_f32;
            for d in LINES {
                let (a1, a3) = (h(p - d)?, h(p + d)?);
                worst = worst.max((2.0 * a2 - a1 - a3).abs());
            }
            Some(worst)
        })
        .collect()
}

/// Sharpness of a manipulated map against its raw counterpart (thesis table 6), in percent of
/// the maximum elevation.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Sharpness {
    /// Vertices of the mesh (`v`).
    pub vertices: usize,
    /// Vertices with a full neighborhood, where curvature is defined.
    pub measured: usize,
    /// Largest curvature of the raw map.
    pub raw_max: f32,
    /// Average curvature of the raw map (`s2`).
    pub raw_average: f32,
    /// Vertices moved by hex unity or edge/corner correction (`v1`).
    pub manipulated_vertices: usize,
    /// Largest curvature at manipulated vertices.
    pub manipulated_max: f32,
    /// Average curvature at manipulated vertices (`s1`).
    pub manipulated_average: f32,
    /// Eq. 7.3: `(v1 s1 + (v - v1) s2) / v`.
    pub weighted_mesh: f32,
    /// Average curvature over every measured vertex of the manipulated map, measured directly.
    pub mesh_average: f32,
}

impl Sharpness {
    /// Compares a manipulated mesh with the raw mesh of the same tiles (same config with
    /// manipulation off), both from [`crate::Terrain::generate`] with
    /// [`GenerateOptions::DIAGNOSTICS`](crate::GenerateOptions::DIAGNOSTICS).
    ///
    /// # Panics
    /// If a mesh was generated without diagnostics, or the two meshes do not cover the same
    /// lattice (programming errors, not user data).
    #[must_use]
    pub fn measure(raw: &ChunkMesh, manipulated: &ChunkMesh, max_elevation: f32) -> Self {
        fn diagnostics(m: &ChunkMesh) -> &Diagnostics {
            m.diagnostics.as_ref().expect("Sharpness::measure needs meshes generated with diagnostics")
        }
        let (raw_d, man_d) = (diagnostics(raw), diagnostics(manipulated));
        assert_eq!(raw_d.lattice, man_d.lattice, "meshes of different tiles");
        let scale = if max_elevation > 0.0 { 100.0 / max_elevation } else { 0.0 };
        let raw_c = curvatures(&raw_d.lattice, &raw.buffers);
        let man_c = curvatures(&man_d.lattice, &manipulated.buffers);
        let mut s = Self { vertices: raw_d.lattice.len(), ..Self::default() };
        let (mut raw_sum, mut man_sum, mut mesh_sum) = (0.0_f64, 0.0_f64, 0.0_f64);
        for i in 0..raw_c.len() {
            let (Some(r), Some(m)) = (raw_c[i], man_c[i]) else { continue };
            let (r, m) = (r * scale, m * scale);
            s.measured += 1;
            s.raw_max = s.raw_max.max(r);
            raw_sum += f64::from(r);
            mesh_sum += f64::from(m);
            if man_d.moved[i] {
                s.manipulated_vertices += 1;
                s.manipulated_max = s.manipulated_max.max(m);
                man_sum += f64::from(m);
            }
        }
        if s.measured > 0 {
            s.raw_average = (raw_sum / s.measured as f64) as f32;
            s.mesh_average = (mesh_sum / s.measured as f64) as f32;
        }
        if s.manipulated_vertices > 0 {
            s.manipulated_average = (man_sum / s.manipulated_vertices as f64) as f32;
        }
        let (v, v1) = (s.vertices as f32, s.manipulated_vertices as f32);
        if v > 0.0 {
            s.weighted_mesh = (v1 * s.manipulated_average + (v - v1) * s.raw_average) / v;
        }
        s
    }
}
