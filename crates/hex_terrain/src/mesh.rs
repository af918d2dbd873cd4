//! Mesh buffers of a chunk: positions, smooth normals, UVs, per-vertex tile data, u32 indices.

use hexx::Hex;

use crate::chunk::{ChunkCoord, TileRect};
use crate::classify::TileKind;
use crate::terrain::{Terrain, TileInfo, VertexSample};

/// Plain vertex and index buffers, ready for any renderer.
///
/// Positions are world coordinates with `y` up; faces are wound counter-clockwise seen from
/// above. UVs are world-space (`x`, `z`) divided by twice the hex size, so textures tile across
/// chunks without seams.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MeshBuffers {
    /// Vertex positions `[x, y, z]`.
    pub positions: Vec<[f32; 3]>,
    /// Unit vertex normals, averaged over the six lattice triangles around each vertex.
    pub normals: Vec<[f32; 3]>,
    /// World-space texture coordinates.
    pub uvs: Vec<[f32; 2]>,
    /// Kind of the tile owning the vertex (`TileKind as u32`; on a border, the highest kind
    /// among the tiles sharing it).
    pub tile_kinds: Vec<u32>,
    /// Distance to the tile centre in rings, normalised: 0 at the centre, 1 on the border.
    /// Interpolated across a triangle it reaches 1 exactly on tile edges, which is what a shader
    /// needs to draw tile outlines.
    pub centre_distances: Vec<f32>,
    /// Triangle list indices.
    pub indices: Vec<u32>,
}

impl MeshBuffers {
    /// Number of vertices.
    #[must_use]
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles.
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }
}

/// A generated chunk: its mesh plus what tests, metrics and games read.
#[derive(Debug, Clone, PartialEq)]
pub struct ChunkMesh {
    /// The tiles it covers (clipped to the map).
    pub rect: TileRect,
    /// The mesh.
    pub buffers: MeshBuffers,
    /// Lattice coordinate of each vertex.
    pub lattice: Vec<Hex>,
    /// Normalised height of each vertex before manipulation.
    pub raw_heights: Vec<f32>,
    /// Whether hex unity or edge/corner correction moved each vertex.
    pub moved: Vec<bool>,
    /// Ring of each vertex in its tile (`n` on borders).
    pub rings: Vec<u32>,
    /// Type and centre elevation of each tile, row by row.
    pub tiles: Vec<TileInfo>,
}

#[cfg(feature = "rayon")]
fn par_map<I: Sync, O: Send>(items: &[I], f: impl Fn(&I) -> O + Sync + Send) -> Vec<O> {
    use rayon::prelude::*;
    items.par_iter().with_min_len(256).map(f).collect()
}

#[cfg(not(feature = "rayon"))]
fn par_map<I, O>(items: &[I], f: impl Fn(&I) -> O) -> Vec<O> {
    items.iter().map(f).collect()
}

#[cfg(feature = "rayon")]
fn par_chunks<I: Sync, O: Send>(input: &[I], output: &mut [O], size: usize, f: impl Fn(&[I], &mut [O]) + Sync + Send) {
    use rayon::prelude::*;
    input.par_chunks(size).zip(output.par_chunks_mut(size)).for_each(|(i, o)| f(i, o));
}

#[cfg(not(feature = "rayon"))]
fn par_chunks<I, O>(input: &[I], output: &mut [O], size: usize, f: impl Fn(&[I], &mut [O])) {
    input.chunks(size).zip(output.chunks_mut(size)).for_each(|(i, o)| f(i, o));
}

/// Dense lookup from lattice coordinates to vertex indices over a bounding box.
struct Grid {
    min: Hex,
    width: i32,
    height: i32,
    slots: Vec<u32>,
}

impl Grid {
    const EMPTY: u32 = u32::MAX;

    fn new(min: Hex, max: Hex) -> Self {
        let (width, height) = (max.x - min.x + 1, max.y - min.y + 1);
        Self { min, width, height, slots: vec![Self::EMPTY; (width as usize) * (height as usize)] }
    }

    #[inline]
    fn slot(&self, p: Hex) -> usize {
        let (x, y) = (p.x - self.min.x, p.y - self.min.y);
        debug_assert!(x >= 0 && y >= 0 && x < self.width && y < self.height);
        (y as usize) * (self.width as usize) + x as usize
    }

    #[inline]
    fn get(&self, p: Hex) -> u32 {
        self.slots[self.slot(p)]
    }
}

