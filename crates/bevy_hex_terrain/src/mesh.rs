//! Core mesh buffers to Bevy meshes.

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, MeshVertexAttribute, PrimitiveTopology, VertexFormat};
use bevy::prelude::*;
use hex_terrain::ChunkMesh;

/// Per-vertex tile data: `[tile kind (0 sea, 1 land, 2 mountain), distance to the tile center
/// (0 at the center, 1 on the border)]`, for materials that draw outlines or tint by type.
pub const ATTRIBUTE_TILE: MeshVertexAttribute =
    MeshVertexAttribute::new("HexTerrain_Tile", 0x4845_5854_494c_4501, VertexFormat::Float32x2);

/// Builds a Bevy mesh (positions, normals, UVs, [`ATTRIBUTE_TILE`], u32 indices) from a
/// generated chunk. The terrain material colors it by height in the shader.
#[must_use]
pub fn chunk_to_mesh(chunk: ChunkMesh) -> Mesh {
    let b = chunk.buffers;
    let tile: Vec<[f32; 2]> = b.tile_kinds.iter().zip(&b.center_distances).map(|(&k, &d)| [k as f32, d]).collect();
    Mesh::new(PrimitiveTopology::TriangleList, RenderAssetUsages::default())
        .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, b.positions)
        .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, b.normals)
        .with_inserted_attribute(Mesh::ATTRIBUTE_UV_0, b.uvs)
        .with_inserted_attribute(ATTRIBUTE_TILE, tile)
        .with_inserted_indices(Indices::U32(b.indices))
}
