//! The whole globe's mesh: its chunks laid out in parallel, each point given to the first chunk
//! holding it, then each chunk finishing its points and writing those it holds first, by work
//! that runs on every core (no step walks all the points on one thread).

use std::sync::atomic::{AtomicU32, Ordering};

use rayon::prelude::*;

use super::mesh::{Layout, Vertices};
use super::{GlobeMesh, GlobePoint, GlobeTerrain};
use crate::globe::GlobeTile;
use crate::mesh::MeshBuffers;

impl GlobeTerrain {
    /// The whole globe's mesh, measured from the globe's center.
    ///
    /// Its vertices are each chunk's points not in an earlier chunk (in [`GlobeTerrain::chunks`]'
    /// order), in the order the chunk meets them; its triangles each chunk's in turn.
    #[must_use]
    pub fn generate_whole(&self) -> GlobeMesh {
        // Every chunk's points and triangles, before any point is finished.
        let layouts: Vec<Layout> =
            self.chunks().into_par_iter().map(|chunk| self.layout(self.chunk_tiles(chunk))).collect();
        // Each of a chunk's points' place among all the globe's points.
        let denses: Vec<Vec<u32>> = layouts
            .par_iter()
            .map(|layout| (0..layout.len()).map(|v| self.fine.dense(layout.point(v)) as u32).collect())
            .collect();
        // Each point's first chunk, then (once every chunk has read it) its whole vertex.
        let slot: Vec<AtomicU32> = (0..self.fine.point_count()).map(|_| AtomicU32::new(u32::MAX)).collect();
        denses.par_iter().enumerate().for_each(|(c, dense)| {
            for &k in dense {
                slot[k as usize].fetch_min(c as u32, Ordering::Relaxed);
            }
        });
        let first: Vec<Vec<u32>> = denses
            .par_iter()
            .enumerate()
            .map(|(c, dense)| {
                (0..dense.len() as u32)
                    .filter(|&v| slot[dense[v as usize] as usize].load(Ordering::Relaxed) == c as u32)
                    .collect()
            })
            .collect();
        let mut starts = Vec::with_capacity(layouts.len());
        let mut vertices = 0;
        for owned in &first {
            starts.push(vertices);
            vertices += owned.len();
        }
        debug_assert_eq!(vertices as u64, self.vertex_count());
        denses.par_iter().zip(&first).zip(&starts).for_each(|((dense, owned), &start)| {
            for (w, &v) in owned.iter().enumerate() {
                slot[dense[v as usize] as usize].store((start + w) as u32, Ordering::Relaxed);
            }
        });

        // Each chunk finishes its points (and the ring beyond them its fans reach) and writes
        // the ones it is first to hold, and its triangles, into its own piece of the buffers.
        let colored = self.config.climate.enabled;
        let corners: usize = layouts.iter().map(|l| l.indices.len()).sum();
        let mut whole = GlobeMesh {
            origin: [0.0; 3],
            buffers: MeshBuffers {
                positions: vec![[0.0; 3]; vertices],
                normals: vec![[0.0; 3]; vertices],
                tile_kinds: vec![0; vertices],
                center_distances: vec![0.0; vertices],
                colors: vec![[0; 4]; if colored { vertices } else { 0 }],
                indices: vec![0; corners],
                ..MeshBuffers::default()
            },
            points: vec![GlobePoint(0); vertices],
            heights: vec![0.0; vertices],
            tiles: layouts.iter().flat_map(|l| l.tiles.iter().copied()).collect(),
            triangle_tiles: vec![GlobeTile(0); corners / 3],
        };
        let lens: Vec<usize> = first.iter().map(Vec::len).collect();
        let colors: Vec<usize> = lens.iter().map(|&len| if colored { len } else { 0 }).collect();
        let corners: Vec<usize> = layouts.iter().map(|l| l.indices.len()).collect();
        let triangles: Vec<usize> = layouts.iter().map(|l| l.triangle_tiles.len()).collect();
        let b = &mut whole.buffers;
        let mut positions = split(&mut b.positions, &lens).into_iter();
        let mut normals = split(&mut b.normals, &lens).into_iter();
        let mut kinds = split(&mut b.tile_kinds, &lens).into_iter();
        let mut distances = split(&mut b.center_distances, &lens).into_iter();
        let mut colors = split(&mut b.colors, &colors).into_iter();
        let mut points = split(&mut whole.points, &lens).into_iter();
        let mut heights = split(&mut whole.heights, &lens).into_iter();
        let mut indices = split(&mut b.indices, &corners).into_iter();
        let mut triangle_tiles = split(&mut whole.triangle_tiles, &triangles).into_iter();
        let pieces: Vec<Piece<'_>> = (0..layouts.len())
            .map(|_| Piece {
                vertices: Vertices {
                    positions: positions.next().unwrap_or_default(),
                    normals: normals.next().unwrap_or_default(),
                    kinds: kinds.next().unwrap_or_default(),
                    distances: distances.next().unwrap_or_default(),
                    colors: colors.next().unwrap_or_default(),
                    points: points.next().unwrap_or_default(),
                    heights: heights.next().unwrap_or_default(),
                },
                indices: indices.next().unwrap_or_default(),
                triangle_tiles: triangle_tiles.next().unwrap_or_default(),
            })
            .collect();
        pieces.into_par_iter().zip(&layouts).zip(&denses).zip(&first).for_each(|(((out, layout), dense), owned)| {
            let all = self.finish_layout(layout);
            self.write_vertices(layout, &all, owned, [0.0; 3], out.vertices);
            // Each of the chunk's points' whole vertex, then its triangles' corners.
            let vertex: Vec<u32> = dense.iter().map(|&k| slot[k as usize].load(Ordering::Relaxed)).collect();
            for (o, &i) in out.indices.iter_mut().zip(&layout.indices) {
                *o = vertex[i as usize];
            }
            out.triangle_tiles.copy_from_slice(&layout.triangle_tiles);
        });
        // Each chunk's layout given back on the core that made it.
        layouts.into_par_iter().for_each(drop);
        whole
    }

    /// The 3D fBm at the direction of every point of the whole globe's mesh (each point once,
    /// batched and on all cores as meshing samples them), and nothing else: the noise floor of
    /// generating the globe. Returns the sum of the samples so the work cannot be elided.
    #[cfg(feature = "bench")]
    #[must_use]
    pub fn noise_floor(&self) -> f64 {
        use crate::heights::fbm::LANES;

        self.fine
            .points()
            .par_chunks(LANES)
            .map(|batch| self.directions_and_fbm_lanes(batch)[..batch.len()].iter().map(|l| l.1).sum::<f64>())
            .sum()
    }
}

/// The part of the whole globe's buffers one chunk writes: its first points' vertices, and its
/// triangles.
struct Piece<'a> {
    vertices: Vertices<'a>,
    indices: &'a mut [u32],
    triangle_tiles: &'a mut [GlobeTile],
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