/// Lattice directions around a vertex, counter-clockwise in lattice space.
const AROUND: [Hex; 6] =
    [Hex::new(1, 0), Hex::new(0, 1), Hex::new(-1, 1), Hex::new(-1, 0), Hex::new(0, -1), Hex::new(1, -1)];

impl Terrain {
    /// Generates a chunk, `None` when it lies outside a bounded map.
    #[must_use]
    pub fn generate_chunk(&self, chunk: ChunkCoord) -> Option<ChunkMesh> {
        self.chunk_rect(chunk).map(|rect| self.generate_rect(rect))
    }

    /// Generates a bounded map in one mesh, `None` for an unbounded world.
    #[must_use]
    pub fn generate_map(&self) -> Option<ChunkMesh> {
        self.bounds().map(|rect| self.generate_rect(rect))
    }

    /// Lattice points of the tiles of `rect` (each once, tile by tile in template order) and of
    /// the one-step halo around them that smooth normals need, with the grid indexing both.
    fn collect_points(&self, tiles: &[Hex]) -> (Grid, Vec<Hex>, usize, Vec<u32>) {
        let lattice = self.lattice();
        let n = lattice.subdivisions() as i32;
        let (mut min, mut max) = (Hex::new(i32::MAX, i32::MAX), Hex::new(i32::MIN, i32::MIN));
        for &tile in tiles {
            let c = lattice.tile_centre(tile);
            min = Hex::new(min.x.min(c.x), min.y.min(c.y));
            max = Hex::new(max.x.max(c.x), max.y.max(c.y));
        }
        let margin = Hex::new(n + 1, n + 1);
        let mut grid = Grid::new(min - margin, max + margin);
        let mut points = Vec::with_capacity(tiles.len() * 3 * (n * n) as usize + 4 * n as usize * 64);
        let mut centres = Vec::with_capacity(tiles.len());
        let mut border = Vec::new();
        for &tile in tiles {
            let c = lattice.tile_centre(tile);
            for tp in lattice.template() {
                let p = c + tp.offset;
                let slot = grid.slot(p);
                if grid.slots[slot] == Grid::EMPTY {
                    grid.slots[slot] = points.len() as u32;
                    if tp.ring == 0 {
                        centres.push(points.len() as u32);
                    } else if tp.ring == n as u32 {
                        border.push(points.len());
                    }
                    points.push(p);
                }
            }
        }
        let owned = points.len();
        for i in border {
            let p = points[i];
            for d in AROUND {
                let q = p + d;
                let slot = grid.slot(q);
                if grid.slots[slot] == Grid::EMPTY {
                    grid.slots[slot] = points.len() as u32;
                    points.push(q);
                }
            }
        }
        (grid, points, owned, centres)
    }

    /// Generates the mesh of any rectangle of tiles (clipped to the map) with the halo it needs:
    /// the result for a tile does not depend on which rectangle it was generated in.
    #[must_use]
    pub fn generate_rect(&self, rect: TileRect) -> ChunkMesh {
        let rect = self.bounds().map_or(rect, |b| rect.intersect(&b));
        let tiles: Vec<Hex> = rect.iter().map(|oc| self.tile_from_offset(oc)).collect();
        let lattice = self.lattice();

        // Kinds of the tiles and their neighbours: every vertex evaluated below lies in one of them.
        let halo = rect.grow(1);
        let halo_offsets: Vec<[i32; 2]> = halo.iter().collect();
        let kinds: Vec<Option<TileKind>> = par_map(&halo_offsets, |&oc| {
            let tile = self.tile_from_offset(oc);
            self.map_tile_kind(tile)
        });
        let halo_width = (halo.max[0] - halo.min[0]) as usize;
        let kind_of = |tile: Hex| {
            let [c, r] = self.offset_of(tile);
            if halo.contains([c, r]) {
                kinds[(r - halo.min[1]) as usize * halo_width + (c - halo.min[0]) as usize]
            } else {
                self.map_tile_kind(tile)
            }
        };

        let (grid, points, owned, centres) = self.collect_points(&tiles);
        let samples: Vec<VertexSample> = par_map(&points, |&p| self.vertex_with(p, kind_of));

        let max_elevation = self.config().terrain.max_elevation;
        let heights: Vec<f32> = samples.iter().map(|s| s.height * max_elevation).collect();
        let (step_a, step_b) = lattice.steps();
        let around: [[f32; 2]; 6] = AROUND.map(|d| {
            let (i, j) = (f64::from(d.x), f64::from(d.y));
            [(i * step_a[0] + j * step_b[0]) as f32, (i * step_a[1] + j * step_b[1]) as f32]
        });
        let owned_points = &points[..owned];
        let normals: Vec<[f32; 3]> = par_map(owned_points, |&p| {
            let h0 = heights[grid.get(p) as usize];
            let e: [[f32; 3]; 6] = std::array::from_fn(|k| {
                let h = heights[grid.get(p + AROUND[k]) as usize];
                [around[k][0], h - h0, around[k][1]]
            });
            let mut sum = [0.0_f32; 3];
            for k in 0..6 {
                let (u, v) = (e[(k + 1) % 6], e[k]);
                // u x v: upward for a counter-clockwise pair in (x, z).
                sum[0] += u[1] * v[2] - u[2] * v[1];
                sum[1] += u[2] * v[0] - u[0] * v[2];
                sum[2] += u[0] * v[1] - u[1] * v[0];
            }
            let len = (sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]).sqrt();
            if len > 0.0 && len.is_finite() { sum.map(|c| c / len) } else { [0.0, 1.0, 0.0] }
        });

