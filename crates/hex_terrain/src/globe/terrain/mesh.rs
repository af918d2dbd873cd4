//! A globe's meshes: the fine triangles of some tiles, each point once, finished in parallel,
//! with its normal from the whole fan of triangles round it.

use std::collections::HashMap;

use rayon::prelude::*;

use super::super::atlas::Spot;
use super::super::fine::{Fan, Fine, Point};
use super::super::project::{self, Dir, cross};
use super::{Finished, GlobeTerrain};
use crate::globe::GlobeTile;
use crate::heights::fbm::LANES;
use crate::mesh::MeshBuffers;

/// A point of a globe's fine lattice (a vertex of its meshes): a dense id, the same in every
/// chunk that holds the point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct GlobePoint(pub u64);

/// The mesh of a chunk of a globe, or of the whole globe.
#[derive(Debug, Clone, PartialEq)]
pub struct GlobeMesh {
    /// Where its positions are measured from: the first tile's center on the sphere of
    /// [`GlobeTerrain::radius`] (the globe's center for the whole globe), in world units.
    pub origin: [f64; 3],
    /// Positions (relative to `origin`), unit normals (outward, each the normalised sum of the
    /// fine triangles around its point, the same whichever chunk holds it), the tile kinds (on
    /// a border the highest of the tiles holding it), rings over `n` in `center_distances`, on
    /// a globe with a climate the colors (the biome colors of the tiles holding the point
    /// averaged, alpha 0: no water), and the triangles, counterclockwise seen from outside. No
    /// texture coordinates yet.
    pub buffers: MeshBuffers,
    /// Each vertex's point.
    pub points: Vec<GlobePoint>,
    /// Each vertex's normalised height after manipulation.
    pub heights: Vec<f32>,
    /// Its tiles.
    pub tiles: Vec<GlobeTile>,
    /// The tile each triangle lies in (triangle `k` is `indices[3 k..3 k + 3]`): a tile's
    /// triangles are all in it, so a point on a border is in the triangles of every tile holding
    /// it.
    pub triangle_tiles: Vec<GlobeTile>,
}

/// A mesh before its points are finished: its points once each, the order they were met in
/// (the mesh's own first, then the ring of points just beyond it that their fans reach), what is
/// known of each, where each point's fan is found, and the triangles.
pub(super) struct Layout {
    pub(super) tiles: Vec<GlobeTile>,
    points: Vec<Point>,
    known: Vec<Option<(u32, GlobeTile)>>,
    /// How many of `points` are the mesh's own (the rest are the ring beyond them).
    count: usize,
    /// Each tile's points' slots, cell by cell (a pentagon's `NOT_INSIDE`).
    locals: Vec<u32>,
    /// Where each mesh point's fan is found: its cell in `locals` (a point inside a hexagon),
    /// or `NOT_INSIDE - 1 - k` for `rings[k]`.
    home: Vec<u32>,
    rings: Vec<([u32; 6], u8)>,
    pub(super) indices: Vec<u32>,
    pub(super) triangle_tiles: Vec<GlobeTile>,
}

impl Layout {
    /// The mesh's own points (the ring beyond them left out).
    pub(super) fn len(&self) -> usize {
        self.count
    }
}

/// Where some finished points go as vertices: a slice of each vertex buffer but the normals, as
/// long as the points written (the colors empty on a globe without a climate).
pub(super) struct Vertices<'a> {
    pub(super) positions: &'a mut [[f32; 3]],
    pub(super) kinds: &'a mut [u32],
    pub(super) distances: &'a mut [f32],
    pub(super) colors: &'a mut [[u8; 4]],
    pub(super) points: &'a mut [GlobePoint],
    pub(super) heights: &'a mut [f32],
}

impl Vertices<'_> {
    /// Vertex `w`: the finished point `f`, its position measured from `origin`, its ring over
    /// the `n` steps from a tile's center to its corner.
    pub(super) fn set(&mut self, w: usize, f: &Finished, point: GlobePoint, origin: [f64; 3], n: u32) {
        let a = f.position;
        self.positions[w] = [(a[0] - origin[0]) as f32, (a[1] - origin[1]) as f32, (a[2] - origin[2]) as f32];
        self.kinds[w] = f.kind as u32;
        self.distances[w] = f.ring as f32 / n as f32;
        if let (Some(c), Some(color)) = (self.colors.get_mut(w), f.color) {
            *c = color;
        }
        self.points[w] = point;
        self.heights[w] = f.height;
    }
}

