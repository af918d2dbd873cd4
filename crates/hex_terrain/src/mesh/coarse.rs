//! Level of detail: a chunk's mesh with fewer triangles for chunks seen from afar.
//!
//! [`Detail::Coarse`] draws each tile as a fan of triangles from its center to its border: inside
//! the chunk a tile edge is one segment between two corners (six triangles a tile instead of
//! `6n²`), while on the chunk's outline every lattice point of the full mesh stays. So:
//!
//! - every vertex of the coarse mesh is a vertex of the full mesh, with the same bits in every
//!   attribute but the color: whatever holds of a vertex (its tile type's height range, the
//!   seams, chunked = whole) holds of the coarse mesh. Each tile's fan has its own copies of its
//!   border's vertices, colored with the tile's own biome color (the full mesh's border vertices
//!   average the colors of the tiles around them, which a fan would smear over the whole tile)
//!   and keeping their own water;
//! - the coarse mesh's outline is the full mesh's, point for point, so two neighboring chunks
//!   meet without a crack whatever level each is drawn at (no skirt needed);
//! - the tile is still one colored hexagon: its center at its type's height, its corners on the
//!   thresholds, the distance to the center 0 in the middle and 1 on the edges, where the
//!   shader draws outlines, borders and fog from the world position as at full detail.

use std::collections::HashMap;

use hexx::Hex;

use super::{ChunkMesh, Diagnostics, MeshBuffers};
use crate::chunk::TileRect;
use crate::geometry::Geometry;

/// How finely a chunk is meshed ([`Terrain::generate_detail`](crate::Terrain::generate_detail)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum Detail {
    /// Every lattice point: `6n²` triangles a tile.
    #[default]
    Full,
    /// A fan of six triangles a tile from its center to its corners, the chunk's outline kept
    /// whole (see the module docs): for chunks far from every camera.
    Coarse,
}

/// The border of `tile`'s fan in a coarse mesh of `rect`, as lattice points in ring order: its
/// six corners, and on an edge shared with a tile outside `rect` (the chunk's outline) every
/// lattice point of the edge, so the outline stays the full mesh's. `n` is the lattice's
/// subdivisions.
pub(crate) fn fan_border(geometry: &Geometry, rect: TileRect, tile: Hex) -> Vec<Hex> {
    let lattice = geometry.lattice();
    let n = lattice.subdivisions() as usize;
    let center = lattice.tile_center(tile);
    // The border of a tile, as offsets from its center in ring order: a corner every `n` points.
    let ring: Vec<Hex> = Hex::ZERO.ring(n as u32).collect();
    let mut border = Vec::with_capacity(ring.len());
    for edge in 0..6 {
        // The tile across this edge, from a point inside the edge (n >= 2, so there is one).
        let inner = center + ring[edge * n + 1];
        let across = lattice.tiles_at(inner).tiles().iter().copied().find(|&t| t != tile);
        let inside = across.is_some_and(|t| rect.contains(geometry.offset_of(t)));
        let step = if inside { n } else { 1 };
        border.extend((0..n).step_by(step).map(|k| center + ring[edge * n + k]));
    }
    border
}

/// The coarse mesh of `full`, which must have been generated with diagnostics (its vertices'
/// lattice coordinates); the coarse mesh keeps diagnostics only if `keep_diagnostics`. `None`
/// when `full` has no diagnostics.
pub(crate) fn coarsen(geometry: &Geometry, full: &ChunkMesh, keep_diagnostics: bool) -> Option<ChunkMesh> {
    let diagnostics = full.diagnostics.as_ref()?;
    let lattice = geometry.lattice();
    let index: HashMap<Hex, u32> = diagnostics.lattice.iter().enumerate().map(|(i, &p)| (p, i as u32)).collect();
    let buffers = &full.buffers;
    // Which way the full mesh winds its faces (up seen from above), to wind the fans alike.
    let up = |t: [u32; 3]| {
        let [a, b, c] = t.map(|i| buffers.positions[i as usize]);
        (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]) > 0.0
    };
    let full_up = buffers.indices.get(..3).is_none_or(|t| up([t[0], t[1], t[2]]));
    // Each tile's fan has vertices of its own: a copy of the full mesh's vertex at each point,
    // with, on a map with vertex colors, the tile's own biome color (the full mesh's border
    // vertices average the colors of the tiles around them, which a fan would smear over the
    // whole tile) and the point's own water.
    let mut kept: Vec<(usize, Option<[u8; 4]>)> = Vec::with_capacity(full.tiles.len() * 8);
    let mut indices: Vec<u32> = Vec::with_capacity(full.tiles.len() * 24);
    let mut polygon: Vec<u32> = Vec::new();
    for info in &full.tiles {
        let Some(&middle) = index.get(&lattice.tile_center(info.hex)) else { continue };
        let own = buffers.colors.get(middle as usize).copied();
        let first = kept.len() as u32;
        kept.push((middle as usize, None));
        polygon.clear();
        for p in fan_border(geometry, full.rect, info.hex) {
            let Some(&v) = index.get(&p) else { continue };
            let color = own.map(|[r, g, b, _]| [r, g, b, buffers.colors[v as usize][3]]);
            polygon.push(kept.len() as u32);
            kept.push((v as usize, color));
        }
        for k in 0..polygon.len() {
            let t = [first, polygon[k], polygon[(k + 1) % polygon.len()]];
            let source = t.map(|i| kept[i as usize].0 as u32);
            indices.extend(if up(source) == full_up { t } else { [t[0], t[2], t[1]] });
        }
    }
    let colors = if buffers.colors.is_empty() {
        Vec::new()
    } else {
        kept.iter().map(|&(i, own)| own.unwrap_or(buffers.colors[i])).collect()
    };
    // A fan's vertices are its tile's alone: every entry its own layer (the middle's own).
    let texture_layers = if buffers.texture_layers.is_empty() {
        Vec::new()
    } else {
        let mut middle = [0; 3];
        kept.iter()
            .map(|&(i, own)| {
                if own.is_none() {
                    middle = buffers.texture_layers[i];
                }
                middle
            })
            .collect()
    };
    let kept: Vec<usize> = kept.into_iter().map(|(i, _)| i).collect();
    let buffers = MeshBuffers {
        positions: kept.iter().map(|&i| buffers.positions[i]).collect(),
        normals: kept.iter().map(|&i| buffers.normals[i]).collect(),
        uvs: kept.iter().map(|&i| buffers.uvs[i]).collect(),
        tile_kinds: kept.iter().map(|&i| buffers.tile_kinds[i]).collect(),
        center_distances: kept.iter().map(|&i| buffers.center_distances[i]).collect(),
        colors,
        texture_layers,
        indices,
    };
    let diagnostics = keep_diagnostics.then(|| Diagnostics {
        lattice: kept.iter().map(|&i| diagnostics.lattice[i]).collect(),
        raw_heights: kept.iter().map(|&i| diagnostics.raw_heights[i]).collect(),
        moved: kept.iter().map(|&i| diagnostics.moved[i]).collect(),
        rings: kept.iter().map(|&i| diagnostics.rings[i]).collect(),
    });
    Some(ChunkMesh { rect: full.rect, origin: full.origin, buffers, tiles: full.tiles.clone(), diagnostics })
}
