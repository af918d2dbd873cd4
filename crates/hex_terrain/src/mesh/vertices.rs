//! The vertex passes: the tiles' own points in stages over batches of [`BATCH`], compiled for
//! the map's kernel (the noise, read where a side thread sampled it during the enumeration
//! ([`Early`]) and sampled together for the rest; raw heights; the kinds of the tiles sharing
//! each point; manipulation sixteen at a time; the rest of the chain where the map has any; then
//! a loop a buffer), and the halo's heights that the border normals read.

use hexx::Hex;

use super::early::Early;
use super::grid::{Owner, Points};
use super::job::{Job, Kinds, TileLayers};
use super::lanes;
use super::parallel::{BATCH, Outputs, in_batches};
use super::{mixed_color, vertex_color};
use crate::vertex::{Sharing, VertexSample};
use crate::vocab::TileKind;

/// Tiles whose points the side thread samples together.
const EARLY_TILES: usize = 8;

/// The points of one batch, an array a quantity (the first `len` of each used).
struct Stage {
    len: usize,
    raws: [f32; BATCH],
    rings: [u32; BATCH],
    /// Lowest kind of the tiles sharing each point.
    los: [TileKind; BATCH],
    /// Highest kind of the tiles sharing each point: the vertex's kind.
    his: [TileKind; BATCH],
    /// Normalised heights: manipulated, then finished.
    heights: [f32; BATCH],
    moved: [bool; BATCH],
}