impl GlobeTerrain {
    /// The mesh of `tiles`: their fine triangles and their points once each, every point
    /// finished once (in parallel), each normal the sum of the faces round its point going round
    /// it from its first step (in its hexagon's template for a point inside a hexagon, else in
    /// its owner's frame: the same bits in any chunk). The faces of the tiles beyond `tiles` come
    /// from the ring of points around the mesh.
    pub(super) fn mesh(&self, tiles: Vec<GlobeTile>, origin: [f64; 3]) -> GlobeMesh {
        let layout = self.layout(tiles);
        let all = self.finish_layout(&layout);
        let count = layout.len();
        let mut buffers = MeshBuffers {
            positions: vec![[0.0; 3]; count],
            normals: vec![[0.0; 3]; count],
            tile_kinds: vec![0; count],
            center_distances: vec![0.0; count],
            colors: vec![[0; 4]; if self.config.climate.enabled { count } else { 0 }],
            ..MeshBuffers::default()
        };
        let mut points = vec![GlobePoint(0); count];
        let mut heights = vec![0.0; count];
        let every: Vec<u32> = (0..count as u32).collect();
        let out = Vertices {
            positions: &mut buffers.positions,
            kinds: &mut buffers.tile_kinds,
            distances: &mut buffers.center_distances,
            colors: &mut buffers.colors,
            points: &mut points,
            heights: &mut heights,
        };
        self.write_vertices(&layout, &all, &every, origin, out, &mut buffers.normals);
        buffers.indices = layout.indices;
        GlobeMesh { origin, buffers, points, heights, tiles: layout.tiles, triangle_tiles: layout.triangle_tiles }
    }

    /// Writes the layout's points `which` (finished in `all`, with the ring beyond them) into
    /// `out` and `normals` as vertices, in that order, their positions measured from `origin`.
    pub(super) fn write_vertices(
        &self,
        layout: &Layout,
        all: &[Finished],
        which: &[u32],
        origin: [f64; 3],
        mut out: Vertices<'_>,
        normals: &mut [[f32; 3]],
    ) {
        let mut sums = Vec::with_capacity(which.len());
        for (w, &v) in which.iter().enumerate() {
            let v = v as usize;
            out.set(w, &all[v], GlobePoint(self.fine.id(layout.points[v])), origin, self.config.subdivisions());
            sums.push(self.face_sum(layout, all, v));
        }
        normalize_all(&sums, normals);
    }

    /// The points and triangles of `tiles`, each point once, and where each point's fan is.
    pub(super) fn layout(&self, tiles: Vec<GlobeTile>) -> Layout {
        let fine = &self.fine;
        let (cells, cell_triangles) = fine.template();
        let n = self.config.subdivisions();
        let per = cells.len();
        let spots = tiles.iter().map(|&t| self.spot(t));
        let mut slots = Slots::new(fine, spots, tiles.len() * per + tiles.len() * per / 4);
        let mut indices = Vec::with_capacity(tiles.len() * cell_triangles.len() * 3);
        let mut triangle_tiles = Vec::with_capacity(tiles.len() * cell_triangles.len());
        let mut locals: Vec<u32> = Vec::with_capacity(tiles.len() * per);
        let mut home: Vec<u32> = Vec::with_capacity(tiles.len() * per);
        for &t in &tiles {
            if let Some((d, ci, cj)) = fine.hexagon(self.spot(t)) {
                let base = locals.len();
                for c in cells {
                    let p = fine.hexagon_point(d, ci + c.offset.0, cj + c.offset.1);
                    // A point inside the hexagon is its alone: its ring and tile are known.
                    let known = (c.ring < n).then_some((c.ring, t));
                    let slot = slots.intern(p, known);
                    if slot as usize == home.len() {
                        home.push(if c.fan.is_some() { locals.len() as u32 } else { NOT_INSIDE });
                    }
                    locals.push(slot);
                }
                let local = &locals[base..];
                for triangle in cell_triangles {
                    indices.extend_from_slice(&triangle.map(|k| local[usize::from(k)]));
                }
                triangle_tiles.extend(std::iter::repeat_n(t, cell_triangles.len()));
            } else {
                locals.extend(std::iter::repeat_n(NOT_INSIDE, per));
                for triangle in fine.triangles(self.spot(t)) {
                    indices.extend_from_slice(&triangle.map(|p| slots.intern(p, None)));
                    triangle_tiles.push(t);
                }
                home.resize(slots.points.len(), NOT_INSIDE);
            }
        }
        let count = slots.points.len();
        // The other points' fans in their owners' frames, reaching the ring of points just
        // beyond the mesh.
        let pending: Vec<usize> = (0..count).filter(|&i| home[i] == NOT_INSIDE).collect();
        let fans: Vec<Fan> = pending.par_iter().map(|&i| fine.fan(slots.points[i])).collect();
        let mut rings: Vec<([u32; 6], u8)> = Vec::with_capacity(fans.len());
        for (&i, fan) in pending.iter().zip(&fans) {
            let mut ring = [0; 6];
            for (r, &q) in ring.iter_mut().zip(fan.points()) {
                *r = slots.intern(q, None);
            }
            home[i] = NOT_INSIDE - 1 - rings.len() as u32;
            rings.push((ring, fan.points().len() as u8));
        }
        let (points, known) = slots.into_points();
        Layout { tiles, points, known, count, locals, home, rings, indices, triangle_tiles }
    }

