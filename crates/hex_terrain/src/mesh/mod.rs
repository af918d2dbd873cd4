//! Mesh generation: any rectangle of tiles to plain vertex and index buffers.
//!
//! | file | stage |
//! | --- | --- |
//! | `mod.rs` | the public buffers ([`MeshBuffers`], [`ChunkMesh`], [`Diagnostics`]), options ([`GenerateOptions`]), [`generate`] and [`vertex_color`] |
//! | `grid.rs` | the point grid: lattice coordinates to point indices, and the enumeration of a rectangle's points |
//! | `job.rs` | one generation as a job whose passes are methods: the prelude (points, buffers, tile kinds) |
//! | `indices.rs` | the indices pass: a tile's triangles from one grid lookup a template row |
//! | `vertices.rs` | the vertex passes: the owned points in stages over batches, the halo's heights |
//! | `normals.rs` | the normals pass |
//! | `lanes.rs` | the passes' loops compiled for the instruction set of the map's kernel (AVX2, AVX-512), checked at run time |
//! | `parallel.rs` | the parallel policy: batches, pool entry, disjoint output slices |
//! | `coarse.rs` | level of detail: a generated mesh as a fan a tile, its outline kept whole ([`Detail`]) |

pub(crate) mod coarse;
mod early;
mod grid;
mod indices;
mod job;
mod lanes;
mod normals;
mod parallel;
mod vertices;

use hexx::Hex;

pub use coarse::Detail;

use crate::chunk::TileRect;
use crate::info::TileInfo;
use crate::pipeline::Pipeline;
use crate::vocab::Biome;

/// Generates the mesh of any rectangle of tiles (clipped to the map), with the halo it needs:
/// the result for a tile does not depend on which rectangle it was generated in, nor on the
/// options (diagnostics, and where the work runs).
#[must_use]
pub fn generate(pipeline: &Pipeline, rect: TileRect, options: GenerateOptions) -> ChunkMesh {
    job::Job::new(pipeline, rect, options).run()
}

/// The lattice points generation evaluates for `rect`, enumerated as generation does: its
/// vertices, then the one-step halo that normals need. For benchmarks (the noise floor).
#[cfg(feature = "bench")]
#[must_use]
pub fn mesh_points(pipeline: &Pipeline, rect: TileRect) -> Vec<Hex> {
    job::Job::new(pipeline, rect, GenerateOptions::default()).points()
}

/// The color of a vertex shared by tiles of `biomes`: their colors averaged (integer
/// arithmetic, so the order of the tiles does not matter), the water cover in alpha.
#[must_use]
#[inline]
pub fn vertex_color(biomes: &[Biome], water: f32) -> [u8; 4] {
    let colors: Vec<[u8; 3]> = biomes.iter().map(|b| b.color()).collect();
    mixed_color(&colors, water)
}

/// The texture class of a tile (`0..3`, [`MeshBuffers::texture_layers`]): `(q - r) mod 3` of its
/// axial coordinate. Each of the six neighbors of a tile is of another class. A chunk's tiles
/// are the map's own (on a wrapping map, `Terrain::wrap_tile`'s); a neighbor across a wrapping
/// map's seam is taken where it lies beside them, so a shader reads the entry of the class of
/// the map's own tile under a fragment.
#[must_use]
#[inline]
pub fn texture_class(tile: Hex) -> usize {
    (tile.x - tile.y).rem_euclid(3) as usize
}

/// The color of a vertex shared by tiles of `colors`: their colors averaged (integer
/// arithmetic, so the order of the tiles does not matter), the water cover in alpha.
#[must_use]
#[inline]
pub fn mixed_color(colors: &[[u8; 3]], water: f32) -> [u8; 4] {
    let mut sum = [0_u32; 3];
    for color in colors {
        for (s, &c) in sum.iter_mut().zip(color) {
            *s += u32::from(c);
        }
    }
    let n = colors.len().max(1) as u32;
    let avg = sum.map(|s| ((s + n / 2) / n) as u8);
    [avg[0], avg[1], avg[2], (water.clamp(0.0, 1.0) * 255.0).round() as u8]
}

/// Plain vertex and index buffers, ready for any renderer.
///
/// Positions are relative to the generation's origin ([`ChunkMesh::origin`], the center of its
/// first tile), `y` up: computed from integer lattice offsets, so they keep their precision
/// however far from the world's origin the chunk lies. Faces are wound counter-clockwise seen
/// from above. UVs are world-space (`x`, `z`) divided by twice the hex size, modulo whole
/// texture repeats, so textures tile across chunks without seams.
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
    /// Distance to the tile center in rings, normalised: 0 at the center, 1 on the border.
    /// Interpolated across a triangle it reaches 1 exactly on tile edges.
    pub center_distances: Vec<f32>,
    /// sRGB color of each vertex when the map has a climate or rivers (empty otherwise): the
    /// biome colors of the tiles holding it averaged, and in alpha how much river or lake water
    /// covers it (0 dry, 255 open water).
    pub colors: Vec<[u8; 4]>,
    /// With the colors, each vertex's texture layers: entry `c` is the texture layer
    /// ([`Look::texture`](crate::Look::texture)) of the tile of class `c` ([`texture_class`])
    /// holding the vertex, where one does (else the vertex's own tile's layer). A tile's
    /// neighbors are of the two other classes, so the three tiles meeting at a corner have one
    /// class each, and every vertex of a triangle holds the triangle's tile: entry
    /// `texture_class(tile)` is that tile's layer at all three, and a shader reading it draws
    /// each tile with its own layer. Empty without colors.
    pub texture_layers: Vec<[u8; 3]>,
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

