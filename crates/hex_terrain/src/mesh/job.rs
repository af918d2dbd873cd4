//! One generation as a job: the tiles of a rectangle, the grid over them and the passes that
//! fill the buffers.
//!
//! While the points are enumerated (sequentially), other threads classify the tiles, allocate
//! the buffers and then sample the noise at the first tiles' points until the enumeration ends
//! ([`Job::prelude`], [`Early`]). Then one pass computes the owned vertices (noise,
//! shaping, manipulation and every attribute but the normal, [`Job::owned_pass`]) while another
//! computes the halo's heights ([`Job::halo_pass`]); then the normals, which need the heights of
//! the six lattice neighbors, and the indices. Each pass runs on all cores when the job splits.

use std::sync::atomic::{AtomicBool, Ordering};

use hexx::Hex;

use super::early::Early;
use super::grid::{GridShape, Points};
use super::indices::Rows;
use super::parallel::{BATCH, Outputs, Split};
use super::{Buffers, ChunkMesh, Diagnostics, GenerateOptions, Threads, texture_class};
use crate::chunk::TileRect;
use crate::climate::TileSample;
use crate::geometry::Geometry;
use crate::heights::Kernel;
use crate::info::TileInfo;
use crate::lattice::Lattice;
use crate::pipeline::Pipeline;
use crate::ruleset::TileTerrain;
use crate::vocab::{Biome, TileKind};

/// A generation of one rectangle of tiles.
pub(super) struct Job<'a> {
    pub pipeline: &'a Pipeline,
    pub geometry: &'a Geometry,
    pub lattice: &'a Lattice,
    /// The tiles (clipped to the map).
    pub rect: TileRect,
    /// The tiles of `rect`, row by row.
    pub tiles: Vec<Hex>,
    pub shape: GridShape,
    /// Slot offsets of each template point from its tile's center, by the center's parity.
    offsets: [Vec<isize>; 2],
    pub split: Split,
    pub diagnostics: bool,
    /// The lattice point positions are relative to ([`Geometry::rect_origin`]).
    pub origin: Hex,
    /// The map's kernel, which the passes' loops are compiled for (module `lanes`).
    pub kernel: Kernel,
    /// The template's rows, for the indices.
    pub rows: Rows,
}

/// A tile's color and its six neighbors' (`None` off the map).
pub(super) type TileColors = ([u8; 3], [Option<[u8; 3]>; 6]);

/// A tile's texture class and layer and its six neighbors' (`all_neighbors` order; a neighbor
/// off the map has the tile's own).
#[derive(Debug, Clone, Copy)]
pub(super) struct TileLayers {
    pub own: (usize, u8),
    pub around: [(usize, u8); 6],
}

/// Kinds of the tiles of a job and of the ring around them, and their center samples.
pub(super) struct Kinds {
    /// The job's rectangle grown by one tile (two when biomes are computed here, which need
    /// the kinds around each tile of the first ring).
    halo: TileRect,
    /// Kind of each tile of `halo` (row by row), `None` outside the map.
    kinds: Vec<Option<TileKind>>,
    /// Per tile of the job: its own kind and its six neighbors' (`all_neighbors` order).
    pub around: Vec<(TileKind, [Option<TileKind>; 6])>,
    /// Per tile of the job, when meshes have vertex colors: its biome and its neighbors'.
    pub biomes: Vec<(Biome, [Option<Biome>; 6])>,
    /// Per tile of the job, on a map with its own terrain ruleset: its color and its
    /// neighbors' ([`Pipeline::tile_color`]); empty otherwise (the biomes' colors).
    pub colors: Vec<TileColors>,
    /// Per tile of the job, when meshes have vertex colors: its texture class and layer and
    /// its neighbors' ([`MeshBuffers::texture_layers`](crate::MeshBuffers::texture_layers)).
    pub layers: Vec<TileLayers>,
    /// Per tile of the job, on a map with rivers: whether water lies on it and on each neighbor
    /// (only points of wet tiles are carved).
    pub wet: Vec<(bool, [bool; 6])>,
    /// Per tile of the job: what it is under the map's ruleset
    /// ([`TileInfo::terrain`](crate::TileInfo::terrain)).
    pub terrains: Vec<TileTerrain>,
}