    /// Every point of a layout finished, the ring beyond its own points too. Each is a pure
    /// function of the config and the point: the threads change no bit.
    pub(super) fn finish_layout(&self, layout: &Layout) -> Vec<Finished> {
        let mut all = vec![Finished::UNSET; layout.points.len()];
        all.par_chunks_mut(LANES).zip(layout.points.par_chunks(LANES)).zip(layout.known.par_chunks(LANES)).for_each(
            |((out, points), known)| {
                for (o, f) in out.iter_mut().zip(self.finish_batch(points, known)) {
                    *o = f;
                }
            },
        );
        all
    }

    /// The faces round the layout's point `i` summed going round its fan: its normal before
    /// [`normalize_all`].
    pub(super) fn face_sum(&self, layout: &Layout, all: &[Finished], i: usize) -> [f64; 3] {
        let (cells, _) = self.fine.template();
        let per = cells.len();
        let mut ring = [0; 6];
        let len = match layout.home[i] {
            at if at < NOT_INSIDE - layout.rings.len() as u32 => {
                let (tile, cell) = (at as usize / per, at as usize % per);
                let fan = cells[cell].fan.expect("a point inside its hexagon");
                for (r, k) in ring.iter_mut().zip(fan) {
                    *r = layout.locals[tile * per + usize::from(k)];
                }
                6
            }
            at => {
                let (r, len) = layout.rings[(NOT_INSIDE - 1 - at) as usize];
                ring = r;
                usize::from(len)
            }
        };
        let around = ring.map(|r| all[r as usize].position.map(|c| c as f32));
        sum_faces(&around[..len])
    }
}

/// The faces between a point and each two points after each other of its ring (going round it
/// clockwise seen from outside, from its first step) summed: its normal before
/// [`normalize_all`]. The ring's positions are the whole globe's vertices (the world positions
/// rounded to f32, which the whole mesh holds and a chunk's mesh rounds the same way), so the
/// normal is that of the surface drawn, and the whole globe's mesh needs no other copy of them.
/// A face `(center, next, this)` is `(next - center) x (this - center)`; round a closed ring the
/// terms with the center cancel, so the sum is that of `next x this` alone, in f64 (the
/// cancellation between terms about the globe's radius times a fine step long leaves it exact
/// far beyond an f32 normal's bits).
pub(super) fn sum_faces(ring: &[[f32; 3]]) -> Dir {
    let mut normal = [0.0f64; 3];
    for (k, &this) in ring.iter().enumerate() {
        let next = ring[(k + 1) % ring.len()];
        let face = cross(next.map(f64::from), this.map(f64::from));
        normal = [normal[0] + face[0], normal[1] + face[1], normal[2] + face[2]];
    }
    normal
}

/// Each sum of faces normalised into `normals`: one loop over many, which the compiler
/// vectorizes, where a normal at a time waits on each square root and division.
pub(super) fn normalize_all(sums: &[[f64; 3]], normals: &mut [[f32; 3]]) {
    for (n, &s) in normals.iter_mut().zip(sums) {
        *n = project::normalize(s).map(|c| c as f32);
    }
}

/// A mesh point whose ring is not in its hexagon's template (on a border, or a pentagon's).
const NOT_INSIDE: u32 = u32::MAX;

/// Points by id, each once, in the order first met, with what is known of them beforehand.
struct Slots<'a> {
    fine: &'a Fine,
    /// The mesh's box in its diamond's frame, if it has one, and its points' slots.
    frame: Option<Frame>,
    table: Stamped,
    /// The slots of the points beyond the box (across a diamond edge, or all a pole's).
    others: HashMap<u64, u32, foldhash::fast::FixedState>,
    points: Vec<Point>,
    known: Vec<Option<(u32, GlobeTile)>>,
}

/// The rectangle of a diamond's frame that holds a mesh's points there and the ring beyond them,
/// each point at `(i - i0) row + (j - j0) / 3` (a row's points are every third `j`).
#[derive(Debug, Clone, Copy)]
struct Frame {
    d: u8,
    i0: u32,
    j0: u32,
    rows: u32,
    columns: u32,
    row: usize,
}

