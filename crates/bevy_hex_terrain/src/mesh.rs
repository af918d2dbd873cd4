//! Core mesh buffers to Bevy meshes.

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, MeshVertexAttribute, PrimitiveTopology, VertexFormat};
use bevy::prelude::*;
use hex_terrain::{ChunkMesh, Terrain};

/// Per-vertex tile data: `[tile kind (0 sea, 1 land, 2 mountain), distance to the tile centre
/// (0 at the centre, 1 on the border)]`, for materials that draw outlines or tint by type.
pub const ATTRIBUTE_TILE: MeshVertexAttribute =
    MeshVertexAttribute::new("HexTerrain_Tile", 0x4845_5854_494c_4501, VertexFormat::Float32x2);

/// Vertex colours of the three layers, blended by height as thesis Algorithm 5 does, for the
/// `StandardMaterial` fallback.
const SEA: [f32; 3] = [0.10, 0.32, 0.70];
const LAND: [f32; 3] = [0.30, 0.58, 0.20];
const MOUNTAIN: [f32; 3] = [0.60, 0.58, 0.56];

fn albedo(h: f32, sea: f32, mountain: f32, blend: f32) -> [f32; 3] {
    let own = if h < sea {
        SEA
    } else if h < mountain {
        LAND
    } else {
        MOUNTAIN
    };
    for (t, below, above) in [(sea, SEA, LAND), (mountain, LAND, MOUNTAIN)] {
        let d = h - t;
        if blend > 0.0 && d.abs() < blend {
            let other = if d < 0.0 { above } else { below };
            let w = 0.5 * (1.0 - d.abs() / blend);
            return std::array::from_fn(|i| own[i] + (other[i] - own[i]) * w);
        }
    }
    own
}

/// Builds a Bevy mesh (positions, normals, UVs, vertex colours, [`ATTRIBUTE_TILE`], u32
/// indices) from a generated chunk.
#[must_use]
pub fn chunk_to_mesh(terrain: &Terrain, chunk: ChunkMesh) -> Mesh {
    let b = chunk.buffers;
    let t = &terrain.config().terrain;
    let blend = terrain.config().appearance.blend;
    let max = t.max_elevation;
    let colours: Vec<[f32; 4]> = b
        .positions
        .iter()
        .map(|p| {
            let h = if max > 0.0 { p[1] / max } else { 0.0 };
            // The palette is sRGB; vertex colours are linear.
            let [r, g, bl] = albedo(h, t.sea_threshold, t.mountain_threshold, blend);
            let c = LinearRgba::from(Srgba::rgb(r, g, bl));
            [c.red, c.green, c.blue, 1.0]
        })
        .collect();
    let tile: Vec<[f32; 2]> = b.tile_kinds.iter().zip(&b.centre_distances).map(|(&k, &d)| [k as f32, d]).collect();
    Mesh::new(PrimitiveTopology::TriangleList, RenderAssetUsages::default())
        .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, b.positions)
        .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, b.normals)
        .with_inserted_attribute(Mesh::ATTRIBUTE_UV_0, b.uvs)
        .with_inserted_attribute(Mesh::ATTRIBUTE_COLOR, colours)
        .with_inserted_attribute(ATTRIBUTE_TILE, tile)
        .with_inserted_indices(Indices::U32(b.indices))
}