        let uv_scale = 0.5 / self.config().layout.hex_size;
        let mut buffers = MeshBuffers {
            positions: Vec::with_capacity(owned),
            normals,
            uvs: Vec::with_capacity(owned),
            tile_kinds: Vec::with_capacity(owned),
            centre_distances: Vec::with_capacity(owned),
            indices: Vec::new(),
        };
        let inv_n = 1.0 / lattice.subdivisions() as f32;
        for (i, &p) in owned_points.iter().enumerate() {
            let [x, z] = lattice.world(p);
            let (x, z) = (x as f32, z as f32);
            buffers.positions.push([x, heights[i], z]);
            buffers.uvs.push([x * uv_scale, z * uv_scale]);
            buffers.tile_kinds.push(samples[i].kind as u32);
            buffers.centre_distances.push(samples[i].ring as f32 * inv_n);
        }

        let per_tile = lattice.triangles_per_tile() * 3;
        let tile_indices: Vec<Vec<u32>> = par_map(&tiles, |&tile| {
            let c = lattice.tile_centre(tile);
            let mut out = Vec::with_capacity(per_tile);
            for tri in lattice.template_triangles() {
                out.extend(tri.iter().map(|&o| grid.get(c + o)));
            }
            out
        });
        buffers.indices = tile_indices.concat();

        let tiles_info = tiles
            .iter()
            .zip(&centres)
            .map(|(&hex, &ci)| {
                let s = &samples[ci as usize];
                TileInfo { hex, kind: self.thresholds().classify(s.raw), elevation: heights[ci as usize], in_map: true }
            })
            .collect();

        ChunkMesh {
            rect,
            buffers,
            raw_heights: samples[..owned].iter().map(|s| s.raw).collect(),
            moved: samples[..owned].iter().map(|s| s.moved).collect(),
            rings: samples[..owned].iter().map(|s| s.ring).collect(),
            lattice: points[..owned].to_vec(),
            tiles: tiles_info,
        }
    }

    /// The lattice points [`Terrain::generate_rect`] evaluates for `rect`: its vertices, then
    /// the one-step halo that normals need.
    #[must_use]
    pub fn mesh_points(&self, rect: TileRect) -> Vec<Hex> {
        let rect = self.bounds().map_or(rect, |b| rect.intersect(&b));
        let tiles: Vec<Hex> = rect.iter().map(|oc| self.tile_from_offset(oc)).collect();
        self.collect_points(&tiles).1
    }

    /// Bare fBm at exactly the points [`Terrain::generate_rect`] evaluates: the noise floor of
    /// generation. Returns the sum of the samples so the work cannot be elided.
    #[must_use]
    pub fn noise_floor(&self, rect: TileRect) -> f64 {
        let points = self.mesh_points(rect);
        let positions: Vec<[f64; 2]> = points.iter().map(|&p| self.noise_position(p)).collect();
        let mut samples = vec![0.0; positions.len()];
        par_chunks(&positions, &mut samples, 1024, |pos, out| self.fbm().sample_many(pos, out));
        samples.iter().sum()
    }
}

#[cfg(test)]
mod tests;
