//! What a chunk holds besides its terrain: the water surface over its sea, rivers and lakes, and
//! where its props stand. Both are built in the chunk's task from the generated chunk (pure
//! functions of the map and the chunk, like the mesh) and kept on the chunk entity as
//! [`ChunkContent`]; the water and prop plugins turn them into child entities, which despawn
//! with their chunk.

use std::sync::Arc;

use bevy::prelude::*;
use hex_terrain::{ChunkMesh, Detail, Prop, Terrain};

/// What chunk tasks build besides the terrain. The water and props plugins write their part
/// from their own settings when those change (`None`: no such plugin, nothing of its kind is
/// built); the streaming system copies it into each task it starts, so a task never reads a
/// resource and streaming depends on neither plugin.
#[derive(Resource, Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct ContentRequest {
    /// River and lake water depth, a fraction of the hex size; `None` without the water plugin
    /// (no surface is built).
    pub river_depth: Option<f32>,
    /// The props' cap per chunk and density; `None` without the props plugin (none are placed;
    /// the game setup's markers still are).
    pub props: Option<(usize, f32)>,
}

/// A chunk's water surface and props (see the module docs). Twin chunks of a wrapping map
/// share them, as they share their mesh.
#[derive(Component, Debug, Clone, Default, Reflect)]
#[reflect(Component, Default)]
pub struct ChunkContent {
    /// The water surface's mesh, `None` for a dry chunk.
    pub water: Option<Handle<Mesh>>,
    /// Triangles of the water surface.
    pub water_triangles: usize,
    /// Where the chunk's props stand, relative to the chunk's origin.
    #[reflect(ignore)]
    pub props: Arc<[Prop]>,
}

/// The water mesh and props of a generated chunk, as its task builds them.
pub(crate) struct BuiltContent {
    pub(crate) water: Option<Mesh>,
    pub(crate) water_triangles: usize,
    pub(crate) props: Arc<[Prop]>,
}

impl BuiltContent {
    pub(crate) fn empty() -> Self {
        Self { water: None, water_triangles: 0, props: Arc::from([]) }
    }

    /// Builds the water and props of `chunk` (the full mesh) as requested (whether they are
    /// shown or not: the plugins show them), the props standing on the surface drawn at
    /// `detail`: the same props at every level, so a level change moves them instead of making
    /// them anew. The water surface is the full mesh's at every level: it lies over the sea and
    /// lakes, which a coarse tile keeps.
    pub(crate) fn build(terrain: &Terrain, chunk: &ChunkMesh, snapshot: ContentRequest, detail: Detail) -> Self {
        let (mut water, mut water_triangles) = (None, 0);
        if let Some(depth) = snapshot.river_depth {
            let depth = depth.max(0.0) * terrain.config().layout.hex_size;
            let surface = terrain.water_surface(chunk, if depth.is_finite() { depth } else { 0.0 });
            water_triangles = surface.triangle_count();
            water = (!surface.is_empty()).then(|| crate::mesh::water_to_mesh(surface));
        }
        // Trees, rocks and reeds (thinned to the cap), then the game setup's resources and
        // wonders (never thinned).
        let mut all =
            snapshot.props.map_or_else(Vec::new, |(cap, density)| terrain.props_on(chunk, cap, density, detail));
        // Markers stand at tile centers, a vertex of both levels.
        all.extend(terrain.marker_props(chunk));
        let props = all.into();
        Self { water, water_triangles, props }
    }
}

/// Every chunk with its content and children, as the water and prop plugins read them.
pub(crate) type ContentQuery<'w, 's> =
    Query<'w, 's, (Entity, Ref<'static, ChunkContent>, Option<&'static Children>), With<super::HexChunk>>;

/// The chunks whose children of one kind (water, props: those `of_kind` says) must be made anew (all of them
/// when the kind's switch changed, else those whose content changed), with their content and
/// their old children of that kind, which the caller despawns (at once, or a budget a frame).
/// `was` remembers the switch between frames.
pub(crate) fn stale_chunks<'a>(
    chunks: &'a ContentQuery,
    of_kind: impl Fn(Entity) -> bool,
    enabled: bool,
    was: &mut Option<bool>,
) -> Vec<(Entity, &'a ChunkContent, Vec<Entity>)> {
    let toggled = *was != Some(enabled);
    *was = Some(enabled);
    let mut stale = Vec::new();
    for (chunk, content, children) in chunks {
        if !(toggled || content.is_changed()) {
            continue;
        }
        let old = children.into_iter().flatten().copied().filter(|c| of_kind(*c)).collect();
        stale.push((chunk, content.into_inner(), old));
    }
    stale
}
