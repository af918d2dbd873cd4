//! The whole globe's mesh: every fine point once, in the lattice's own order, so a point's vertex
//! is its place in it ([`Fine::dense`](super::super::fine::Fine::dense)) and nothing is looked
//! up. The points are finished row by row of the diamonds' frames, their normals summed round
//! each point as a chunk's mesh sums them (the same bits), and each tile's triangles written
//! straight into its own piece of the buffers: all on every core, no step on one thread.

use rayon::prelude::*;

use super::super::atlas::Spot;
use super::mesh::{Vertices, normalize_all, sum_faces};
use super::{GlobeMesh, GlobePoint, GlobeTerrain};
use crate::globe::GlobeTile;
use crate::heights::fbm::LANES;
use crate::mesh::MeshBuffers;

impl GlobeTerrain {
    /// The whole globe's mesh, measured from the globe's center.
    ///
    /// Its vertices are every point of the globe's fine lattice once: the north pole, each
    /// diamond's rows of points, the south pole. Its tiles are [`GlobeTerrain::chunks`]' tiles
    /// in turn, and its triangles each tile's in that order (a tile's triangles one after
    /// another, as in a chunk's mesh).
    #[must_use]
    pub fn generate_whole(&self) -> GlobeMesh {
        let fine = &self.fine;
        let rows = fine.rows();
        let lens: Vec<usize> = rows.iter().map(|&row| fine.row_len(row)).collect();
        let vertices: usize = lens.iter().sum();
        debug_assert_eq!(vertices as u64, self.vertex_count());
        let tiles: Vec<GlobeTile> = self.chunks().into_iter().flat_map(|chunk| self.chunk_tiles(chunk)).collect();
        let n = self.config.subdivisions() as usize;
        let triangles: Vec<usize> =
            tiles.iter().map(|&t| if self.grid.is_pentagon(t) { 5 } else { 6 } * n * n).collect();
        let corners: Vec<usize> = triangles.iter().map(|&t| 3 * t).collect();
        let colored = self.config.climate.enabled;
        let mut whole = GlobeMesh {
            origin: [0.0; 3],
            buffers: MeshBuffers {
                positions: vec![[0.0; 3]; vertices],
                normals: vec![[0.0; 3]; vertices],
                tile_kinds: vec![0; vertices],
                center_distances: vec![0.0; vertices],
                colors: vec![[0; 4]; if colored { vertices } else { 0 }],
                indices: vec![0; corners.iter().sum()],
                ..MeshBuffers::default()
            },
            points: vec![GlobePoint(0); vertices],
            heights: vec![0.0; vertices],
            tiles,
            triangle_tiles: vec![GlobeTile(0); triangles.iter().sum()],
        };

        // Every point finished, row by row.
        {
            let b = &mut whole.buffers;
            let colors: Vec<usize> = lens.iter().map(|&len| if colored { len } else { 0 }).collect();
            let mut positions = split(&mut b.positions, &lens).into_iter();
            let mut kinds = split(&mut b.tile_kinds, &lens).into_iter();
            let mut distances = split(&mut b.center_distances, &lens).into_iter();
            let mut colors = split(&mut b.colors, &colors).into_iter();
            let mut points = split(&mut whole.points, &lens).into_iter();
            let mut heights = split(&mut whole.heights, &lens).into_iter();
            let pieces: Vec<Vertices<'_>> = (0..rows.len())
                .map(|_| Vertices {
                    positions: positions.next().unwrap_or_default(),
                    kinds: kinds.next().unwrap_or_default(),
                    distances: distances.next().unwrap_or_default(),
                    colors: colors.next().unwrap_or_default(),
                    points: points.next().unwrap_or_default(),
                    heights: heights.next().unwrap_or_default(),
                })
                .collect();
            let subdivisions = self.config.subdivisions();
            pieces.into_par_iter().zip(&rows).for_each(|(mut out, &row)| {
                let points: Vec<_> = fine.row_points(row).collect();
                for (k, batch) in points.chunks(LANES).enumerate() {
                    for (l, f) in self.finish_batch(batch, &[None; LANES]).enumerate() {
                        let w = k * LANES + l;
                        out.set(w, &f, GlobePoint(fine.id(batch[l])), [0.0; 3], subdivisions);
                    }
                }
            });
        }

        // Each point's normal: the faces round it (between the vertices just written), going
        // round it as a chunk's mesh does. Well inside a diamond, the neighbors are the same
        // offsets away in the lattice's order from every point of a row.
        let starts: Vec<usize> =
            lens.iter().scan(0, |start, &len| Some(std::mem::replace(start, *start + len))).collect();
        let positions = &whole.buffers.positions;
        let normals = split(&mut whole.buffers.normals, &lens);
        normals.into_par_iter().zip(&rows).zip(&starts).for_each(|((normals, &row), &start)| {
            let steps = fine.row_steps(row);
            let sums: Vec<[f64; 3]> = fine
                .row_points(row)
                .enumerate()
                .map(|(w, p)| {
                    let v = start + w;
                    let mut around = [[0.0; 3]; 6];
                    match (&steps, p) {
                        (Some((steps, columns)), Spot::Diamond { j, .. }) if columns.contains(&j) => {
                            for (a, &s) in around.iter_mut().zip(steps) {
                                *a = positions[v.wrapping_add_signed(s)];
                            }
                            sum_faces(&around)
                        }
                        _ => {
                            let fan = fine.walk(p);
                            for (a, &q) in around.iter_mut().zip(fan.points()) {
                                *a = positions[fine.dense(q)];
                            }
                            sum_faces(&around[..fan.points().len()])
                        }
                    }
                })
                .collect();
            normalize_all(&sums, normals);
        });

        // Each tile's triangles, its points' vertices their places in the lattice.
        let (_, cell_triangles) = fine.template();
        let b = &mut whole.buffers;
        split(&mut b.indices, &corners)
            .into_par_iter()
            .zip(split(&mut whole.triangle_tiles, &triangles))
            .zip(&whole.tiles)
            .for_each_init(Vec::new, |local, ((indices, triangle_tiles), &t)| {
                let spot = self.spot(t);
                if let Some(hexagon) = fine.hexagon(spot) {
                    fine.hexagon_dense(hexagon, local);
                    for (out, triangle) in indices.chunks_exact_mut(3).zip(cell_triangles) {
                        out.copy_from_slice(&triangle.map(|k| local[usize::from(k)]));
                    }
                } else {
                    for (out, triangle) in indices.chunks_exact_mut(3).zip(fine.triangles(spot)) {
                        out.copy_from_slice(&triangle.map(|p| fine.dense(p) as u32));
                    }
                }
                triangle_tiles.fill(t);
            });
        whole
    }

    /// The 3D fBm at the direction of every point of the whole globe's mesh (each point once,
    /// batched and on all cores as meshing samples them), and nothing else: the noise floor of
    /// generating the globe. Returns the sum of the samples so the work cannot be elided.
    #[cfg(feature = "bench")]
    #[must_use]
    pub fn noise_floor(&self) -> f64 {
        self.fine
            .points()
            .par_chunks(LANES)
            .map(|batch| self.directions_and_fbm_lanes(batch)[..batch.len()].iter().map(|l| l.1).sum::<f64>())
            .sum()
    }
}

/// `buffer` cut into consecutive pieces of the given lengths (which sum to its length).
fn split<'a, T>(mut buffer: &'a mut [T], lens: &[usize]) -> Vec<&'a mut [T]> {
    lens.iter()
        .map(|&len| {
            let (piece, rest) = std::mem::take(&mut buffer).split_at_mut(len);
            buffer = rest;
            piece
        })
        .collect()
}
