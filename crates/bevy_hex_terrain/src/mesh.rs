//! Core mesh buffers to Bevy meshes.

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::prelude::*;
use hex_terrain::ChunkMesh;

/// Builds a Bevy mesh (positions, normals, UVs, u32 indices) from a generated chunk. The
/// terrain material colors it by height and finds tiles and outlines from the world position in
/// the shader, so no per-vertex tile data is needed.
#[must_use]
pub fn chunk_to_mesh(chunk: ChunkMesh) -> Mesh {
    let b = chunk.buffers;
    Mesh::new(PrimitiveTopology::TriangleList, RenderAssetUsages::default())
        .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, b.positions)
        .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, b.normals)
        .with_inserted_attribute(Mesh::ATTRIBUTE_UV_0, b.uvs)
        .with_inserted_indices(Indices::U32(b.indices))
}
