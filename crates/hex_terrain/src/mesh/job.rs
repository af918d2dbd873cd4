//! One generation as a job: the tiles of a rectangle, the grid over them and the passes that
//! fill the buffers.
//!
//! While the points are enumerated (sequentially), other threads classify the tiles and
//! allocate the buffers ([`Job::prelude`]). Then one pass computes the owned vertices (noise,
//! shaping, manipulation and every attribute but the normal, [`Job::owned_pass`]) while another
//! computes the halo's heights ([`Job::halo_pass`]); then the normals, which need the heights of
//! the six lattice neighbors, and the indices. Each pass runs on all cores when the job splits.

use hexx::Hex;

use super::grid::{GridShape, Owner, Points, TEMPLATE_MAX};
use super::lanes;
use super::parallel::{BATCH, Outputs, Split, in_batches};
use super::{Buffers, ChunkMesh, Diagnostics, GenerateOptions, Threads, vertex_color};
use crate::chunk::TileRect;
use crate::climate::TileSample;
use crate::geometry::Geometry;
use crate::lattice::Lattice;
use crate::manipulate::Manipulated;
use crate::pipeline::Pipeline;
use crate::vertex::{Sharing, VertexSample};
use crate::vocab::{Biome, TileInfo, TileKind};

/// Slots of a tile's point indices: a power of two at least [`TEMPLATE_MAX`], so that a
/// template index masked into it stays in it.
const OWN: usize = TEMPLATE_MAX.next_power_of_two();

/// No direction: a border point's slot for a sharing neighbor that is not in the map.
const NONE: u8 = u8::MAX;

/// A generation of one rectangle of tiles.
pub(super) struct Job<'a> {
    pub pipeline: &'a Pipeline,
    pub geometry: &'a Geometry,
    pub lattice: &'a Lattice,
    /// The tiles (clipped to the map).
    rect: TileRect,
    /// The tiles of `rect`, row by row.
    tiles: Vec<Hex>,
    shape: GridShape,
    /// Slot offsets of each template point from its tile's center, by the center's parity.
    offsets: [Vec<isize>; 2],
    pub split: Split,
    diagnostics: bool,
    /// The lattice point positions are relative to ([`Geometry::rect_origin`]).
    origin: Hex,
}

/// Kinds of the tiles of a job and of the ring around them, and their center samples.
struct Kinds {
    /// The job's rectangle grown by one tile (two when biomes are computed here, which need
    /// the kinds around each tile of the first ring).
    halo: TileRect,
    /// Kind of each tile of `halo` (row by row), `None` outside the map.
    kinds: Vec<Option<TileKind>>,
    /// Per tile of the job: its own kind and its six neighbors' (`all_neighbors` order).
    around: Vec<(TileKind, [Option<TileKind>; 6])>,
    /// Per tile of the job, when meshes have vertex colors: its biome and its neighbors'.
    biomes: Vec<(Biome, [Option<Biome>; 6])>,
    /// Per tile of the job, on a map with rivers: whether water lies on it and on each neighbor
    /// (only points of wet tiles are carved).
    wet: Vec<(bool, [bool; 6])>,
}

impl Kinds {
    fn index(&self, [c, r]: [i32; 2]) -> usize {
        let width = (self.halo.max[0] - self.halo.min[0]) as usize;
        (r - self.halo.min[1]) as usize * width + (c - self.halo.min[0]) as usize
    }

    /// Kind of a tile, `None` outside the map; every vertex of the job lies in a tile of `halo`.
    #[inline]
    fn get(&self, pipeline: &Pipeline, tile: Hex) -> Option<TileKind> {
        let oc = pipeline.geometry().offset_of(tile);
        if self.halo.contains(oc) { self.kinds[self.index(oc)] } else { pipeline.map_tile_kind(tile) }
    }
}

impl<'a> Job<'a> {
    pub fn new(pipeline: &'a Pipeline, rect: TileRect, options: GenerateOptions) -> Self {
        let geometry = pipeline.geometry();
        let rect = geometry.bounds().map_or(rect, |b| rect.intersect(&b));
        let lattice = geometry.lattice();
        let n = lattice.subdivisions() as usize;
        let split = Split(options.threads == Threads::Pool && rect.len() * 3 * n * n > Split::MIN_POINTS);
        let tiles: Vec<Hex> = rect.iter().map(|oc| geometry.tile_from_offset(oc)).collect();
        let shape = GridShape::around(lattice, &tiles);
        let offsets = shape.template_offsets(lattice);
        let origin = geometry.rect_origin(rect);
        Self {
            pipeline,
            geometry,
            lattice,
            rect,
            tiles,
            shape,
            offsets,
            split,
            diagnostics: options.diagnostics,
            origin,
        }
    }

