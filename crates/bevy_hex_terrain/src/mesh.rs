//! Core mesh buffers to Bevy meshes.

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::prelude::*;
use hex_terrain::ChunkMesh;

/// Builds a Bevy mesh (positions, normals, UVs, u32 indices) from a generated chunk. The
/// terrain material colors it by height and finds tiles and outlines from the world position in
/// the shader, so no per-vertex tile data is needed. A map with climate or rivers adds
/// `ATTRIBUTE_COLOR`: the biome color (converted from sRGB to linear) and, in alpha, the river or
/// lake water over the vertex; the material then colors by biome.
#[must_use]
pub fn chunk_to_mesh(chunk: ChunkMesh) -> Mesh {
    let b = chunk.buffers;
    let mut mesh = Mesh::new(PrimitiveTopology::TriangleList, RenderAssetUsages::default())
        .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, b.positions)
        .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, b.normals)
        .with_inserted_attribute(Mesh::ATTRIBUTE_UV_0, b.uvs)
        .with_inserted_indices(Indices::U32(b.indices));
    if !b.colors.is_empty() {
        let colors: Vec<[f32; 4]> = b
            .colors
            .iter()
            .map(|&[r, g, bl, a]| {
                let c = Color::srgb_u8(r, g, bl).to_linear();
                [c.red, c.green, c.blue, f32::from(a) / 255.0]
            })
            .collect();
        mesh.insert_attribute(Mesh::ATTRIBUTE_COLOR, colors);
    }
    mesh
}
