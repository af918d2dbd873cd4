//! A globe's meshes: the fine triangles of some tiles, each point once, finished in parallel,
//! with its normal from the whole fan of triangles round it.

use std::collections::HashMap;

use rayon::prelude::*;

use super::super::fine::{Fan, Fine, Point};
use super::super::project::{self, Dir, cross, sub};
use super::GlobeTerrain;
use crate::globe::GlobeTile;
use crate::kind::TileKind;
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
    /// a border the highest of the tiles holding it), rings over `n` in `center_distances`, and
    /// the triangles, counterclockwise seen from outside. No texture coordinates and no colors
    /// yet (a globe has no climate yet).
    pub buffers: MeshBuffers,
    /// Each vertex's point.
    pub points: Vec<GlobePoint>,
    /// Each vertex's normalised height after manipulation.
    pub heights: Vec<f32>,
    /// Its tiles.
    pub tiles: Vec<GlobeTile>,
}

impl GlobeTerrain {
    /// The mesh of `tiles`: their fine triangles and their points once each, every point
    /// finished once (in parallel), each normal the sum of the faces round its point going round
    /// it from its first step (in its hexagon's template for a point inside a hexagon, else in
    /// its owner's frame: the same bits in any chunk). The faces of the tiles beyond `tiles` come
    /// from the ring of points around the mesh.
    pub(super) fn mesh(&self, tiles: Vec<GlobeTile>, origin: [f64; 3]) -> GlobeMesh {
        let fine = &self.fine;
        let (cells, cell_triangles) = fine.template();
        let n = self.config.subdivisions();
        let estimate = tiles.len() * cells.len();
        let mut slots = Slots::new(fine, estimate + estimate / 4);
        let mut indices = Vec::with_capacity(tiles.len() * cell_triangles.len() * 3);
        let mut local = Vec::with_capacity(cells.len());
        // Each mesh point's ring of neighbors (by slot), as far as known.
        let mut rings: Vec<Option<[u32; 6]>> = Vec::with_capacity(estimate);
        for &t in &tiles {
            let spot = self.spot(t);
            if let Some((d, ci, cj)) = fine.hexagon(spot) {
                let kind = self.kinds[t.0 as usize];
                local.clear();
                for c in cells {
                    let p = fine.hexagon_point(d, ci + c.offset.0, cj + c.offset.1);
                    // A point inside the hexagon is its alone: its ring and kind are known.
                    let known = (c.ring < n).then_some((c.ring, kind));
                    local.push(slots.intern(p, known));
                }
                rings.resize(slots.points.len(), None);
                for (c, &slot) in cells.iter().zip(&local) {
                    if let Some(fan) = c.fan {
                        rings[slot as usize] = Some(fan.map(|k| local[usize::from(k)]));
                    }
                }
                indices.extend(cell_triangles.iter().flat_map(|t| t.map(|k| local[usize::from(k)])));
            } else {
                for triangle in fine.triangles(spot) {
                    indices.extend(triangle.map(|p| slots.intern(p, None)));
                }
            }
        }
        let count = slots.points.len();
        rings.resize(count, None);
        // The other points' fans in their owners' frames, reaching the ring of points just
        // beyond the mesh.
        let pending: Vec<usize> = (0..count).filter(|&i| rings[i].is_none()).collect();
        let fans: Vec<Fan> = pending.par_iter().map(|&i| fine.fan(slots.points[i])).collect();
        let mut pentagons: Vec<(usize, [u32; 5])> = Vec::new();
        for (&i, fan) in pending.iter().zip(&fans) {
            let mut ring = [0; 6];
            for (r, &q) in ring.iter_mut().zip(fan.points()) {
                *r = slots.intern(q, None);
            }
            match fan.points().len() {
                6 => rings[i] = Some(ring),
                _ => pentagons.push((i, [ring[0], ring[1], ring[2], ring[3], ring[4]])),
            }
        }
        // Each point is a pure function of the config and the point: the threads change no bit.
        let finished: Vec<(f32, u32, TileKind, Dir)> =
            slots.points.par_iter().zip(&slots.known).map(|(&p, &known)| self.finish(p, known)).collect();
        let normal = |i: usize, ring: &[u32]| {
            let a = finished[i].3;
            let mut normal = [0.0f64; 3];
            for (k, &this) in ring.iter().enumerate() {
                // The ring goes round clockwise seen from outside: (a, next, this) is
                // counterclockwise.
                let next = ring[(k + 1) % ring.len()];
                let face = cross(sub(finished[next as usize].3, a), sub(finished[this as usize].3, a));
                normal = [normal[0] + face[0], normal[1] + face[1], normal[2] + face[2]];
            }
            project::normalize(normal).map(|c| c as f32)
        };
        let mut normals: Vec<[f32; 3]> =
            rings.par_iter().enumerate().map(|(i, ring)| ring.map_or([0.0; 3], |ring| normal(i, &ring))).collect();
        for (i, ring) in pentagons {
            normals[i] = normal(i, &ring);
        }
        let rings_per = n as f32;
        let mut buffers = MeshBuffers::default();
        let mut heights = Vec::with_capacity(count);
        for (&(h, ring, kind, pos), normal) in finished[..count].iter().zip(normals) {
            heights.push(h);
            buffers.positions.push([
                (pos[0] - origin[0]) as f32,
                (pos[1] - origin[1]) as f32,
                (pos[2] - origin[2]) as f32,
            ]);
            buffers.normals.push(normal);
            buffers.tile_kinds.push(kind as u32);
            buffers.center_distances.push(ring as f32 / rings_per);
        }
        buffers.indices = indices;
        let points = slots.points[..count].iter().map(|&p| GlobePoint(fine.id(p))).collect();
        GlobeMesh { origin, buffers, points, heights, tiles }
    }
}

/// Points by id, each once, in the order first met, with what is known of them beforehand.
struct Slots<'a> {
    fine: &'a Fine,
    index: Index,
    points: Vec<Point>,
    known: Vec<Option<(u32, TileKind)>>,
}

/// Slots by point id: a table over every id when the mesh holds a good part of the globe (one
/// read a point), else a hash map of the few the mesh holds.
enum Index {
    Dense(Vec<u32>),
    Sparse(HashMap<u64, u32, foldhash::fast::FixedState>),
}

impl<'a> Slots<'a> {
    fn new(fine: &'a Fine, capacity: usize) -> Self {
        let ids = fine.id_count();
        let index = if capacity as u64 * 8 >= ids {
            Index::Dense(vec![u32::MAX; ids as usize])
        } else {
            Index::Sparse(HashMap::with_capacity_and_hasher(capacity, Default::default()))
        };
        Self { fine, index, points: Vec::with_capacity(capacity), known: Vec::with_capacity(capacity) }
    }

    /// The point's slot, given it now if it has none.
    fn intern(&mut self, p: Point, known: Option<(u32, TileKind)>) -> u32 {
        let next = self.points.len() as u32;
        let id = self.fine.id(p);
        let slot = match &mut self.index {
            Index::Dense(table) => {
                let slot = &mut table[id as usize];
                if *slot == u32::MAX {
                    *slot = next;
                }
                *slot
            }
            Index::Sparse(map) => *map.entry(id).or_insert(next),
        };
        if slot == next {
            self.points.push(p);
            self.known.push(known);
        }
        slot
    }
}
