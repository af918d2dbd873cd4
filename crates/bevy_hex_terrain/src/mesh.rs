//! Core mesh buffers to Bevy meshes.

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::prelude::*;
use hex_terrain::ChunkMesh;

/// Builds a Bevy mesh (positions, normals, UVs, u32 indices) from a generated chunk. The
/// terrain material colors it by height and finds tiles and outlines from the world position in
/// the shader, so no per-vertex tile data is needed. A map with climate or rivers adds
/// `ATTRIBUTE_COLOR`: the biome color (converted from sRGB to linear) and, in alpha, the river or
/// lake water over the vertex; the material then colors by biome. Its texture layers
/// ([`MeshBuffers::texture_layers`](hex_terrain::MeshBuffers::texture_layers): the layer of the
/// tile of each texture class holding the vertex) take the UVs' place: classes 0 and 1 in
/// `ATTRIBUTE_UV_0`, class 2 in `ATTRIBUTE_UV_1`'s first component (the material reads the
/// world position, not UVs; a mesh without layers keeps world-space UVs).
#[must_use]
pub fn chunk_to_mesh(chunk: ChunkMesh) -> Mesh {
    let b = chunk.buffers;
    let mut mesh = Mesh::new(PrimitiveTopology::TriangleList, RenderAssetUsages::default())
        .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, b.positions)
        .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, b.normals)
        .with_inserted_indices(Indices::U32(b.indices));
    if b.texture_layers.is_empty() {
        mesh.insert_attribute(Mesh::ATTRIBUTE_UV_0, b.uvs);
    } else {
        let entry = |l: u8| f32::from(l);
        let first: Vec<[f32; 2]> = b.texture_layers.iter().map(|l| [entry(l[0]), entry(l[1])]).collect();
        let second: Vec<[f32; 2]> = b.texture_layers.iter().map(|l| [entry(l[2]), 0.0]).collect();
        mesh.insert_attribute(Mesh::ATTRIBUTE_UV_0, first);
        mesh.insert_attribute(Mesh::ATTRIBUTE_UV_1, second);
    }
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

/// Builds a Bevy mesh of a chunk's water surface: positions, normals, UVs and, in
/// `ATTRIBUTE_UV_1`'s first component, the depth of water below each vertex (world units), which
/// the terrain material's water pass colors by.
#[must_use]
pub fn water_to_mesh(water: hex_terrain::WaterBuffers) -> Mesh {
    let depths: Vec<[f32; 2]> = water.depths.iter().map(|&d| [d, 0.0]).collect();
    Mesh::new(PrimitiveTopology::TriangleList, RenderAssetUsages::default())
        .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, water.positions)
        .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, water.normals)
        .with_inserted_attribute(Mesh::ATTRIBUTE_UV_0, water.uvs)
        .with_inserted_attribute(Mesh::ATTRIBUTE_UV_1, depths)
        .with_inserted_indices(Indices::U32(water.indices))
}
