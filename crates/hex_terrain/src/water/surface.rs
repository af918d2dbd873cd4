//! The water surface, the last stage of a chunk's water: over a generated chunk, a separate mesh at sea level over the sea, and
//! over river channels and lakes a sheet a little above their carved beds, with the depth of
//! water below each vertex, from which a renderer colors shallows and deeps and draws the shore.
//!
//! It is built from the chunk's own triangles, so it is exactly as seamless, deterministic and
//! chunk-independent as the terrain: a triangle with a vertex below sea level becomes a flat
//! triangle at sea level (its depth, sea level minus the floor, interpolated across it, is 0
//! exactly where the floor crosses sea level: the coastline), a wet triangle above the sea
//! (river or lake) a sheet that follows the floor, raised by the water cover at each vertex
//! times the river depth (so it meets dry banks at depth 0). Dry triangles make nothing.

use crate::mesh::MeshBuffers;

/// The water surface of a chunk, positions relative to the chunk's origin like its terrain.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct WaterBuffers {
    /// Vertex positions `[x, y, z]` on the water surface.
    pub positions: Vec<[f32; 3]>,
    /// Unit normals of the undisturbed surface (straight up on the sea).
    pub normals: Vec<[f32; 3]>,
    /// The terrain's world-space texture coordinates at each vertex (for animated waves).
    pub uvs: Vec<[f32; 2]>,
    /// Depth of water at each vertex: surface minus floor, in world units. Negative where the
    /// floor rises above a flat sea triangle's surface (the land side of a coast), so that the
    /// interpolated depth crosses 0 on the shoreline.
    pub depths: Vec<f32>,
    /// Triangle list indices.
    pub indices: Vec<u32>,
}

impl WaterBuffers {
    /// Whether there is no water.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.indices.is_empty()
    }

    /// Number of triangles.
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }
}

/// Which surface a water vertex belongs to: its triangle's flat sea level, or the river sheet.
#[derive(Clone, Copy)]
enum Surface {
    Sea,
    River,
}

/// The water surface over a chunk's buffers (see the module docs), with the sea at `sea_level`
/// and river and lake water `river_depth` over a fully covered vertex, in world units. Empty
/// for a dry chunk.
#[must_use]
pub fn water_surface(b: &MeshBuffers, sea_level: f32, river_depth: f32) -> WaterBuffers {
    let cover = |i: usize| b.colors.get(i).map_or(0.0, |c| f32::from(c[3]) / 255.0);
    let mut out = WaterBuffers::default();
    // Output index of each input vertex on each surface, `u32::MAX` before it is used.
    let mut index = [vec![u32::MAX; b.positions.len()], vec![u32::MAX; b.positions.len()]];
    for tri in b.indices.chunks_exact(3) {
        let below = tri.iter().any(|&i| b.positions[i as usize][1] < sea_level);
        let surface = if below {
            Surface::Sea
        } else if river_depth > 0.0 && tri.iter().any(|&i| cover(i as usize) > 0.0) {
            Surface::River
        } else {
            continue;
        };
        for &i in tri {
            let i = i as usize;
            let slot = &mut index[surface as usize][i];
            if *slot == u32::MAX {
                *slot = out.positions.len() as u32;
                let [x, y, z] = b.positions[i];
                let (top, normal) = match surface {
                    Surface::Sea => (sea_level, [0.0, 1.0, 0.0]),
                    Surface::River => (y + cover(i) * river_depth, b.normals[i]),
                };
                out.positions.push([x, top, z]);
                out.normals.push(normal);
                out.uvs.push(b.uvs[i]);
                out.depths.push(top - y);
            }
            out.indices.push(*slot);
        }
    }
    out
}
