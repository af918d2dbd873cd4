//! The whole globe's mesh: its chunks meshed in parallel and merged, each point kept once, by
//! work that runs on every core too (no step walks all the points on one thread).

use std::sync::atomic::{AtomicU32, Ordering};

use rayon::prelude::*;

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
        // Every point is the same bits in every chunk that holds it: the chunk it is first met
        // in writes it.
        let parts: Vec<(GlobeMesh, Vec<u32>)> =
            self.chunks().into_par_iter().map(|chunk| self.mesh(self.chunk_tiles(chunk), [0.0; 3])).collect();
        // Each point's first chunk, then (once every chunk has read it) its whole vertex.
        let slot: Vec<AtomicU32> = (0..self.fine.point_count()).map(|_| AtomicU32::new(u32::MAX)).collect();
        parts.par_iter().enumerate().for_each(|(c, (_, dense))| {
            for &k in dense {
                slot[k as usize].fetch_min(c as u32, Ordering::Relaxed);
            }
        });
        let first: Vec<Vec<u32>> = parts
            .par_iter()
            .enumerate()
            .map(|(c, (_, dense))| {
                (0..dense.len() as u32)
                    .filter(|&v| slot[dense[v as usize] as usize].load(Ordering::Relaxed) == c as u32)
                    .collect()
            })
            .collect();
        let mut starts = Vec::with_capacity(parts.len());
        let mut vertices = 0;
        for owned in &first {
            starts.push(vertices);
            vertices += owned.len();
        }
        debug_assert_eq!(vertices as u64, self.vertex_count());
        parts.par_iter().zip(&first).zip(&starts).for_each(|(((_, dense), owned), &start)| {
            for (w, &v) in owned.iter().enumerate() {
                slot[dense[v as usize] as usize].store((start + w) as u32, Ordering::Relaxed);
            }
        });

        let colored = parts.first().is_some_and(|(mesh, _)| !mesh.buffers.colors.is_empty());
        let mut whole = GlobeMesh {
            origin: [0.0; 3],
            buffers: MeshBuffers {
                positions: vec![[0.0; 3]; vertices],
                normals: vec![[0.0; 3]; vertices],
                tile_kinds: vec![0; vertices],
                center_distances: vec![0.0; vertices],
                colors: vec![[0; 4]; if colored { vertices } else { 0 }],
                indices: vec![0; parts.iter().map(|(mesh, _)| mesh.buffers.indices.len()).sum()],
                ..MeshBuffers::default()
            },
            points: vec![GlobePoint(0); vertices],
            heights: vec![0.0; vertices],
            tiles: parts.iter().flat_map(|(mesh, _)| mesh.tiles.iter().copied()).collect(),
            triangle_tiles: vec![GlobeTile(0); parts.iter().map(|(mesh, _)| mesh.triangle_tiles.len()).sum()],
        };
        let lens: Vec<usize> = first.iter().map(Vec::len).collect();
        let colors: Vec<usize> = lens.iter().map(|&len| if colored { len } else { 0 }).collect();
        let corners: Vec<usize> = parts.iter().map(|(mesh, _)| mesh.buffers.indices.len()).collect();
        let triangles: Vec<usize> = parts.iter().map(|(mesh, _)| mesh.triangle_tiles.len()).collect();
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
        let pieces: Vec<Piece<'_>> = (0..parts.len())
            .map(|_| Piece {
                positions: positions.next().unwrap_or_default(),
                normals: normals.next().unwrap_or_default(),
                kinds: kinds.next().unwrap_or_default(),
                distances: distances.next().unwrap_or_default(),
                colors: colors.next().unwrap_or_default(),
                points: points.next().unwrap_or_default(),
                heights: heights.next().unwrap_or_default(),
                indices: indices.next().unwrap_or_default(),
                triangle_tiles: triangle_tiles.next().unwrap_or_default(),
            })
            .collect();
        pieces.into_par_iter().zip(&parts).zip(&first).for_each(|((out, (part, dense)), owned)| {
            let from = &part.buffers;
            for (w, &v) in owned.iter().enumerate() {
                let v = v as usize;
                out.positions[w] = from.positions[v];
                out.normals[w] = from.normals[v];
                out.kinds[w] = from.tile_kinds[v];
                out.distances[w] = from.center_distances[v];
                if let Some(c) = out.colors.get_mut(w) {
                    *c = from.colors[v];
                }
                out.points[w] = part.points[v];
                out.heights[w] = part.heights[v];
            }
            for (o, &i) in out.indices.iter_mut().zip(&from.indices) {
                *o = slot[dense[i as usize] as usize].load(Ordering::Relaxed);
            }
            out.triangle_tiles.copy_from_slice(&part.triangle_tiles);
        });
        // Each chunk's buffers given back on the core that made them.
        parts.into_par_iter().for_each(drop);
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
    positions: &'a mut [[f32; 3]],
    normals: &'a mut [[f32; 3]],
    kinds: &'a mut [u32],
    distances: &'a mut [f32],
    colors: &'a mut [[u8; 4]],
    points: &'a mut [GlobePoint],
    heights: &'a mut [f32],
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
