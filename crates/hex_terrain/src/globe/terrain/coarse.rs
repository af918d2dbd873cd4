//! A globe mesh's far level of detail ([`GlobeMesh::coarse`]): each tile a fan of triangles from
//! its center to its corners, as a flat map's coarse chunk, the mesh's outline kept whole (every
//! point on an edge with a tile beyond the mesh), so a coarse chunk meets a full one without a
//! crack. Every vertex kept is the full mesh's, bit for bit.

use std::collections::HashMap;

use super::mesh::GlobeMesh;
use crate::globe::GlobeProp;
use crate::globe::project::{self, Dir, hit};
use crate::mesh::MeshBuffers;

impl GlobeMesh {
    /// The mesh drawn far away (see the module docs): `6` triangles a hexagon and `5` a pentagon
    /// inside the mesh (a tile on its outline keeps the points of its outer edges), its vertices
    /// the full mesh's centers, corners and outline points with all their attributes, the
    /// triangles counterclockwise seen from outside, each starting at its tile's center,
    /// [`GlobeMesh::triangle_tiles`] named.
    #[must_use]
    pub fn coarse(&self) -> GlobeMesh {
        let b = &self.buffers;
        let triangles = self.triangle_tiles.len();
        // How many tiles hold each vertex (a corner three, a point on an edge two, in the mesh),
        // and every directed edge of the mesh.
        let mut holders = vec![0u8; b.positions.len()];
        let mut last = vec![u32::MAX; b.positions.len()];
        let mut edges: HashMap<(u32, u32), ()> = HashMap::with_capacity(b.indices.len());
        for (k, t) in b.indices.chunks_exact(3).enumerate() {
            let tile = self.triangle_tiles[k].0;
            for i in 0..3 {
                let v = t[i] as usize;
                if last[v] != tile {
                    last[v] = tile;
                    holders[v] = holders[v].saturating_add(1);
                }
                edges.insert((t[i], t[(i + 1) % 3]), ());
            }
        }
        let mut keep = vec![u32::MAX; b.positions.len()];
        let mut out = Vec::new();
        let mut indices = Vec::new();
        let mut triangle_tiles = Vec::new();
        let mut start = 0;
        while start < triangles {
            let tile = self.triangle_tiles[start];
            let mut end = start;
            while end < triangles && self.triangle_tiles[end] == tile {
                end += 1;
            }
            let run = &b.indices[3 * start..3 * end];
            start = end;
            // The tile's outline: its directed edges whose reverse is not in the tile, in order
            // (counterclockwise seen from outside), from any of them.
            let inside: HashMap<(u32, u32), ()> =
                run.chunks_exact(3).flat_map(|t| (0..3).map(move |i| ((t[i], t[(i + 1) % 3]), ()))).collect();
            let next: HashMap<u32, u32> =
                inside.keys().filter(|&&(a, c)| !inside.contains_key(&(c, a))).map(|&(a, c)| (a, c)).collect();
            let center = run.iter().copied().find(|&v| b.center_distances[v as usize] == 0.0);
            let (Some(center), Some(&first)) = (center, next.keys().min()) else { continue };
            let mut cycle = vec![first];
            while let Some(&v) = next.get(cycle.last().expect("a point"))
                && v != first
                && cycle.len() <= next.len()
            {
                cycle.push(v);
            }
            // An edge on the mesh's outline: no tile of the mesh beyond it.
            let outline = |a: u32, c: u32| !edges.contains_key(&(c, a));
            let m = cycle.len();
            let kept: Vec<u32> = (0..m)
                .filter(|&k| {
                    let (before, v, after) = (cycle[(k + m - 1) % m], cycle[k], cycle[(k + 1) % m]);
                    holders[v as usize] >= 3 || outline(before, v) || outline(v, after)
                })
                .map(|k| cycle[k])
                .collect();
            let mut slot = |v: u32| {
                if keep[v as usize] == u32::MAX {
                    keep[v as usize] = out.len() as u32;
                    out.push(v);
                }
                keep[v as usize]
            };
            let c = slot(center);
            for k in 0..kept.len() {
                let (p, q) = (slot(kept[k]), slot(kept[(k + 1) % kept.len()]));
                indices.extend([c, p, q]);
                triangle_tiles.push(tile);
            }
        }
        let buffers = MeshBuffers {
            positions: select(&b.positions, &out),
            normals: select(&b.normals, &out),
            uvs: select(&b.uvs, &out),
            tile_kinds: select(&b.tile_kinds, &out),
            center_distances: select(&b.center_distances, &out),
            colors: select(&b.colors, &out),
            texture_layers: select(&b.texture_layers, &out),
            indices,
        };
        GlobeMesh {
            origin: self.origin,
            buffers,
            points: select(&self.points, &out),
            heights: select(&self.heights, &out),
            tiles: self.tiles.clone(),
            triangle_tiles,
        }
    }

    /// Moves props placed on a full mesh of the same tiles ([`GlobeTerrain::props`](crate::GlobeTerrain::props))
    /// along their up onto this mesh's surface (a coarse mesh's: the tile's own triangles); a
    /// prop whose tile this mesh lacks, or whose up misses them, stays where it is.
    pub fn stand_on(&self, props: &mut [GlobeProp]) {
        let b = &self.buffers;
        let from: Dir = self.origin.map(|c| -c);
        let corner = |v: u32| b.positions[v as usize].map(f64::from);
        let mut runs: HashMap<u32, (usize, usize)> = HashMap::new();
        for (k, t) in self.triangle_tiles.iter().enumerate() {
            runs.entry(t.0).and_modify(|r| r.1 = k + 1).or_insert((k, k + 1));
        }
        for p in props {
            let Some(&(s, e)) = runs.get(&p.tile.0) else { continue };
            let d = project::normalize(p.up.map(f64::from));
            let met = b.indices[3 * s..3 * e]
                .chunks_exact(3)
                .find_map(|t| hit(from, d, corner(t[0]), corner(t[1]), corner(t[2])).filter(|&t| t > 0.0));
            if let Some(t) = met {
                p.position = [0, 1, 2].map(|k| (from[k] + d[k] * t) as f32);
            }
        }
    }
}

/// The values of the vertices `kept` (none of an empty attribute).
fn select<T: Copy>(from: &[T], kept: &[u32]) -> Vec<T> {
    if from.is_empty() {
        return Vec::new();
    }
    kept.iter().map(|&v| from[v as usize]).collect()
}