    /// The lattice points the job evaluates: its vertices, then the one-step halo.
    #[cfg(feature = "bench")]
    pub fn points(&self) -> Vec<Hex> {
        Points::collect(self.lattice, &self.tiles, self.shape, &self.offsets).lattice
    }

    /// Runs every pass and returns the chunk.
    pub fn run(self) -> ChunkMesh {
        let (points, out, kinds) = self.split.in_pool(|| self.prelude());
        let Buffers { mut b, mut raws, mut moved, mut rings, mut heights } =
            out.fit(points.owned, self.diagnostics, self.pipeline.has_vertex_colors());
        // Every pass from here on, in one visit to the thread pool.
        self.split.in_pool(|| {
            let outputs = Outputs {
                positions: &mut b.positions,
                uvs: &mut b.uvs,
                kinds: &mut b.tile_kinds,
                distances: &mut b.center_distances,
                colors: &mut b.colors,
                raws: &mut raws,
                moved: &mut moved,
                rings: &mut rings,
                heights: &mut heights,
                first_slot: 0,
            };
            let ((), halo_heights) =
                self.split.join(|| self.owned_pass(&points, &kinds, outputs), || self.halo_pass(&points, &kinds));
            for (&p, h) in points.lattice[points.owned..].iter().zip(halo_heights) {
                heights[points.grid.slot(p)] = h;
            }
            self.split.join(
                || self.normals_pass(&points, &heights, &mut b.normals),
                || self.indices_pass(&points, &mut b.indices),
            );
        });

        let table = self.pipeline.table();
        let edits = self.pipeline.heights().edits();
        let tiles = self
            .tiles
            .iter()
            .zip(&kinds.around)
            .enumerate()
            .map(|(t, (&hex, &(kind, _)))| TileInfo {
                hex,
                kind,
                elevation: heights[points.grid.slot(self.lattice.tile_center(hex))],
                in_map: true,
                // Without vertex colors the map has no climate and no table: a biome set by
                // hand, else the kind's (as `Pipeline::tile_biome`).
                biome: kinds.biomes.get(t).map_or_else(
                    || edits.and_then(|e| e.biome(self.geometry, hex)).unwrap_or(Biome::of_kind(kind)),
                    |b| b.0,
                ),
                river_flow: table.map_or(0.0, |t| t.river_flow(self.geometry, hex)),
                lake: table.and_then(|t| t.lake(self.geometry, hex)),
            })
            .collect();
        let diagnostics = self.diagnostics.then(|| {
            let mut lattice = points.lattice;
            lattice.truncate(points.owned);
            Diagnostics { lattice, raw_heights: raws, moved, rings }
        });
        let [x, z] = self.lattice.world(self.origin);
        ChunkMesh { rect: self.rect, origin: [x, 0.0, z], buffers: b, tiles, diagnostics }
    }

    /// The work before the passes: the point enumeration beside the tile kinds and the buffers
    /// (on other threads, unless the rectangle is small: then the side work is shorter than
    /// waking a second thread and letting it fall asleep again).
    fn prelude(&self) -> (Points, Buffers, Kinds) {
        let side = Split(self.split.0 && self.tiles.len() * self.lattice.points_per_tile() > Split::SIDE_MIN_POINTS);
        let ((points, buffers), kinds) = side.join(
            || {
                side.join(
                    || Points::collect(self.lattice, &self.tiles, self.shape, &self.offsets),
                    || {
                        Buffers::new(
                            self.vertex_count(),
                            self.tiles.len() * self.lattice.triangles_per_tile() * 3,
                            self.shape.len(),
                            self.diagnostics,
                            self.pipeline.has_vertex_colors(),
                        )
                    },
                )
            },
            || self.kinds(),
        );
        (points, buffers, kinds)
    }

    /// Vertex count of the mesh, from the count formula
    /// ([`Lattice::mesh_vertex_count`](crate::Lattice::mesh_vertex_count)).
    fn vertex_count(&self) -> usize {
        let rect = self.rect;
        if rect.is_empty() {
            return 0;
        }
        // Only tiles in the first or last row or column can have a neighbor outside.
        let [c0, r0] = rect.min;
        let [c1, r1] = [rect.max[0] - 1, rect.max[1] - 1];
        let outline = rect
            .iter()
            .filter(|&[c, r]| c == c0 || c == c1 || r == r0 || r == r1)
            .map(|oc| {
                let tile = self.geometry.tile_from_offset(oc);
                tile.all_neighbors().iter().filter(|&&nb| !rect.contains(self.geometry.offset_of(nb))).count()
            })
            .sum();
        self.lattice.mesh_vertex_count(rect.len(), outline)
    }