/// At most this many entries in a mesh's box (8 bytes each: 32 MiB); a bigger mesh's points
/// all go to the hash map.
const MAX_BOX: usize = 1 << 22;

/// A thread's table of slots by place in a mesh's box, each entry `(stamp, slot)`: reused by
/// the meshes the thread makes (an entry is this mesh's when it bears the mesh's stamp, so
/// nothing is cleared between meshes), so it stays in the core's cache.
#[derive(Default)]
struct Stamped {
    stamp: u32,
    entries: Vec<(u32, u32)>,
}

thread_local! {
    /// The table the thread's last mesh used, lent to the next one.
    static TABLE: std::cell::Cell<Stamped> = std::cell::Cell::new(Stamped::default());
}

impl<'a> Slots<'a> {
    /// Slots for the points of `tiles` (and the ring beyond them), about `capacity` of them.
    fn new(fine: &'a Fine, tiles: impl Iterator<Item = Spot>, capacity: usize) -> Self {
        let frame = Self::frame(fine, tiles);
        let mut table = TABLE.with(std::cell::Cell::take);
        if let Some(f) = frame {
            let len = f.rows as usize * f.row;
            if table.entries.len() < len {
                table.entries.resize(len, (0, 0));
            }
        }
        table.stamp = table.stamp.wrapping_add(1);
        if table.stamp == 0 {
            // After 2^32 meshes on a thread, stamps come round again: forget the old ones.
            table.entries.fill((0, 0));
            table.stamp = 1;
        }
        Self {
            fine,
            frame,
            table,
            others: HashMap::with_capacity_and_hasher(
                if frame.is_some() { capacity / 8 } else { capacity },
                Default::default(),
            ),
            points: Vec::with_capacity(capacity),
            known: Vec::with_capacity(capacity),
        }
    }

    /// The box of the tiles' diamond that holds their points and the fans' ring beyond them,
    /// clipped to the diamond; `None` for tiles of several diamonds or a pole.
    fn frame(fine: &Fine, mut tiles: impl Iterator<Item = Spot>) -> Option<Frame> {
        let Some(Spot::Diamond { d, i, j }) = tiles.next() else { return None };
        let (mut lo, mut hi) = ((i, j), (i, j));
        for spot in tiles {
            let Spot::Diamond { d: e, i, j } = spot else { return None };
            if e != d {
                return None;
            }
            lo = (lo.0.min(i), lo.1.min(j));
            hi = (hi.0.max(i), hi.1.max(j));
        }
        // A tile's points lie within 2 n of its center in the frame, the fans' ring 2 further.
        let (m, reach, big) = (i64::from(3 * fine.n()), i64::from(2 * fine.n() + 2), i64::from(fine.big()));
        let clip = |v: i64| v.clamp(0, big - 1) as u32;
        let (i0, i1) = (clip(i64::from(lo.0) * m - reach), clip(i64::from(hi.0) * m + reach));
        let (j0, j1) = (clip(i64::from(lo.1) * m - reach), clip(i64::from(hi.1) * m + reach));
        let (rows, columns) = (i1 - i0 + 1, j1 - j0 + 1);
        let row = columns as usize / 3 + 1;
        (rows as usize * row <= MAX_BOX).then_some(Frame { d, i0, j0, rows, columns, row })
    }

    /// The points in slot order, and what is known of them.
    fn into_points(mut self) -> (Vec<Point>, Vec<Option<(u32, GlobeTile)>>) {
        (std::mem::take(&mut self.points), std::mem::take(&mut self.known))
    }

    /// The point's slot, given it now if it has none.
    fn intern(&mut self, p: Point, known: Option<(u32, GlobeTile)>) -> u32 {
        let next = self.points.len() as u32;
        let boxed = match (p, self.frame) {
            (Spot::Diamond { d, i, j }, Some(f))
                if d == f.d && i.wrapping_sub(f.i0) < f.rows && j.wrapping_sub(f.j0) < f.columns =>
            {
                Some((i - f.i0) as usize * f.row + (j - f.j0) as usize / 3)
            }
            _ => None,
        };
        let slot = match boxed {
            Some(at) => {
                let entry = &mut self.table.entries[at];
                if entry.0 != self.table.stamp {
                    *entry = (self.table.stamp, next);
                }
                entry.1
            }
            None => *self.others.entry(self.fine.id(p)).or_insert(next),
        };
        if slot == next {
            self.points.push(p);
            self.known.push(known);
        }
        slot
    }
}

impl Drop for Slots<'_> {
    fn drop(&mut self) {
        TABLE.with(|t| t.set(std::mem::take(&mut self.table)));
    }
}