/// A generated chunk: its mesh plus what games read of its tiles.
#[derive(Debug, Clone, PartialEq)]
pub struct ChunkMesh {
    /// The tiles it covers (clipped to the map).
    pub rect: TileRect,
    /// World position `[x, y, z]` of the origin its positions are relative to (the center of
    /// its first tile at height 0): put the mesh there. A whole map starting at offset `[0, 0]`
    /// has its origin at zero, so its positions are world positions.
    pub origin: [f64; 3],
    /// The mesh.
    pub buffers: MeshBuffers,
    /// Type and center elevation of each tile, row by row.
    pub tiles: Vec<TileInfo>,
    /// Per-vertex data that metrics and tests read, when asked for with
    /// [`GenerateOptions::diagnostics`].
    pub diagnostics: Option<Diagnostics>,
}

/// Per-vertex data of a generation beyond what renders: where each vertex sits in the lattice
/// and what manipulation did to it. Index `i` is vertex `i` of the buffers.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Diagnostics {
    /// Lattice coordinate of each vertex.
    pub lattice: Vec<Hex>,
    /// Normalised height of each vertex before manipulation.
    pub raw_heights: Vec<f32>,
    /// Whether hex unity or edge/corner correction moved each vertex.
    pub moved: Vec<bool>,
    /// Ring of each vertex in its tile (`n` on borders).
    pub rings: Vec<u8>,
}

/// How a generation runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct GenerateOptions {
    /// Keep [`Diagnostics`] (four more buffers written, about 10 bytes a vertex).
    pub diagnostics: bool,
    /// Where the work runs.
    pub threads: Threads,
}

impl GenerateOptions {
    /// On rayon's pool, with diagnostics: what metrics and tests use.
    pub const DIAGNOSTICS: Self = Self { diagnostics: true, threads: Threads::Pool };
    /// On the calling thread, without diagnostics: what a caller on its own pool uses (the Bevy
    /// plugin's chunk tasks on the async compute pool).
    pub const CURRENT_THREAD: Self = Self { diagnostics: false, threads: Threads::Current };
}

/// Where a generation's work runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Threads {
    /// On rayon's global pool when the rectangle is large enough to pay for it (more than one
    /// batch of 1024 points), else on the calling thread.
    #[default]
    Pool,
    /// Only on the calling thread; rayon is not touched.
    Current,
}

/// Output buffers of a generation.
struct Buffers {
    b: MeshBuffers,
    raws: Vec<f32>,
    moved: Vec<bool>,
    rings: Vec<u8>,
    /// World height of the point in each grid slot.
    heights: Vec<f32>,
}

impl Buffers {
    /// Zeroed buffers for `vertices` vertices (and their diagnostics when `diagnostics`),
    /// `indices` indices and a height grid of `slots`. Zeroing recycled memory costs a pass over
    /// it, so it is done beside the sequential point enumeration; fresh pages come zeroed from
    /// the system and are mapped when the passes first write them.
    fn new(vertices: usize, indices: usize, slots: usize, diagnostics: bool, colors: bool) -> Self {
        let d = if diagnostics { vertices } else { 0 };
        Self {
            b: MeshBuffers {
                positions: vec![[0.0; 3]; vertices],
                normals: vec![[0.0; 3]; vertices],
                uvs: vec![[0.0; 2]; vertices],
                tile_kinds: vec![0; vertices],
                center_distances: vec![0.0; vertices],
                colors: vec![[0; 4]; if colors { vertices } else { 0 }],
                texture_layers: vec![[0; 3]; if colors { vertices } else { 0 }],
                indices: vec![0; indices],
            },
            raws: vec![0.0; d],
            moved: vec![false; d],
            rings: vec![0; d],
            heights: vec![0.0; slots],
        }
    }

    /// The same buffers holding exactly `vertices` vertices (a no-op when the count was right).
    fn fit(mut self, vertices: usize, diagnostics: bool, colors: bool) -> Self {
        if colors {
            self.b.colors.resize(vertices, [0; 4]);
            self.b.texture_layers.resize(vertices, [0; 3]);
        }
        self.b.positions.resize(vertices, [0.0; 3]);
        self.b.normals.resize(vertices, [0.0; 3]);
        self.b.uvs.resize(vertices, [0.0; 2]);
        self.b.tile_kinds.resize(vertices, 0);
        self.b.center_distances.resize(vertices, 0.0);
        if diagnostics {
            self.raws.resize(vertices, 0.0);
            self.moved.resize(vertices, false);
            self.rings.resize(vertices, 0);
        }
        self
    }
}

#[cfg(test)]
mod tests;