impl Job<'_> {
    /// The noise at the points of the first tiles, until `stop()` (asked between groups of
    /// tiles, so it stops soon after). A point shared with an earlier tile of the job is that
    /// tile's ([`Points::collect`]'s rule), so only each tile's own points are sampled.
    pub(super) fn early_noise(&self, stop: impl Fn() -> bool) -> Early {
        let (heights, template, rect) = (self.pipeline.heights(), self.lattice.template(), self.rect);
        let ppt = template.len();
        // The directions of the neighbors sharing each template point, as bits.
        let shared: Vec<u8> = (0..ppt)
            .map(|k| self.lattice.shared_tiles(k).iter().filter(|&&d| d != u8::MAX).fold(0, |m, &d| m | 1 << d))
            .collect();
        let (mut tiles, mut noise, mut last_slot) = (0, Vec::new(), 0);
        let (mut pts, mut at, mut sampled) = (Vec::new(), Vec::new(), Vec::new());
        while tiles < self.tiles.len() && !stop() {
            let end = (tiles + EARLY_TILES).min(self.tiles.len());
            pts.clear();
            at.clear();
            for (t, &tile) in self.tiles.iter().enumerate().take(end).skip(tiles) {
                let earlier = (0..6)
                    .filter(|&d| {
                        let nb = tile + Hex::NEIGHBORS_COORDS[d];
                        rect.index(self.geometry.offset_of(nb)).is_some_and(|i| i < t && self.tiles[i] == nb)
                    })
                    .fold(0_u8, |m, d| m | 1 << d);
                let center = self.lattice.tile_center(tile);
                for (k, tp) in template.iter().enumerate().filter(|&(k, _)| shared[k] & earlier == 0) {
                    let p = center + tp.offset;
                    last_slot = last_slot.max(self.shape.slot(p));
                    pts.push(p);
                    at.push(t * ppt + k);
                }
            }
            sampled.resize(pts.len(), 0.0);
            heights.source_heights(self.geometry, &pts, &mut sampled);
            noise.resize(end * ppt, 0.0);
            for (&i, &h) in at.iter().zip(&sampled) {
                noise[i] = h;
            }
            tiles = end;
        }
        Early { tiles, noise, last_slot }
    }

    /// The noise at a batch's points: from [`Early`] where their tile's points were sampled,
    /// else sampled here, together.
    #[inline(always)]
    fn batch_noise(&self, early: &Early, pts: &[Hex], owners: &[Owner], noise: &mut [f64]) {
        let heights = self.pipeline.heights();
        let ppt = self.lattice.points_per_tile();
        let known = |o: &Owner| (o.tile as usize) < early.tiles;
        // Points run in slot order.
        if pts.first().is_none_or(|&p| early.tiles == 0 || self.shape.slot(p) > early.last_slot) {
            heights.source_heights(self.geometry, pts, noise);
            return;
        }
        let (mut missing, mut at, mut m) = ([Hex::ZERO; BATCH], [0_u16; BATCH], 0);
        for (j, (o, &p)) in owners.iter().zip(pts).enumerate() {
            if known(o) {
                noise[j] = early.noise[o.tile as usize * ppt + usize::from(o.k)];
            } else {
                (missing[m], at[m]) = (p, j as u16);
                m += 1;
            }
        }
        let mut sampled = [0.0; BATCH];
        heights.source_heights(self.geometry, &missing[..m], &mut sampled[..m]);
        for (&j, &h) in at[..m].iter().zip(&sampled) {
            noise[usize::from(j)] = h;
        }
    }

    /// The tiles' own vertices: their tiles are known, so no lookup is needed.
    pub(super) fn owned_pass(&self, points: &Points, kinds: &Kinds, early: &Early, outputs: Outputs<'_>) {
        in_batches(self.split, outputs, 0, &|i| points.slot_of(i), &|start, o: Outputs<'_>| {
            lanes::run(
                self.kernel,
                #[inline(always)]
                || self.owned_batch(points, kinds, early, start, o),
            );
        });
    }

    /// The owned points `start..start + o.len()` into `o`.
    #[inline(always)]
    fn owned_batch(&self, points: &Points, kinds: &Kinds, early: &Early, start: usize, o: Outputs<'_>) {
        let (geometry, heights) = (self.geometry, self.pipeline.heights());
        let len = o.len();
        let pts = &points.lattice[start..start + len];
        let owners = &points.owner[start..start + len];
        let mut stage = Stage {
            len,
            raws: [0.0; BATCH],
            rings: [0; BATCH],
            los: [TileKind::Sea; BATCH],
            his: [TileKind::Sea; BATCH],
            heights: [0.0; BATCH],
            moved: [false; BATCH],
        };
        let mut noise = [0.0; BATCH];
        self.batch_noise(early, pts, owners, &mut noise[..len]);
        heights.shaped_many(geometry, &noise[..len], pts, &mut stage.raws[..len]);
        self.sharing(kinds, owners, &mut stage);
        let rules = self.pipeline.vertex_rules();
        rules.manipulated_many(
            (&stage.raws[..len], &stage.rings[..len]),
            (&stage.los[..len], &stage.his[..len]),
            &mut stage.heights[..len],
            &mut stage.moved[..len],
        );
        // Else a vertex is its manipulation, its kind the highest sharing it.
        if !rules.ends_at_manipulation(self.pipeline.water_table()) || self.pipeline.has_vertex_colors() {
            self.finish_rest(kinds, pts, owners, &mut stage, (o.colors, o.layers));
        }
        self.write(points, pts, &stage, o);
    }

    /// Each point's ring and the lowest and highest kind of the tiles sharing it: its own tile's,
    /// and on a border the in-map neighbors' in the directions the lattice lists.
    #[inline(always)]
    fn sharing(&self, kinds: &Kinds, owners: &[Owner], stage: &mut Stage) {
        let (n, template) = (self.lattice.subdivisions(), self.lattice.template());
        for (j, &Owner { tile, k }) in owners.iter().enumerate() {
            let k = usize::from(k);
            let ring = template[k].ring;
            let (own, around) = &kinds.around[tile as usize];
            let (mut lo, mut hi) = (*own, *own);
            if ring == n {
                for d in self.lattice.shared_tiles(k) {
                    if let Some(&Some(kind)) = around.get(usize::from(d)) {
                        (lo, hi) = (lo.min(kind), hi.max(kind));
                    }
                }
            }
            (stage.rings[j], stage.los[j], stage.his[j]) = (ring, lo, hi);
        }
    }

    /// The chain after manipulation (relief, carving) and the vertex colors.
    fn finish_rest(
        &self,
        kinds: &Kinds,
        pts: &[Hex],
        owners: &[Owner],
        stage: &mut Stage,
        (colors, layers): (&mut [[u8; 4]], &mut [[u8; 3]]),
    ) {
        let rules = self.pipeline.vertex_rules();
        let water = self.pipeline.water_table();
        for j in 0..stage.len {
            let tile = owners[j].tile as usize;
            let (own, around) = &kinds.around[tile];
            let hex = self.tiles[tile];
            let mut hexes = [hex; 3];
            let mut sharing = [*own; 3];
            let mut dirs = [0_usize; 3];
            let mut count = 1;
            if stage.rings[j] == self.lattice.subdivisions() {
                for d in self.lattice.shared_tiles(usize::from(owners[j].k)).map(usize::from) {
                    if let Some(&Some(kind)) = around.get(d) {
                        (hexes[count], sharing[count], dirs[count]) = (hex + Hex::NEIGHBORS_COORDS[d], kind, d);
                        count += 1;
                    }
                }
            }
            // Only points of wet tiles are carved: the others read no water.
            let wet = kinds
                .wet
                .get(tile)
                .is_some_and(|(own_wet, around_wet)| *own_wet || dirs[1..count].iter().any(|&d| around_wet[d]));
            let tiles = Sharing { tiles: &hexes[..count], kinds: &sharing[..count] };
            let (raw, height, moved, ring, kind) =
                (stage.raws[j], stage.heights[j], stage.moved[j], stage.rings[j], stage.his[j]);
            let s = VertexSample { raw, height, moved, ring, kind, water: 0.0 };
            let s = rules.finish_manipulated(self.geometry, water.filter(|_| wet), pts[j], tiles, s);
            if !colors.is_empty() {
                colors[j] = match kinds.colors.get(tile) {
                    Some((own, around)) => {
                        let mut tones = [*own; 3];
                        for (c, &d) in tones.iter_mut().zip(&dirs).skip(1).take(count - 1) {
                            *c = around[d].unwrap_or(*own);
                        }
                        mixed_color(&tones[..count], s.water)
                    }
                    None => {
                        let (own_biome, around_biomes) = &kinds.biomes[tile];
                        let mut biomes = [*own_biome; 3];
                        for (b, &d) in biomes.iter_mut().zip(&dirs).skip(1).take(count - 1) {
                            *b = around_biomes[d].unwrap_or(*own_biome);
                        }
                        vertex_color(&biomes[..count], s.water)
                    }
                };
            }
            if !layers.is_empty() {
                // Each tile holding the vertex writes its class's entry (their classes differ).
                let TileLayers { own, around } = &kinds.layers[tile];
                let mut entry = [own.1; 3];
                for &d in &dirs[1..count] {
                    let (class, layer) = around[d];
                    entry[class] = layer;
                }
                layers[j] = entry;
            }
            (stage.heights[j], stage.moved[j]) = (s.height, s.moved);
        }
    }

    /// The batch's buffers, each in a loop of its own.
    #[inline(always)]
    fn write(&self, points: &Points, pts: &[Hex], stage: &Stage, o: Outputs<'_>) {
        let (lattice, len) = (self.lattice, stage.len);
        let max_elevation = self.pipeline.max_elevation();
        let uv_scale = 0.5 / self.geometry.hex_size();
        // UVs are world-space modulo whole texture repeats: the origin's fraction plus the
        // local offset, so they stay small (and exact) anywhere in the world.
        let [ox, oz] = lattice.world(self.origin);
        let uv_origin = [(ox * uv_scale).rem_euclid(1.0), (oz * uv_scale).rem_euclid(1.0)];
        let inv_n = 1.0 / lattice.subdivisions() as f32;
        for (((position, uv), &p), &height) in o.positions.iter_mut().zip(o.uvs.iter_mut()).zip(pts).zip(&stage.heights)
        {
            // Relative to the origin from the integer lattice offset: exact however far out.
            let [x, z] = lattice.world(p - self.origin);
            *position = [x as f32, height * max_elevation, z as f32];
            *uv = [(uv_origin[0] + x * uv_scale) as f32, (uv_origin[1] + z * uv_scale) as f32];
        }
        for (&p, &height) in pts.iter().zip(&stage.heights) {
            o.heights[points.grid.slot(p) - o.first_slot] = height * max_elevation;
        }
        for (((kind, distance), &k), &ring) in
            o.kinds.iter_mut().zip(o.distances.iter_mut()).zip(&stage.his).zip(&stage.rings)
        {
            (*kind, *distance) = (k as u32, ring as f32 * inv_n);
        }
        if self.diagnostics {
            for j in 0..len {
                (o.raws[j], o.moved[j], o.rings[j]) = (stage.raws[j], stage.moved[j], stage.rings[j] as u8);
            }
        }
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
    pub(super) fn halo_pass(&self, points: &Points, kinds: &Kinds) -> Vec<f32> {
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
}
