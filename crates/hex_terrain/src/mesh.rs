//! Mesh buffers of a chunk: positions, smooth normals, UVs, per-vertex tile data, u32 indices.

use hexx::Hex;
use rayon::prelude::*;

use crate::chunk::{ChunkCoord, TileRect};
use crate::classify::TileKind;
use crate::config::Orientation;
use crate::lattice::Lattice;
use crate::terrain::{Terrain, TileInfo};

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
    pub rings: Vec<u8>,
    /// Type and centre elevation of each tile, row by row.
    pub tiles: Vec<TileInfo>,
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
    /// Zeroed buffers for `vertices` vertices, `indices` indices and a height grid of `slots`.
    /// Zeroing recycled memory costs a pass over it, so it is done here, beside the sequential
    /// point enumeration; fresh pages come zeroed from the system and are mapped when the passes
    /// first write them.
    fn new(vertices: usize, indices: usize, slots: usize) -> Self {
        Self {
            b: MeshBuffers {
                positions: vec![[0.0; 3]; vertices],
                normals: vec![[0.0; 3]; vertices],
                uvs: vec![[0.0; 2]; vertices],
                tile_kinds: vec![0; vertices],
                centre_distances: vec![0.0; vertices],
                indices: vec![0; indices],
            },
            raws: vec![0.0; vertices],
            moved: vec![false; vertices],
            rings: vec![0; vertices],
            heights: vec![0.0; slots],
        }
    }

    /// The same buffers holding exactly `vertices` vertices (a no-op when the count was right).
    fn fit(mut self, vertices: usize) -> Self {
        self.b.positions.resize(vertices, [0.0; 3]);
        self.b.normals.resize(vertices, [0.0; 3]);
        self.b.uvs.resize(vertices, [0.0; 2]);
        self.b.tile_kinds.resize(vertices, 0);
        self.b.centre_distances.resize(vertices, 0.0);
        self.raws.resize(vertices, 0.0);
        self.moved.resize(vertices, false);
        self.rings.resize(vertices, 0);
        self
    }
}

/// `f(i)` for `i` in `0..len`, on all cores, in order.
fn par_map<O: Send>(len: usize, f: impl Fn(usize) -> O + Sync + Send) -> Vec<O> {
    (0..len).into_par_iter().with_min_len(512).map(f).collect()
}

/// Points processed together by one task.
const BATCH: usize = 1024;

/// The tile whose template enumerated a point first, and the point's index in that template.
#[derive(Clone, Copy)]
struct Owner {
    tile: u32,
    k: u16,
}

/// Lattice points of a rectangle of tiles, as [`Terrain::collect_points`] enumerates them.
struct Points {
    grid: Grid,
    /// Every point: the tiles' own first, then the halo, each in grid order (row by row).
    lattice: Vec<Hex>,
    /// How many points belong to the tiles (the rest is halo).
    owned: usize,
    /// The owner of each owned point.
    owner: Vec<Owner>,
}

/// Dense lookup from lattice coordinates to point indices over a bounding box.
///
/// Rows are staggered like hexx's offset coordinates, so that a rectangle of tiles covers a
/// rectangle of slots with little waste: for flat tiles a row is a lattice `y` and the column
/// `x + ⌊y/2⌋` follows world x; for pointy tiles a row is a lattice `x` (a world column) and
/// the column `y + ⌊x/2⌋` follows world z. Points are numbered in slot order, so the slots of a
/// run of points increase, and along a row consecutive points sit in consecutive slots and share
/// the parity of the row, which decides the slot offsets of their neighbours.
struct Grid {
    shape: GridShape,
    slots: Vec<u32>,
    /// Slot offsets of the six [`AROUND`] steps, by row parity.
    around: [[isize; 6]; 2],
}

/// The extent and layout of a [`Grid`].
#[derive(Clone, Copy)]
struct GridShape {
    /// Whether rows are lattice `x` (pointy tiles) rather than lattice `y` (flat).
    pointy: bool,
    min: [i32; 2],
    width: usize,
    height: usize,
}