impl Kinds {
    /// Kind of a tile, `None` outside the map; every vertex of the job lies in a tile of `halo`.
    #[inline]
    pub fn get(&self, pipeline: &Pipeline, tile: Hex) -> Option<TileKind> {
        let oc = pipeline.geometry().offset_of(tile);
        self.halo.index(oc).map_or_else(|| pipeline.map_tile_kind(tile), |i| self.kinds[i])
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
        let rows = Rows::new(lattice, &shape);
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
            kernel: pipeline.heights().fbm().kernel(),
            rows,
        }
    }

    /// The lattice points the job evaluates: its vertices, then the one-step halo.
    #[cfg(feature = "bench")]
    pub fn points(&self) -> Vec<Hex> {
        Points::collect(self.lattice, &self.tiles, self.shape, &self.offsets).lattice
    }

    /// Runs every pass and returns the chunk, in one visit to the thread pool.
    pub fn run(self) -> ChunkMesh {
        self.split.in_pool(|| {
            let (points, out, kinds, early) = self.prelude();
            self.passes(points, out, kinds, &early)
        })
    }

    /// The passes after the prelude.
    pub(super) fn passes(self, points: Points, out: Buffers, kinds: Kinds, early: &Early) -> ChunkMesh {
        let Buffers { mut b, mut raws, mut moved, mut rings, mut heights } =
            out.fit(points.owned, self.diagnostics, self.pipeline.has_vertex_colors());
        // In the thread pool already when `run` called this.
        self.split.in_pool(|| {
            let outputs = Outputs {
                positions: &mut b.positions,
                uvs: &mut b.uvs,
                kinds: &mut b.tile_kinds,
                distances: &mut b.center_distances,
                colors: &mut b.colors,
                layers: &mut b.texture_layers,
                raws: &mut raws,
                moved: &mut moved,
                rings: &mut rings,
                heights: &mut heights,
                first_slot: 0,
            };
            let ((), halo_heights) = self
                .split
                .join(|| self.owned_pass(&points, &kinds, early, outputs), || self.halo_pass(&points, &kinds));
            for (&p, h) in points.lattice[points.owned..].iter().zip(halo_heights) {
                heights[points.grid.slot(p)] = h;
            }
            self.split.join(
                || self.normals_pass(&points, &heights, &mut b.normals),
                || self.rows.indices_pass(self.split, self.kernel, self.lattice, &self.tiles, &points, &mut b.indices),
            );
        });

        let table = self.pipeline.table();
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
                terrain: kinds.terrains[t],
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
    ///
    /// What time the side threads have left before the enumeration ends goes to the noise of
    /// the first tiles' points ([`Early`]).
    pub(super) fn prelude(&self) -> (Points, Buffers, Kinds, Early) {
        let side = Split(self.split.0 && self.tiles.len() * self.lattice.points_per_tile() > Split::SIDE_MIN_POINTS);
        let enumerated = AtomicBool::new(false);
        let ((points, (buffers, early)), kinds) = side.join(
            || {
                side.join(
                    || {
                        let points = Points::collect(self.lattice, &self.tiles, self.shape, &self.offsets);
                        enumerated.store(true, Ordering::Relaxed);
                        points
                    },
                    || {
                        let buffers = Buffers::new(
                            self.vertex_count(),
                            self.tiles.len() * self.lattice.triangles_per_tile() * 3,
                            self.shape.len(),
                            self.diagnostics,
                            self.pipeline.has_vertex_colors(),
                        );
                        (buffers, self.early_noise(|| enumerated.load(Ordering::Relaxed)))
                    },
                )
            },
            || self.kinds(),
        );
        (points, buffers, kinds, early)
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
        let mut out = Kinds {
            halo,
            kinds,
            around: Vec::new(),
            biomes: Vec::new(),
            colors: Vec::new(),
            layers: Vec::new(),
            wet: Vec::new(),
            terrains: Vec::new(),
        };
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
                let i = out.halo.index(geometry.offset_of(t)).expect("a tile within two of the job's");
                let kind = out.kinds[i].unwrap_or(TileKind::Sea);
                let sample = TileSample::new(raws[i], kind, t.all_neighbors().map(|nb| out.get(pipeline, nb)));
                Some(pipeline.climate().biome_of(geometry, heights, t, &sample, false))
            };
            // Each tile of the job and of the ring around it asked once (a tile's biome reads
            // its neighbors' kinds; under the map's own ruleset its terrain samples its center
            // and its neighbors), then read for the tile and for each of its neighbors.
            let ring = self.rect.grow(1);
            let around: Vec<Hex> = ring.iter().map(|oc| geometry.tile_from_offset(oc)).collect();
            let ring_biomes = self.split.map(around.len(), |k| biome(around[k]));
            let mut ring_terrains = Vec::new();
            let at = |t: Hex| ring.index(geometry.offset_of(t)).filter(|&i| around[i] == t);
            let biome_at = |t: Hex| at(t).map_or_else(|| biome(t), |i| ring_biomes[i]);
            let biomes: Vec<(Biome, [Option<Biome>; 6])> = self
                .tiles
                .iter()
                .map(|&t| (biome_at(t).unwrap_or(Biome::Ocean), t.all_neighbors().map(biome_at)))
                .collect();
            let looks: Vec<Option<([u8; 3], u8)>> = if pipeline.has_own_ruleset() {
                ring_terrains = self
                    .split
                    .map(around.len(), |k| geometry.contains(around[k]).then(|| pipeline.tile_terrain(around[k])));
                ring_terrains.iter().map(|t| t.as_ref().map(|t| pipeline.look_of(t))).collect()
            } else {
                ring_biomes.iter().map(|b| b.map(|b| (b.color(), pipeline.biome_texture(b)))).collect()
            };
            let own_look = |t: Hex| {
                if pipeline.has_own_ruleset() {
                    pipeline.tile_look(t)
                } else {
                    let b = biome(t).unwrap_or(Biome::Ocean);
                    (b.color(), pipeline.biome_texture(b))
                }
            };
            let look = |t: Hex| at(t).map_or_else(|| geometry.contains(t).then(|| own_look(t)), |i| looks[i]);
            // A tile of the job is the map's own; a neighbor across a wrapping map's seam is
            // taken where it lies, beside the job's tile (so of another class than it).
            let class = texture_class;
            let fallback = (Biome::Ocean.color(), 0);
            let mut tile_colors = Vec::new();
            let mut tile_layers = Vec::with_capacity(self.tiles.len());
            for &t in &self.tiles {
                let own = look(t).unwrap_or(fallback);
                let neighbors = t.all_neighbors().map(look);
                if pipeline.has_own_ruleset() {
                    tile_colors.push((own.0, neighbors.map(|n| n.map(|(color, _)| color))));
                }
                let neighbor_classes = t.all_neighbors().map(class);
                tile_layers.push(TileLayers {
                    own: (class(t), own.1),
                    around: std::array::from_fn(|d| (neighbor_classes[d], neighbors[d].unwrap_or(own).1)),
                });
            }
            if pipeline.has_own_ruleset() {
                out.terrains =
                    self.tiles.iter().map(|&t| at(t).and_then(|i| ring_terrains[i]).expect("a map tile")).collect();
            }
            (out.biomes, out.colors, out.layers) = (biomes, tile_colors, tile_layers);
        }
        if out.terrains.is_empty() {
            out.terrains = self.terrains(&out, &raws);
        }
        out
    }

    /// What each tile of the job is, where the colors did not ask it already: under the map's
    /// own ruleset the pipeline's answer; under the default, the tile's biome (as the colors
    /// have it, else set by hand or its kind's, as [`Pipeline::tile_biome`] has it on a map
    /// without climate and table) on its landform, from the sample of its center.
    fn terrains(&self, kinds: &Kinds, raws: &[f32]) -> Vec<TileTerrain> {
        let pipeline = self.pipeline;
        let geometry = self.geometry;
        if pipeline.has_own_ruleset() {
            return self.split.map(self.tiles.len(), |k| pipeline.tile_terrain(self.tiles[k]));
        }
        let edits = pipeline.heights().edits();
        let table = pipeline.table();
        self.tiles
            .iter()
            .enumerate()
            .map(|(k, &t)| {
                let i = kinds.halo.index(geometry.offset_of(t)).expect("a tile of the job");
                let kind = kinds.kinds[i].unwrap_or(TileKind::Sea);
                let sample = TileSample::new(raws[i], kind, t.all_neighbors().map(|nb| kinds.get(pipeline, nb)));
                let lake = table.is_some_and(|table| table.lake(geometry, t).is_some());
                let biome = kinds
                    .biomes
                    .get(k)
                    .map_or_else(|| edits.and_then(|e| e.biome(geometry, t)).unwrap_or(Biome::of_kind(kind)), |b| b.0);
                pipeline.biome_terrain(biome, pipeline.climate().landform(&sample, lake))
            })
            .collect()
    }
}