    /// Bare source heights at every point, batched.
    fn noise_at(&self, points: &[Hex]) -> Vec<f64> {
        let mut out = vec![0.0; points.len()];
        self.split.for_each_chunk(&mut out, BATCH, 1, |k, chunk| {
            self.pipeline.heights().source_heights(self.geometry, &points[k * BATCH..k * BATCH + chunk.len()], chunk);
        });
        out
    }

    /// Kinds of the tiles and of the ring around them (`None` outside the map), from one sample
    /// at each center: every vertex evaluated lies in one of those tiles.
    fn kinds(&self) -> Kinds {
        let pipeline = self.pipeline;
        let geometry = self.geometry;
        let heights = pipeline.heights();
        let table = pipeline.table();
        let colors = pipeline.has_vertex_colors();
        // Without a precomputed table, a tile's biome needs its neighbors' kinds: two rings.
        let local_biomes = colors && table.is_none();
        let halo = self.rect.grow(if local_biomes { 2 } else { 1 });
        let tiles: Vec<Hex> = halo.iter().map(|oc| geometry.tile_from_offset(oc)).collect();
        let centers: Vec<Hex> = tiles.iter().map(|&t| self.lattice.tile_center(t)).collect();
        let noise = self.noise_at(&centers);
        let raws = self.split.map(tiles.len(), |k| heights.shaped(geometry, noise[k], centers[k]));
        let kinds = self
            .split
            .map(tiles.len(), |k| geometry.contains(tiles[k]).then(|| pipeline.thresholds().classify(raws[k])));
        let mut out = Kinds { halo, kinds, around: Vec::new(), biomes: Vec::new(), wet: Vec::new() };
        out.around = self
            .tiles
            .iter()
            .map(|&t| {
                (out.get(pipeline, t).unwrap_or(TileKind::Sea), t.all_neighbors().map(|nb| out.get(pipeline, nb)))
            })
            .collect();
        if pipeline.water_table().is_some() {
            out.wet = self
                .tiles
                .iter()
                .map(|&t| (pipeline.tile_is_wet(t), t.all_neighbors().map(|nb| pipeline.tile_is_wet(nb))))
                .collect();
        }
        if colors {
            let biome = |t: Hex| -> Option<Biome> {
                if !geometry.contains(t) {
                    return None;
                }
                if table.is_some() {
                    return Some(pipeline.tile_biome(t));
                }
                if let Some(biome) = heights.edits().and_then(|e| e.biome(geometry, t)) {
                    return Some(biome);
                }
                let i = out.index(geometry.offset_of(t));
                let kind = out.kinds[i].unwrap_or(TileKind::Sea);
                let sample = TileSample::new(raws[i], kind, t.all_neighbors().map(|nb| out.get(pipeline, nb)));
                Some(pipeline.climate().biome_of(geometry, heights, t, &sample, false))
            };
            out.biomes =
                self.tiles.iter().map(|&t| (biome(t).unwrap_or(Biome::Ocean), t.all_neighbors().map(biome))).collect();
        }
        out
    }