impl GridShape {
    /// A shape holding every point of `tiles` and the one-step halo around them.
    fn around(lattice: &Lattice, tiles: &[Hex]) -> Self {
        let pointy = lattice.orientation() == Orientation::Pointy;
        let (mut min, mut max) = ([i32::MAX; 2], [i32::MIN; 2]);
        for &tile in tiles {
            let c = Self::coords(pointy, lattice.tile_centre(tile));
            min = [min[0].min(c[0]), min[1].min(c[1])];
            max = [max[0].max(c[0]), max[1].max(c[1])];
        }
        if tiles.is_empty() {
            return Self { pointy, min: [0, 0], width: 0, height: 0 };
        }
        // A point `r` steps from a centre is at most `r + 1` columns and `r` rows away (in
        // either layout); the halo adds one step to the tiles' `n`.
        let margin = lattice.subdivisions() as i32 + 2;
        let min = [min[0] - margin, min[1] - margin];
        let (width, height) = ((max[0] + margin - min[0] + 1) as usize, (max[1] + margin - min[1] + 1) as usize);
        Self { pointy, min, width, height }
    }

    /// `[column, row]` of a point in the grid.
    #[inline]
    fn coords(pointy: bool, p: Hex) -> [i32; 2] {
        if pointy { [p.y + p.x.div_euclid(2), p.x] } else { [p.x + p.y.div_euclid(2), p.y] }
    }

    fn len(&self) -> usize {
        self.width * self.height
    }

    #[inline]
    fn slot(&self, p: Hex) -> usize {
        let [c, r] = Self::coords(self.pointy, p);
        let (c, r) = (c - self.min[0], r - self.min[1]);
        debug_assert!(c >= 0 && r >= 0 && (c as usize) < self.width && (r as usize) < self.height);
        r as usize * self.width + c as usize
    }

    /// The point in `slot`.
    #[inline]
    fn point(&self, slot: usize) -> Hex {
        let c = (slot % self.width) as i32 + self.min[0];
        let r = (slot / self.width) as i32 + self.min[1];
        if self.pointy { Hex::new(r, c - r.div_euclid(2)) } else { Hex::new(c - r.div_euclid(2), r) }
    }

    /// Parity of `p`'s row: which of the tables of [`GridShape::offsets`] applies.
    #[inline]
    fn parity(&self, p: Hex) -> usize {
        (if self.pointy { p.x } else { p.y } & 1) as usize
    }

    /// Slot offset of lattice offset `d` from a point whose row has `parity`.
    fn offset(&self, parity: i32, d: Hex) -> isize {
        let p = if self.pointy { Hex::new(parity, 0) } else { Hex::new(0, parity) };
        let [c0, r0] = Self::coords(self.pointy, p);
        let [c, r] = Self::coords(self.pointy, p + d);
        (r - r0) as isize * self.width as isize + (c - c0) as isize
    }

    /// Slot offsets of lattice offsets `d` from a point, for each parity of the point.
    fn offsets<const N: usize>(&self, d: [Hex; N]) -> [[isize; N]; 2] {
        [0, 1].map(|parity| d.map(|d| self.offset(parity, d)))
    }
}

impl Grid {
    const EMPTY: u32 = u32::MAX;
    /// A slot of the halo, before numbering.
    const HALO: u32 = u32::MAX - 1;

    fn new(shape: GridShape) -> Self {
        Self { shape, slots: vec![Self::EMPTY; shape.len()], around: shape.offsets(AROUND) }
    }

    #[inline]
    fn slot(&self, p: Hex) -> usize {
        self.shape.slot(p)
    }

    /// Slot offsets of the six lattice neighbours of `p`, in [`AROUND`] order.
    #[inline]
    fn around(&self, p: Hex) -> [isize; 6] {
        self.around[self.shape.parity(p)]
    }

