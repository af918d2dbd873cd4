//! What a chunk holds besides its terrain: the water surface over its sea, rivers and lakes, and
//! where its props stand. Both are built in the chunk's task from the generated chunk (pure
//! functions of the map and the chunk, like the mesh) and kept on the chunk entity as
//! [`ChunkContent`]; the water and prop plugins turn them into child entities, which despawn
//! with their chunk.

use std::sync::Arc;

use bevy::prelude::*;
use hex_terrain::{ChunkMesh, Prop, Terrain};

/// The water surface's settings.
#[derive(Debug, Clone, Copy, PartialEq, Reflect)]
pub struct WaterSettings {
    /// Show the water surface over the sea, rivers and lakes (chunks always build it, so
    /// turning it on or off at run time takes effect at once).
    pub enabled: bool,
    /// Height of river and lake water over a fully covered vertex, a fraction of the hex size.
    pub river_depth: f32,
}

impl Default for WaterSettings {
    fn default() -> Self {
        Self { enabled: true, river_depth: 0.12 }
    }
}

/// The props' settings.
#[derive(Debug, Clone, Copy, PartialEq, Reflect)]
pub struct PropSettings {
    /// Show props (trees, rocks, reeds). Chunks always place them, so turning this off at run
    /// time despawns the props of loaded chunks at once and turning it on spawns them again.
    pub enabled: bool,
    /// Props a chunk keeps at most (the rest are thinned deterministically); applies to chunks
    /// built after a change.
    pub max_per_chunk: usize,
    /// Share of each tile's props that stand, in `[0, 1]`; applies to chunks built after a
    /// change.
    pub density: f32,
}

impl Default for PropSettings {
    fn default() -> Self {
        Self { enabled: true, max_per_chunk: 384, density: 1.0 }
    }
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

    /// Builds the water and props of `chunk` under the settings (whether they are shown or
    /// not: the plugins show them).
    pub(crate) fn build(terrain: &Terrain, chunk: &ChunkMesh, water: WaterSettings, props: PropSettings) -> Self {
        let depth = water.river_depth.max(0.0) * terrain.config().layout.hex_size;
        let surface = terrain.water_surface(chunk, if depth.is_finite() { depth } else { 0.0 });
        let water_triangles = surface.triangle_count();
        let water = (!surface.is_empty()).then(|| crate::mesh::water_to_mesh(surface));
        // Trees, rocks and reeds (thinned to the cap), then the game setup's resources and
        // wonders (never thinned).
        let mut all = terrain.props(chunk, props.max_per_chunk, props.density);
        all.extend(terrain.marker_props(chunk));
        let props = all.into();
        Self { water, water_triangles, props }
    }
}

/// Every chunk with its content and children, as the water and prop plugins read them.
pub(crate) type ContentQuery<'w, 's> =
    Query<'w, 's, (Entity, Ref<'static, ChunkContent>, Option<&'static Children>), With<super::HexChunk>>;

/// The chunks whose children of one kind (`T`: water, props) must be made anew (all of them
/// when the kind's switch changed, else those whose content changed), with their content; their
/// old children of that kind are despawned. `was` remembers the switch between frames.
pub(crate) fn stale_chunks<'a, T: Component>(
    commands: &mut Commands,
    chunks: &'a ContentQuery,
    children_of_kind: &Query<(), With<T>>,
    enabled: bool,
    was: &mut Option<bool>,
) -> Vec<(Entity, &'a ChunkContent)> {
    let toggled = *was != Some(enabled);
    *was = Some(enabled);
    let mut stale = Vec::new();
    for (chunk, content, children) in chunks {
        if !(toggled || content.is_changed()) {
            continue;
        }
        for child in children.into_iter().flatten() {
            if children_of_kind.contains(*child) {
                commands.entity(*child).despawn();
            }
        }
        stale.push((chunk, content.into_inner()));
    }
    stale
}
