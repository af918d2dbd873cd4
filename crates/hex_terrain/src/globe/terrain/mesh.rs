//! A globe's meshes: the fine triangles of some tiles, each point once, finished in parallel,
//! with its normal from the whole fan of triangles round it.

use std::collections::{HashMap, HashSet};

use rayon::prelude::*;

use super::super::fine::Point;
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
    /// The mesh of `tiles`: their fine triangles, their points once each, each normal from
    /// every triangle around its point (those of the tiles holding it, some beyond `tiles`),
    /// summed in the order of the triangles' keys.
    pub(super) fn mesh(&self, tiles: Vec<GlobeTile>, origin: [f64; 3]) -> GlobeMesh {
        let triangles: Vec<[Point; 3]> = tiles.iter().flat_map(|&t| self.fine.triangles(self.spot(t))).collect();
        let mut index: HashMap<u64, u32> = HashMap::with_capacity(triangles.len() / 2 + 2);
        let mut points: Vec<Point> = Vec::with_capacity(triangles.len() / 2 + 2);
        let mut indices = Vec::with_capacity(triangles.len() * 3);
        for t in &triangles {
            for &p in t {
                let next = points.len() as u32;
                let i = *index.entry(self.fine.id(p)).or_insert_with(|| {
                    points.push(p);
                    next
                });
                indices.push(i);
            }
        }
        // Every triangle around a point belongs to a tile holding it.
        let own: HashSet<GlobeTile> = tiles.iter().copied().collect();
        let mut halo: Vec<GlobeTile> = points
            .iter()
            .flat_map(|&p| self.fine.holders(p).tiles().iter().map(|&s| self.grid.id(s)).collect::<Vec<_>>())
            .filter(|t| !own.contains(t))
            .collect();
        halo.sort_unstable();
        halo.dedup();
        let around: Vec<[Point; 3]> =
            triangles.iter().copied().chain(halo.iter().flat_map(|&t| self.fine.triangles(self.spot(t)))).collect();
        let mut fans: Vec<Vec<usize>> = vec![Vec::new(); points.len()];
        for (k, t) in around.iter().enumerate() {
            for p in t {
                if let Some(&i) = index.get(&self.fine.id(*p)) {
                    fans[i as usize].push(k);
                }
            }
        }
        // Every point the fans reach, finished once, in parallel (each is a pure function of
        // the config and the point, so the threads change no bit).
        let mut slot: HashMap<u64, usize> = HashMap::with_capacity(points.len() * 2);
        let mut reached: Vec<Point> = Vec::with_capacity(points.len() * 2);
        for &p in around.iter().flatten() {
            slot.entry(self.fine.id(p)).or_insert_with(|| {
                reached.push(p);
                reached.len() - 1
            });
        }
        let finished: Vec<(f32, u32, TileKind, Dir)> = reached
            .par_iter()
            .map(|&p| {
                let (h, ring, kind) = self.finish(p);
                (h, ring, kind, self.position(p, h))
            })
            .collect();
        let at = |p: Point| finished[slot[&self.fine.id(p)]];
        let n = self.config.subdivisions() as f32;
        let vertices: Vec<(f32, u32, TileKind, Dir, Dir)> = points
            .par_iter()
            .zip(&fans)
            .map(|(&p, fan)| {
                let (h, ring, kind, pos) = at(p);
                let mut fan: Vec<([u64; 3], [Point; 3])> = fan
                    .iter()
                    .map(|&k| {
                        let t = around[k];
                        let key = self.fine.key(&t);
                        let first = t.iter().position(|&q| self.fine.id(q) == key[0]).unwrap_or(0);
                        (key, [t[first], t[(first + 1) % 3], t[(first + 2) % 3]])
                    })
                    .collect();
                fan.sort_unstable_by_key(|(key, _)| *key);
                fan.dedup_by_key(|(key, _)| *key);
                let mut normal = [0.0f64; 3];
                for (_, t) in &fan {
                    let [a, b, c] = t.map(|q| at(q).3);
                    let face = cross(sub(b, a), sub(c, a));
                    normal = [normal[0] + face[0], normal[1] + face[1], normal[2] + face[2]];
                }
                (h, ring, kind, pos, project::normalize(normal))
            })
            .collect();
        let mut buffers = MeshBuffers::default();
        let mut heights = Vec::with_capacity(points.len());
        for (h, ring, kind, pos, normal) in vertices {
            heights.push(h);
            buffers.positions.push([
                (pos[0] - origin[0]) as f32,
                (pos[1] - origin[1]) as f32,
                (pos[2] - origin[2]) as f32,
            ]);
            buffers.normals.push(normal.map(|c| c as f32));
            buffers.tile_kinds.push(kind as u32);
            buffers.center_distances.push(ring as f32 / n);
        }
        buffers.indices = indices;
        let points = points.iter().map(|&p| GlobePoint(self.fine.id(p))).collect();
        GlobeMesh { origin, buffers, points, heights, tiles }
    }
}