    /// Point indices of the template points of the tile centred on `centre`, in template order.
    #[inline]
    fn template_points(&self, centre: Hex, offsets: &[Vec<isize>; 2], out: &mut [u32]) {
        let base = self.slot(centre);
        for (o, &d) in out.iter_mut().zip(&offsets[self.shape.parity(centre)]) {
            *o = self.slots[base.wrapping_add_signed(d)];
        }
    }
}

/// Most points of a tile template (`1 + 3n(n + 1)` for the largest `n`).
const TEMPLATE_MAX: usize = {
    let n = crate::config::MAX_INNER_RINGS as usize + 1;
    1 + 3 * n * (n + 1)
};

/// Slot offsets of every template point, for each parity of the centre.
fn template_offsets(shape: &GridShape, lattice: &Lattice) -> [Vec<isize>; 2] {
    let template = lattice.template();
    [0, 1].map(|parity| template.iter().map(|tp| shape.offset(parity, tp.offset)).collect())
}

/// The per-vertex outputs of a run of owned points, split in halves for the tasks, with the
/// part of the height grid from the run's first slot up to the next run's.
struct Outputs<'a> {
    positions: &'a mut [[f32; 3]],
    uvs: &'a mut [[f32; 2]],
    kinds: &'a mut [u32],
    distances: &'a mut [f32],
    raws: &'a mut [f32],
    moved: &'a mut [bool],
    rings: &'a mut [u8],
    heights: &'a mut [f32],
    /// The slot of `heights[0]`.
    first_slot: usize,
}

impl Outputs<'_> {
    fn len(&self) -> usize {
        self.positions.len()
    }

    /// Splits at point `mid`, whose slot is `slot`.
    fn split_at(self, mid: usize, slot: usize) -> (Self, Self) {
        let (p0, p1) = self.positions.split_at_mut(mid);
        let (u0, u1) = self.uvs.split_at_mut(mid);
        let (k0, k1) = self.kinds.split_at_mut(mid);
        let (d0, d1) = self.distances.split_at_mut(mid);
        let (r0, r1) = self.raws.split_at_mut(mid);
        let (m0, m1) = self.moved.split_at_mut(mid);
        let (g0, g1) = self.rings.split_at_mut(mid);
        let (h0, h1) = self.heights.split_at_mut(slot - self.first_slot);
        (
            Outputs {
                positions: p0,
                uvs: u0,
                kinds: k0,
                distances: d0,
                raws: r0,
                moved: m0,
                rings: g0,
                heights: h0,
                first_slot: self.first_slot,
            },
            Outputs {
                positions: p1,
                uvs: u1,
                kinds: k1,
                distances: d1,
                raws: r1,
                moved: m1,
                rings: g1,
                heights: h1,
                first_slot: slot,
            },
        )
    }
}

/// Runs `f(start, outputs)` on batches of at most [`BATCH`] points (`start` is the index of the
/// first; `slot_of(i)` the slot of point `i`), on all cores when splitting.
fn in_batches<F: Fn(usize, Outputs<'_>) + Sync>(
    split: Split,
    out: Outputs<'_>,
    start: usize,
    slot_of: &(impl Fn(usize) -> usize + Sync),
    f: &F,
) {
    if out.len() <= BATCH {
        f(start, out);
    } else {
        let mid = (out.len() / BATCH).div_ceil(2) * BATCH;
        let (a, b) = out.split_at(mid, slot_of(start + mid));
        split.join(|| in_batches(split, a, start, slot_of, f), || in_batches(split, b, start + mid, slot_of, f));
    }
}

/// Whether a generation spreads its work over the thread pool: only when there is enough of it
/// to pay for waking other threads.
#[derive(Clone, Copy)]
struct Split(bool);

impl Split {
    /// Most points not worth splitting (one batch, as in [`Terrain::noise_floor`]): up to this
    /// many, a generation runs on the calling thread.
    const MIN_POINTS: usize = BATCH;

    /// Fewest points for which the work beside the point enumeration goes to another thread.
    const SIDE_MIN_POINTS: usize = 4 * BATCH;