    /// The tiles' own vertices: their tiles are known, so no lookup is needed.
    fn owned_pass(&self, points: &Points, kinds: &Kinds, outputs: Outputs<'_>) {
        let pipeline = self.pipeline;
        let geometry = self.geometry;
        let heights = pipeline.heights();
        let rules = pipeline.vertex_rules();
        let water = pipeline.water_table();
        let lattice = self.lattice;
        let n = lattice.subdivisions();
        let template = lattice.template();
        let max_elevation = pipeline.max_elevation();
        let uv_scale = 0.5 / geometry.hex_size();
        // UVs are world-space modulo whole texture repeats: the origin's fraction plus the
        // local offset, so they stay small (and exact) anywhere in the world.
        let [ox, oz] = lattice.world(self.origin);
        let uv_origin = [(ox * uv_scale).rem_euclid(1.0), (oz * uv_scale).rem_euclid(1.0)];
        let origin = self.origin;
        let inv_n = 1.0 / n as f32;
        let diagnostics = self.diagnostics;
        let plain = rules.ends_at_manipulation(water) && !pipeline.has_vertex_colors();
        let kernel = heights.fbm().kernel();
        in_batches(self.split, outputs, 0, &|i| points.slot_of(i), &|start, o: Outputs<'_>| {
            lanes::run(
                kernel,
                #[inline(always)]
                || {
                    let len = o.len();
                    let pts = &points.lattice[start..start + len];
                    let owners = &points.owner[start..start + len];
                    let mut noise = [0.0; BATCH];
                    heights.source_heights(geometry, pts, &mut noise[..len]);
                    // Each point's raw height, ring and the kinds of the tiles sharing it: its own
                    // tile's, and on a border the neighbors' in the directions `shared` lists (`NONE`
                    // where no tile of the map lies).
                    let mut raws = [0.0_f32; BATCH];
                    heights.shaped_many(geometry, &noise[..len], pts, &mut raws[..len]);
                    let mut rings = [0_u32; BATCH];
                    let (mut los, mut his) = ([TileKind::Sea; BATCH], [TileKind::Sea; BATCH]);
                    let mut shared = [[NONE; 2]; BATCH];
                    for j in 0..len {
                        let Owner { tile, k } = owners[j];
                        let k = usize::from(k);
                        let ring = template[k].ring;
                        let (own, around) = &kinds.around[tile as usize];
                        let (mut lo, mut hi) = (*own, *own);
                        if ring == n {
                            for (dir, d) in shared[j].iter_mut().zip(lattice.shared_tiles(k)) {
                                if let Some(&Some(kind)) = around.get(usize::from(d)) {
                                    (lo, hi) = (lo.min(kind), hi.max(kind));
                                    *dir = d;
                                }
                            }
                        }
                        rings[j] = ring;
                        (los[j], his[j]) = (lo, hi);
                    }
                    // Manipulation, a vector of points at a time.
                    let (mut manipulated, mut moved) = ([0.0_f32; BATCH], [false; BATCH]);
                    rules.manipulated_many(
                        (&raws[..len], &rings[..len]),
                        (&los[..len], &his[..len]),
                        &mut manipulated[..len],
                        &mut moved[..len],
                    );
                    // The rest of the chain (relief, carving, colors) where the map has any of them;
                    // else a vertex is its manipulation and the highest kind sharing it.
                    let mut finished = [0.0_f32; BATCH];
                    let mut kind_of = [TileKind::Sea; BATCH];
                    if plain {
                        for j in 0..len {
                            (finished[j], kind_of[j]) = (manipulated[j], his[j]);
                        }
                    } else {
                        for j in 0..len {
                            let tile = owners[j].tile as usize;
                            let (own, around) = &kinds.around[tile];
                            let hex = self.tiles[tile];
                            let mut hexes = [hex; 3];
                            let mut sharing = [*own; 3];
                            let mut dirs = [0_usize; 3];
                            let mut count = 1;
                            for &d in shared[j].iter().filter(|&&d| d != NONE) {
                                let d = usize::from(d);
                                (hexes[count], sharing[count], dirs[count]) =
                                    (hex + Hex::NEIGHBORS_COORDS[d], around[d].unwrap_or(*own), d);
                                count += 1;
                            }
                            // Only points of wet tiles are carved: the others read no water.
                            let wet = kinds.wet.get(tile).is_some_and(|(own_wet, around_wet)| {
                                *own_wet || dirs[1..count].iter().any(|&d| around_wet[d])
                            });
                            let tiles = Sharing { tiles: &hexes[..count], kinds: &sharing[..count] };
                            let s = rules.finish_manipulated(
                                geometry,
                                water.filter(|_| wet),
                                raws[j],
                                pts[j],
                                rings[j],
                                tiles,
                                Manipulated { height: manipulated[j], moved: moved[j] },
                            );
                            if !o.colors.is_empty() {
                                let (own_biome, around_biomes) = &kinds.biomes[tile];
                                let mut biomes = [*own_biome; 3];
                                for (b, &d) in biomes.iter_mut().zip(&dirs).skip(1).take(count - 1) {
                                    *b = around_biomes[d].unwrap_or(*own_biome);
                                }
                                o.colors[j] = vertex_color(&biomes[..count], s.water);
                            }
                            (finished[j], kind_of[j], moved[j]) = (s.height, s.kind, s.moved);
                        }
                    }
                    // The buffers, each in a loop of its own.
                    for (((position, uv), &p), &finished) in
                        o.positions.iter_mut().zip(o.uvs.iter_mut()).zip(pts).zip(&finished)
                    {
                        // Relative to the origin from the integer lattice offset: exact however far out.
                        let [x, z] = lattice.world(p - origin);
                        *position = [x as f32, finished * max_elevation, z as f32];
                        *uv = [(uv_origin[0] + x * uv_scale) as f32, (uv_origin[1] + z * uv_scale) as f32];
                    }
                    for (&p, &finished) in pts.iter().zip(&finished) {
                        o.heights[points.grid.slot(p) - o.first_slot] = finished * max_elevation;
                    }
                    for (((kind, distance), &k), &ring) in
                        o.kinds.iter_mut().zip(o.distances.iter_mut()).zip(&kind_of).zip(&rings)
                    {
                        (*kind, *distance) = (k as u32, ring as f32 * inv_n);
                    }
                    if diagnostics {
                        for j in 0..len {
                            (o.raws[j], o.moved[j], o.rings[j]) = (raws[j], moved[j], rings[j] as u8);
                        }
                    }
                },
            );
        });
    }

    /// A halo point, one step from a border point of the rectangle, whose tile and template
    /// index tell which tiles hold the halo point (a table of the lattice), so it needs no
    /// search of its own.
    fn halo_vertex(&self, points: &Points, kinds: &Kinds, p: Hex, raw: f32) -> VertexSample {
        let n = self.lattice.subdivisions();
        let template = self.lattice.template();
        let pipeline = self.pipeline;
        let rules = pipeline.vertex_rules();
        let water = pipeline.water_table();
        let kind_of = |tile: Hex| kinds.get(pipeline, tile);
        let slot = points.grid.slot(p);
        for (d, step) in points.grid.around(p).into_iter().enumerate() {
            let i = points.grid.slots[slot.wrapping_add_signed(step)] as usize;
            if i >= points.owned {
                continue;
            }
            let Owner { tile, k } = points.owner[i];
            let k = usize::from(k);
            if template[k].ring == n {
                // `p` is the neighbor of point `i` in the opposite direction.
                let set = self.lattice.around_tiles(k, (d + 3) % 6);
                let base = self.tiles[tile as usize];
                let mut sharing = [TileKind::Sea; 3];
                let mut hexes = [Hex::ZERO; 3];
                let mut len = 0;
                for &t in set.tiles() {
                    if let Some(kind) = kind_of(base + t) {
                        sharing[len] = kind;
                        hexes[len] = base + t;
                        len += 1;
                    }
                }
                let shared = Sharing { tiles: &hexes[..len], kinds: &sharing[..len] };
                return rules.finish(self.geometry, water, raw, p, set.ring, shared);
            }
        }
        rules.finish_at(self.geometry, water, raw, p, kind_of)
    }

    /// The halo's heights, for the normals of border vertices.
    fn halo_pass(&self, points: &Points, kinds: &Kinds) -> Vec<f32> {
        let halo = &points.lattice[points.owned..];
        let heights = self.pipeline.heights();
        let max_elevation = self.pipeline.max_elevation();
        let mut out = vec![0.0_f32; halo.len()];
        self.split.for_each_chunk(&mut out, BATCH, 1, |c, out| {
            let pts = &halo[c * BATCH..c * BATCH + out.len()];
            let mut noise = [0.0; BATCH];
            heights.source_heights(self.geometry, pts, &mut noise[..pts.len()]);
            for ((h, &p), &noise) in out.iter_mut().zip(pts).zip(&noise) {
                *h = self.halo_vertex(points, kinds, p, heights.shaped(self.geometry, noise, p)).height * max_elevation;
            }
        });
        out
    }

    /// Triangle indices, tile by tile, from the template's triangles and the grid.
    fn indices_pass(&self, points: &Points, indices: &mut [u32]) {
        let ppt = self.lattice.points_per_tile();
        let table = self.lattice.template_triangle_indices().as_flattened();
        let kernel = self.pipeline.heights().fbm().kernel();
        // Tiles a task takes together, sharing one table of their points.
        const TILES: usize = 16;
        self.split.for_each_chunk(indices, table.len() * TILES, 1, |g, out| {
            lanes::run(
                kernel,
                #[inline(always)]
                || {
                    let mut own = [0_u32; OWN];
                    for (t, out) in out.chunks_mut(table.len()).enumerate() {
                        let center = self.lattice.tile_center(self.tiles[g * TILES + t]);
                        points.grid.template_points(center, &self.offsets, &mut own[..ppt]);
                        // A template index masked into `own` needs no bounds check, so the copy
                        // vectorises into gathers.
                        for (d, &k) in out.iter_mut().zip(table) {
                            *d = own[usize::from(k) & (OWN - 1)];
                        }
                    }
                },
            );
        });
    }
}
