//! Figures of what a frame draws, for the examples' counters and the tests: instances (visible
//! mesh entities), triangles, and draws, counted the way Bevy batches the main pass: opaque
//! entities sharing a mesh and a material are one instanced draw, each transparent entity
//! (sorted back to front) is a draw of its own. Shadow passes draw again and are not counted.

use bevy::platform::collections::{HashMap, HashSet};
use bevy::prelude::*;

/// What the last frame drew (see the module docs).
#[derive(Resource, Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RenderFigures {
    /// Draw calls of the main pass (batches).
    pub draws: usize,
    /// Visible mesh entities.
    pub instances: usize,
    /// Triangles of the visible meshes.
    pub triangles: usize,
    /// Of those, the triangles of terrain chunks: `[full, coarse]` (levels of detail).
    pub terrain: [usize; 2],
    /// Of those, the triangles of props: `[on full chunks, on coarse chunks]`.
    pub props: [usize; 2],
    /// Chunks showing a mesh, visible or not: `[full, coarse]`.
    pub chunks: [usize; 2],
}

impl std::fmt::Display for RenderFigures {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let Self { draws, instances, triangles, terrain, props, chunks } = self;
        write!(
            f,
            "{draws} draw calls, {instances} instances, {triangles} triangles (terrain {} full + {} coarse, \
             props {} + {}); {} chunks, {} coarse",
            terrain[0],
            terrain[1],
            props[0],
            props[1],
            chunks[0] + chunks[1],
            chunks[1],
        )
    }
}

/// Counts [`RenderFigures`] every frame, after visibility is known.
pub struct RenderFiguresPlugin;

impl Plugin for RenderFiguresPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<RenderFigures>()
            .add_systems(PostUpdate, count.after(bevy::camera::visibility::VisibilitySystems::CheckVisibility));
    }
}

/// A material handle's identity, whatever its type.
type MaterialKey = bevy::asset::UntypedAssetId;

/// Meshes drawn with the terrain material: chunks and water surfaces (with their chunk, if a
/// chunk).
type TerrainDraws<'w, 's> = Query<
    'w,
    's,
    (
        &'static Mesh3d,
        &'static ViewVisibility,
        &'static MeshMaterial3d<bevy_hex_terrain::HexTerrainMaterial>,
        Has<bevy_hex_terrain::HexWater>,
        Option<&'static bevy_hex_terrain::HexChunk>,
    ),
>;

fn count(
    meshes: Res<Assets<Mesh>>,
    mut figures: ResMut<RenderFigures>,
    terrain: TerrainDraws,
    standard: Query<(&Mesh3d, &ViewVisibility, &MeshMaterial3d<StandardMaterial>, Option<&ChildOf>)>,
    chunks: Query<&bevy_hex_terrain::HexChunk>,
    mut triangles: Local<HashMap<AssetId<Mesh>, usize>>,
) {
    let mut f = RenderFigures::default();
    let mut batches: HashSet<(AssetId<Mesh>, MaterialKey)> = HashSet::new();
    let mut add = |mesh: &Mesh3d, material: MaterialKey, transparent: bool| {
        f.instances += 1;
        let id = mesh.id();
        let t = *triangles
            .entry(id)
            .or_insert_with(|| meshes.get(id).map_or(0, |m| m.indices().map_or(m.count_vertices(), |i| i.len()) / 3));
        f.triangles += t;
        // A transparent entity is a draw of its own; opaque ones share their batch's.
        if transparent || batches.insert((id, material)) {
            f.draws += 1;
        }
        t
    };
    // The water surfaces are transparent.
    for (mesh, visible, material, water, chunk) in &terrain {
        if visible.get() {
            let t = add(mesh, material.0.id().untyped(), water);
            if let Some(chunk) = chunk {
                f.terrain[chunk.detail as usize] += t;
            }
        }
    }
    for (mesh, visible, material, parent) in &standard {
        if visible.get() {
            let t = add(mesh, material.0.id().untyped(), false);
            // A chunk's children drawn with a standard material are its props.
            if let Some(chunk) = parent.and_then(|p| chunks.get(p.parent()).ok()) {
                f.props[chunk.detail as usize] += t;
            }
        }
    }
    for chunk in chunks.iter().filter(|c| c.generation.is_some()) {
        f.chunks[chunk.detail as usize] += 1;
    }
    // Meshes change with hot reloads: forget the cache when it grows past what is loaded.
    if triangles.len() > 4 * meshes.len() + 64 {
        triangles.clear();
    }
    *figures = f;
}