    /// `f()`, inside the thread pool when splitting (entered once, rather than at every
    /// parallel call inside `f`).
    fn in_pool<R: Send>(self, f: impl FnOnce() -> R + Send) -> R {
        if self.0 && rayon::current_thread_index().is_none() { rayon::scope(|_| f()) } else { f() }
    }

    /// `(a(), b())`, in parallel when splitting.
    fn join<A: Send, B: Send>(self, a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B + Send) -> (A, B) {
        if self.0 { rayon::join(a, b) } else { (a(), b()) }
    }

    /// Smallest piece a parallel iterator may split into: everything at once when not splitting.
    fn min_len(self, len: usize) -> usize {
        if self.0 { len } else { usize::MAX }
    }
}

/// Coefficients of the smooth normal: the sum of the six lattice triangles' face normals
/// (area-weighted) around a vertex is `(Σ dₖ·x[k], y, Σ dₖ·z[k])`, with `dₖ` the height of the
/// k-th neighbour minus the vertex's, because every lattice offset is flat.
struct NormalCoefficients {
    x: [f32; 6],
    y: f32,
    z: [f32; 6],
}

impl NormalCoefficients {
    fn new(around: &[[f32; 2]; 6]) -> Self {
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
    fn normal(&self, h0: f32, height: impl Fn(usize) -> f32) -> [f32; 3] {
        let mut around = [[0.0; NORMAL_LANES]; 6];
        for (k, a) in around.iter_mut().enumerate() {
            a[0] = height(k);
        }
        let mut out = [[0.0; 3]; NORMAL_LANES];
        self.normals(&[h0; NORMAL_LANES], &around, &mut out);
        out[0]
    }

    /// [`NormalCoefficients::normal`] of [`NORMAL_LANES`] vertices at once (heights `h0`, the
    /// k-th neighbours' heights in `around[k]`), lane by lane so that it vectorises; every lane
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

/// Vertices whose normals are computed together.
const NORMAL_LANES: usize = 8;

/// Lattice directions around a vertex, counter-clockwise in lattice space.
const AROUND: [Hex; 6] = crate::lattice::NEIGHBOURS;

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

    /// Lattice points of `tiles` and of the one-step halo around them that smooth normals need,
    /// with the grid indexing both. Each point belongs to the first tile (in `tiles` order)
    /// whose template holds it; the tiles' points come first, then the halo's, each in grid
    /// order.
    fn collect_points(&self, tiles: &[Hex], shape: GridShape, offsets: &[Vec<isize>; 2]) -> Points {
        let lattice = self.lattice();
        let n = lattice.subdivisions();
        let ppt = lattice.points_per_tile();
        let template = lattice.template();
        let mut grid = Grid::new(shape);
        // Claim: each slot holds `tile * ppt + k` of its first tile until it is numbered.
        for (t, &tile) in tiles.iter().enumerate() {
            let centre = lattice.tile_centre(tile);
            let base = grid.slot(centre);
            for (k, &d) in offsets[shape.parity(centre)].iter().enumerate() {
                let slot = &mut grid.slots[base.wrapping_add_signed(d)];
                if *slot == Grid::EMPTY {
                    *slot = (t * ppt + k) as u32;
                }
            }
        }
        // Number the tiles' points in slot order, marking the halo around border points.
        let estimate = tiles.len() * 3 * (n * n) as usize + 64;
        let mut points = Vec::with_capacity(estimate + estimate / 8);
        let mut owner = Vec::with_capacity(estimate);
        for slot in 0..grid.slots.len() {
            let code = grid.slots[slot];
            if code >= Grid::HALO {
                continue;
            }
            let (tile, k) = (code as usize / ppt, code as usize % ppt);
            let p = shape.point(slot);
            grid.slots[slot] = points.len() as u32;
            points.push(p);
            owner.push(Owner { tile: tile as u32, k: k as u16 });
            if template[k].ring == n {
                for d in grid.around(p) {
                    let next = &mut grid.slots[slot.wrapping_add_signed(d)];
                    if *next == Grid::EMPTY {
                        *next = Grid::HALO;
                    }
                }
            }
        }
        let owned = points.len();
        for slot in 0..grid.slots.len() {
            if grid.slots[slot] == Grid::HALO {
                grid.slots[slot] = points.len() as u32;
                points.push(shape.point(slot));
            }
        }
        Points { grid, lattice: points, owned, owner }
    }

    /// Bare fBm at every point, batched and on all cores.
    fn noise_at(&self, points: &[Hex]) -> Vec<f64> {
        let mut out = vec![0.0; points.len()];
        out.par_chunks_mut(BATCH).enumerate().for_each(|(k, chunk)| {
            self.base_heights(&points[k * BATCH..k * BATCH + chunk.len()], chunk);
        });
        out
    }

    /// Vertex count of the mesh of `rect` (clipped to the map), from the count formula
    /// ([`Lattice::mesh_vertex_count`](crate::Lattice::mesh_vertex_count)).
    fn rect_vertex_count(&self, rect: TileRect) -> usize {
        let tiles = rect.len();
        if tiles == 0 {
            return 0;
        }
        // Only tiles in the first or last row or column can have a neighbour outside.
        let [c0, r0] = rect.min;
        let [c1, r1] = [rect.max[0] - 1, rect.max[1] - 1];
        let outline = rect
            .iter()
            .filter(|&[c, r]| c == c0 || c == c1 || r == r0 || r == r1)
            .map(|oc| {
                let tile = self.tile_from_offset(oc);
                tile.all_neighbors().iter().filter(|&&nb| !rect.contains(self.offset_of(nb))).count()
            })
            .sum();
        self.lattice().mesh_vertex_count(tiles, outline)
    }

    /// Kind of every tile of `rect` (row by row), `None` for those outside the map,
    /// and the height-source sample at each tile's centre.
    fn halo_kinds(&self, rect: TileRect) -> (Vec<Option<TileKind>>, Vec<f64>) {
        let lattice = self.lattice();
        let tiles: Vec<Hex> = rect.iter().map(|oc| self.tile_from_offset(oc)).collect();
        let centres: Vec<Hex> = tiles.iter().map(|&t| lattice.tile_centre(t)).collect();
        let noise = self.noise_at(&centres);
        let kinds = par_map(tiles.len(), |k| {
            self.contains(tiles[k]).then(|| self.thresholds().classify(self.shaped(noise[k], centres[k])))
        });
        (kinds, noise)
    }

    /// Height-source samples of a batch of owned points; a tile's centre (template point 0)
    /// takes the sample already taken for its tile's kind, `centre_noise[tile]`.
    fn batch_noise(&self, points: &[Hex], owners: &[Owner], centre_noise: &[f64], out: &mut [f64]) {
        if !self.samples_noise() {
            self.base_heights(points, out);
            return;
        }
        let mut positions = [[0.0; 2]; BATCH];
        let mut sampled = [0.0; BATCH];
        let mut len = 0;
        for (&p, owner) in points.iter().zip(owners) {
            if owner.k != 0 {
                positions[len] = self.noise_position(p);
                len += 1;
            }
        }
        self.fbm().sample_many(&positions[..len], &mut sampled[..len]);
        let mut next = sampled.iter();
        for (o, owner) in out.iter_mut().zip(owners) {
            *o = if owner.k == 0 { centre_noise[owner.tile as usize] } else { next.next().copied().unwrap_or(0.0) };
        }
    }

    /// Generates the mesh of any rectangle of tiles (clipped to the map) with the halo it needs:
    /// the result for a tile does not depend on which rectangle it was generated in.
    ///
    /// While the points are enumerated (sequentially), other threads classify the tiles and
    /// allocate the buffers. Then one pass computes the owned vertices (noise, shaping,
    /// manipulation and every attribute but the normal) while another computes the halo's
    /// heights; then the normals, which need the heights of the six lattice neighbours, and the
    /// indices. Each pass runs on all cores when the rectangle holds more than one batch.
    #[must_use]
    pub fn generate_rect(&self, rect: TileRect) -> ChunkMesh {
        let rect = self.bounds().map_or(rect, |b| rect.intersect(&b));
        let n = self.lattice().subdivisions() as usize;
        self.generate_rect_with(rect, Split(rect.len() * 3 * n * n > Split::MIN_POINTS))
    }

    fn generate_rect_with(&self, rect: TileRect, split: Split) -> ChunkMesh {
        let tiles: Vec<Hex> = rect.iter().map(|oc| self.tile_from_offset(oc)).collect();
        let lattice = self.lattice();
        let n = lattice.subdivisions();
        let ppt = lattice.points_per_tile();

        // Kinds of the tiles and of the ring around them (`None` outside the map): every vertex
        // evaluated below lies in one of those.
        let halo = rect.grow(1);
        let halo_width = (halo.max[0] - halo.min[0]) as usize;
        let halo_index = |[c, r]: [i32; 2]| (r - halo.min[1]) as usize * halo_width + (c - halo.min[0]) as usize;
        let kind_in = |kinds: &[Option<TileKind>], tile: Hex| {
            let oc = self.offset_of(tile);
            if halo.contains(oc) { kinds[halo_index(oc)] } else { self.map_tile_kind(tile) }
        };
        let shape = GridShape::around(lattice, &tiles);
        let offsets = template_offsets(&shape, lattice);
        // Beside a small rectangle the side work is shorter than waking a second thread (and
        // letting it fall asleep again before the passes): then it runs before the passes.
        let side = Split(split.0 && tiles.len() * ppt > Split::SIDE_MIN_POINTS);
        let prelude = || {
            side.join(
                || {
                    side.join(
                        || self.collect_points(&tiles, shape, &offsets),
                        || {
                            Buffers::new(
                                self.rect_vertex_count(rect),
                                tiles.len() * lattice.triangles_per_tile() * 3,
                                shape.len(),
                            )
                        },
                    )
                },
                || {
                    // Per tile: its own kind and its six neighbours' (`all_neighbors` order).
                    let (kinds, noise) = self.halo_kinds(halo);
                    let centre_noise: Vec<f64> = rect.iter().map(|[c, r]| noise[halo_index([c, r])]).collect();
                    let around: Vec<(TileKind, [Option<TileKind>; 6])> = tiles
                        .iter()
                        .map(|&t| {
                            (
                                kind_in(&kinds, t).unwrap_or(TileKind::Sea),
                                t.all_neighbors().map(|nb| kind_in(&kinds, nb)),
                            )
                        })
                        .collect();
                    (kinds, around, centre_noise)
                },
            )
        };
        let ((Points { grid, lattice: mut points, owned, owner }, out), (kinds, around_kinds, centre_noise)) =
            side.in_pool(prelude);
        let Buffers { mut b, mut raws, mut moved, mut rings, mut heights } = out.fit(owned);
        let kind_of = |tile: Hex| kind_in(&kinds, tile);

        let max_elevation = self.config().terrain.max_elevation;
        let uv_scale = 0.5 / self.config().layout.hex_size;
        let inv_n = 1.0 / n as f32;
        let template = lattice.template();
        let slot_of = |i: usize| grid.slot(points[i]);

        // The halo's heights (for the normals of border vertices), beside the tiles' vertices.
        // A halo point is one step from a border point of the rectangle, whose tile and template
        // index tell which tiles hold the halo point (a table of the lattice), so it needs no
        // search of its own.
        let halo_vertex = |p: Hex, raw: f32| {
            let slot = grid.slot(p);
            for (d, step) in grid.around(p).into_iter().enumerate() {
                let i = grid.slots[slot.wrapping_add_signed(step)] as usize;
                if i >= owned {
                    continue;
                }
                let Owner { tile, k } = owner[i];
                let k = usize::from(k);
                if template[k].ring == n {
                    // `p` is the neighbour of point `i` in the opposite direction.
                    let set = lattice.around_tiles(k, (d + 3) % 6);
                    let base = tiles[tile as usize];
                    let mut sharing = [TileKind::Sea; 3];
                    let mut len = 0;
                    for &t in set.tiles() {
                        if let Some(kind) = kind_of(base + t) {
                            sharing[len] = kind;
                            len += 1;
                        }
                    }
                    return self.finish_vertex(raw, set.ring, &sharing[..len]);
                }
            }
            self.border_vertex(raw, p, kind_of)
        };
        let halo_pass = || {
            let mut out = vec![0.0_f32; points.len() - owned];
            out.par_chunks_mut(BATCH).zip(points[owned..].par_chunks(BATCH)).with_min_len(split.min_len(1)).for_each(
                |(out, pts)| {
                    let mut noise = [0.0; BATCH];
                    self.base_heights(pts, &mut noise[..pts.len()]);
                    for ((h, &p), &noise) in out.iter_mut().zip(pts).zip(&noise) {
                        *h = halo_vertex(p, self.shaped(noise, p)).height * max_elevation;
                    }
                },
            );
            out
        };
        // Every pass from here on, in one visit to the thread pool.
        split.in_pool(|| {
            let outputs = Outputs {
                positions: &mut b.positions,
                uvs: &mut b.uvs,
                kinds: &mut b.tile_kinds,
                distances: &mut b.centre_distances,
                raws: &mut raws,
                moved: &mut moved,
                rings: &mut rings,
                heights: &mut heights,
                first_slot: 0,
            };
            let owned_pass = || {
                // The tiles' own vertices: their tiles are known, so no lookup is needed.
                in_batches(split, outputs, 0, &slot_of, &|start, o: Outputs<'_>| {
                    let pts = &points[start..start + o.len()];
                    let mut noise = [0.0; BATCH];
                    self.batch_noise(pts, &owner[start..start + pts.len()], &centre_noise, &mut noise[..pts.len()]);
                    for (j, &p) in pts.iter().enumerate() {
                        let Owner { tile, k } = owner[start + j];
                        let k = usize::from(k);
                        let ring = template[k].ring;
                        let raw = self.shaped(noise[j], p);
                        let (own, around) = &around_kinds[tile as usize];
                        let s = if ring < n {
                            self.finish_vertex(raw, ring, &[*own])
                        } else {
                            let mut sharing = [*own; 3];
                            let mut len = 1;
                            for d in lattice.shared_tiles(k) {
                                if let Some(&Some(kind)) = around.get(usize::from(d)) {
                                    sharing[len] = kind;
                                    len += 1;
                                }
                            }
                            self.finish_vertex(raw, ring, &sharing[..len])
                        };
                        let height = s.height * max_elevation;
                        let [x, z] = lattice.world(p);
                        let (x, z) = (x as f32, z as f32);
                        o.positions[j] = [x, height, z];
                        o.heights[grid.slot(p) - o.first_slot] = height;
                        o.uvs[j] = [x * uv_scale, z * uv_scale];
                        o.kinds[j] = s.kind as u32;
                        o.distances[j] = ring as f32 * inv_n;
                        o.raws[j] = raw;
                        o.moved[j] = s.moved;
                        o.rings[j] = ring as u8;
                    }
                });
            };
            let ((), halo_heights) = split.join(owned_pass, halo_pass);
            for (&p, h) in points[owned..].iter().zip(halo_heights) {
                heights[grid.slot(p)] = h;
            }

            // Normals: every neighbour of an owned point is an owned or a halo point, so its height
            // is in the grid. Eight points in consecutive slots of one row read eight consecutive
            // heights per direction.
            let (step_a, step_b) = lattice.steps();
            let around: [[f32; 2]; 6] = AROUND.map(|d| {
                let (i, j) = (f64::from(d.x), f64::from(d.y));
                [(i * step_a[0] + j * step_b[0]) as f32, (i * step_a[1] + j * step_b[1]) as f32]
            });
            let coefficients = NormalCoefficients::new(&around);
            let heights = &heights;
            let normals_pass = || {
                b.normals.par_chunks_mut(BATCH).with_min_len(split.min_len(1)).enumerate().for_each(|(c, normals)| {
                    let mut h0 = [0.0; NORMAL_LANES];
                    let mut around = [[0.0; NORMAL_LANES]; 6];
                    let mut out = [[0.0; 3]; NORMAL_LANES];
                    for (g, normals) in normals.chunks_mut(NORMAL_LANES).enumerate() {
                        let first = c * BATCH + g * NORMAL_LANES;
                        let slot = slot_of(first);
                        let last = first + NORMAL_LANES - 1;
                        if normals.len() == NORMAL_LANES
                            && slot_of(last) == slot + NORMAL_LANES - 1
                            && slot / shape.width == (slot + NORMAL_LANES - 1) / shape.width
                        {
                            h0.copy_from_slice(&heights[slot..slot + NORMAL_LANES]);
                            for (a, d) in around.iter_mut().zip(grid.around(points[first])) {
                                let s = slot.wrapping_add_signed(d);
                                a.copy_from_slice(&heights[s..s + NORMAL_LANES]);
                            }
                        } else {
                            for l in 0..normals.len() {
                                let slot = slot_of(first + l);
                                h0[l] = heights[slot];
                                for (a, d) in around.iter_mut().zip(grid.around(points[first + l])) {
                                    a[l] = heights[slot.wrapping_add_signed(d)];
                                }
                            }
                        }
                        coefficients.normals(&h0, &around, &mut out);
                        normals.copy_from_slice(&out[..normals.len()]);
                    }
                });
            };

            let per_tile = lattice.triangles_per_tile() * 3;
            let indices_pass = || {
                b.indices.par_chunks_mut(per_tile).zip(&tiles).with_min_len(split.min_len(16)).for_each(
                    |(out, &tile)| {
                        let mut own = [0_u32; TEMPLATE_MAX];
                        grid.template_points(lattice.tile_centre(tile), &offsets, &mut own[..ppt]);
                        for (tri, dst) in lattice.template_triangle_indices().iter().zip(out.chunks_exact_mut(3)) {
                            for (&k, d) in tri.iter().zip(dst) {
                                *d = own[usize::from(k)];
                            }
                        }
                    },
                );
            };
            split.join(normals_pass, indices_pass);
        });

        let tiles_info = tiles
            .iter()
            .zip(&around_kinds)
            .map(|(&hex, &(kind, _))| TileInfo {
                hex,
                kind,
                elevation: heights[grid.slot(lattice.tile_centre(hex))],
                in_map: true,
            })
            .collect();
        points.truncate(owned);
        ChunkMesh { rect, buffers: b, lattice: points, raw_heights: raws, moved, rings, tiles: tiles_info }
    }

    /// The lattice points [`Terrain::generate_rect`] evaluates for `rect`: its vertices, then
    /// the one-step halo that normals need.
    #[must_use]
    pub fn mesh_points(&self, rect: TileRect) -> Vec<Hex> {
        let rect = self.bounds().map_or(rect, |b| rect.intersect(&b));
        let tiles: Vec<Hex> = rect.iter().map(|oc| self.tile_from_offset(oc)).collect();
        let shape = GridShape::around(self.lattice(), &tiles);
        self.collect_points(&tiles, shape, &template_offsets(&shape, self.lattice())).lattice
    }

    /// Bare fBm at exactly the points [`Terrain::generate_rect`] evaluates, enumerated the same
    /// way: the noise floor of generation. Returns the sum of the samples so the work cannot be
    /// elided.
    #[must_use]
    pub fn noise_floor(&self, rect: TileRect) -> f64 {
        self.noise_at(&self.mesh_points(rect)).iter().sum()
    }
}

#[cfg(test)]
mod tests;
