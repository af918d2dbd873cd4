//! Streaming a globe: the chunks with ground in sight of an agent (within its horizon, and the
//! peaks beyond it) are kept, each meshed on Bevy's async compute pool; the others are despawned,
//! so the far side of the globe is neither built nor drawn.

use std::collections::BTreeSet;

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use bevy::tasks::futures::check_ready;
use bevy::tasks::{AsyncComputeTaskPool, Task};
use hex_terrain::{Biome, GlobeChunk, GlobeMesh, GlobeProp, TileKind};

use super::props::GlobeChunkProps;
use super::{HexGlobe, chunks_within};
use crate::{HexPropSettings, HexTerrainAgent};

/// A chunk of the globe on screen (or on its way): which one, and the globe generation its mesh
/// shows (`None` until its first mesh arrives).
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq, Reflect)]
#[reflect(Component)]
#[require(Transform)]
#[cfg_attr(feature = "render", require(Visibility))]
pub struct HexGlobeChunk {
    /// The chunk.
    pub chunk: GlobeChunk,
    /// The [`HexGlobe::generation`] its mesh was built for.
    pub generation: Option<u64>,
}

/// A chunk's mesh (with its origin and props) being built, for a globe generation.
#[derive(Component)]
pub(super) struct GlobeChunkTask {
    task: Task<(Mesh, Vec3, Vec<GlobeProp>)>,
    generation: u64,
}

/// The chunks the globe streaming keeps, by chunk.
#[derive(Resource, Debug, Default)]
pub struct GlobeStreamer {
    chunks: HashMap<GlobeChunk, Entity>,
    /// How many chunks the agents want, and how many of them show the current globe.
    wanted: usize,
    current: usize,
}

impl GlobeStreamer {
    /// The entity of a chunk kept, if it is.
    #[must_use]
    pub fn chunk(&self, chunk: GlobeChunk) -> Option<Entity> {
        self.chunks.get(&chunk).copied()
    }

    /// The chunks kept.
    pub fn chunks(&self) -> impl Iterator<Item = GlobeChunk> + '_ {
        self.chunks.keys().copied()
    }

    /// Whether every chunk the agents want shows the current globe.
    #[must_use]
    pub fn is_settled(&self) -> bool {
        self.wanted > 0 && self.current == self.wanted
    }
}

/// The angle from the direction of an agent `distance` from a globe's center within which its
/// ground may be in sight: to the horizon of the sphere of height 0 (`radius`), and beyond it the
/// peaks up to `max_elevation` that rise over it. An agent under height 0 keeps
/// [`NEAR_ANGLE`] around it. The plugin keeps the chunks with ground within it.
#[must_use]
pub fn globe_horizon(radius: f32, max_elevation: f32, distance: f32) -> f32 {
    if distance <= radius {
        return NEAR_ANGLE;
    }
    let beyond = (radius / (radius + max_elevation.max(0.0))).acos();
    ((radius / distance).acos() + beyond).max(NEAR_ANGLE)
}

/// The angle kept around an agent on or under the ground, radians.
pub const NEAR_ANGLE: f32 = 0.2;

/// Keeps the chunks in sight of the agents (the whole globe without an agent), despawning the
/// others and starting a task for each new or outdated one.
pub(super) fn stream(
    mut commands: Commands,
    globe: Res<HexGlobe>,
    settings: Res<HexPropSettings>,
    mut streamer: ResMut<GlobeStreamer>,
    agents: Query<&GlobalTransform, With<HexTerrainAgent>>,
    chunks: Query<(&HexGlobeChunk, Option<&GlobeChunkTask>)>,
) {
    let Some(terrain) = globe.globe() else { return };
    let (radius, max_elevation) = (terrain.radius() as f32, terrain.config().terrain.max_elevation);
    let wanted: BTreeSet<GlobeChunk> = if agents.is_empty() {
        terrain.chunks().into_iter().collect()
    } else {
        agents
            .iter()
            .flat_map(|t| {
                let p = t.translation();
                let direction = p.try_normalize().unwrap_or(Vec3::Y);
                chunks_within(terrain, direction, globe_horizon(radius, max_elevation, p.length()))
            })
            .collect()
    };
    streamer.chunks.retain(|chunk, entity| {
        let keep = wanted.contains(chunk) && chunks.contains(*entity);
        if !keep && let Ok(mut e) = commands.get_entity(*entity) {
            e.despawn();
        }
        keep
    });
    let generation = globe.generation();
    let mut current = 0;
    for &chunk in &wanted {
        let entity = match streamer.chunks.get(&chunk) {
            Some(&entity) => {
                let Ok((shown, task)) = chunks.get(entity) else { continue };
                let shows = globe.is_current(chunk, shown.generation);
                current += usize::from(shows);
                // A chunk an edit left alone keeps its mesh; a task for the globe as it is now
                // is left to finish.
                if shows || task.is_some_and(|t| globe.is_current(chunk, Some(t.generation))) {
                    continue;
                }
                entity
            }
            None => {
                let entity = commands.spawn(HexGlobeChunk { chunk, generation: None }).id();
                streamer.chunks.insert(chunk, entity);
                entity
            }
        };
        let terrain = terrain.clone();
        let (cap, density) = (settings.max_per_chunk, settings.density);
        let task = AsyncComputeTaskPool::get().spawn(async move {
            let mesh = terrain.generate(chunk);
            let origin = Vec3::from_array(mesh.origin.map(|c| c as f32));
            let props = terrain.props(&mesh, cap, density);
            (globe_mesh(mesh), origin, props)
        });
        commands.entity(entity).insert(GlobeChunkTask { task, generation });
    }
    streamer.wanted = wanted.len();
    streamer.current = current;
}

/// Gives each chunk whose task finished its mesh and props (the globe's material comes with the
/// renderer, `material.rs`; the props' entities, `props.rs`).
pub(super) fn insert(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut tasks: Query<(Entity, &mut HexGlobeChunk, &mut GlobeChunkTask, Option<&Mesh3d>)>,
) {
    for (entity, mut chunk, mut task, old) in &mut tasks {
        let Some((mesh, origin, props)) = check_ready(&mut task.task) else { continue };
        if let Some(old) = old {
            meshes.remove(&old.0);
        }
        chunk.generation = Some(task.generation);
        commands.entity(entity).remove::<GlobeChunkTask>().insert((
            Mesh3d(meshes.add(mesh)),
            Transform::from_translation(origin),
            GlobeChunkProps::new(props),
        ));
    }
}

/// How dark a tile's border ring is drawn, a share of its color: the soft outline that shows
/// each tile, pentagons too.
const OUTLINE: f32 = 0.78;

/// A globe chunk's Bevy mesh: positions, normals, u32 indices, vertex colors (the biome colors
/// with a climate, else each vertex's kind's; darker on tile borders; sRGB to linear) and in the
/// first UV each vertex's tile (`id % GLOBE_ROW`, `id / GLOBE_ROW`) for the material's tile
/// states. A point on a tile border is one vertex for each tile holding it (the same position,
/// normal and color), so every corner of a triangle names the triangle's tile.
pub(crate) fn globe_mesh(mesh: GlobeMesh) -> Mesh {
    let b = mesh.buffers;
    let srgb: Vec<[u8; 3]> = if b.colors.is_empty() {
        let kinds = [TileKind::Sea, TileKind::Land, TileKind::Mountain];
        b.tile_kinds.iter().map(|&k| Biome::of_kind(kinds[(k as usize).min(2)]).color()).collect()
    } else {
        b.colors.iter().map(|c| [c[0], c[1], c[2]]).collect()
    };
    let colors: Vec<[f32; 4]> = srgb
        .iter()
        .zip(&b.center_distances)
        .map(|(&[r, g, bl], &ring)| {
            let c = Color::srgb_u8(r, g, bl).to_linear();
            let shade = if ring >= 1.0 { OUTLINE } else { 1.0 };
            [c.red * shade, c.green * shade, c.blue * shade, 1.0]
        })
        .collect();
    // A tile's triangles come one after the other: a vertex is copied when a tile other than the
    // last one to use it takes it.
    let count = b.positions.len();
    let mut copy_of = vec![(u32::MAX, 0u32); count];
    let capacity = count + count / 2;
    let (mut positions, mut normals, mut vertex_colors, mut uvs) = (
        Vec::with_capacity(capacity),
        Vec::with_capacity(capacity),
        Vec::with_capacity(capacity),
        Vec::with_capacity(capacity),
    );
    let mut indices = Vec::with_capacity(b.indices.len());
    for (triangle, tile) in b.indices.chunks_exact(3).zip(&mesh.triangle_tiles) {
        for &v in triangle {
            let (last, copy) = &mut copy_of[v as usize];
            if *last != tile.0 {
                *last = tile.0;
                *copy = positions.len() as u32;
                positions.push(b.positions[v as usize]);
                normals.push(b.normals[v as usize]);
                vertex_colors.push(colors[v as usize]);
                uvs.push([(tile.0 % GLOBE_ROW) as f32, (tile.0 / GLOBE_ROW) as f32]);
            }
            indices.push(*copy);
        }
    }
    Mesh::new(PrimitiveTopology::TriangleList, RenderAssetUsages::default())
        .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, positions)
        .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, normals)
        .with_inserted_attribute(Mesh::ATTRIBUTE_COLOR, vertex_colors)
        .with_inserted_attribute(Mesh::ATTRIBUTE_UV_0, uvs)
        .with_inserted_indices(Indices::U32(indices))
}

/// Tiles a row of the globe's textures holds, and of the first UV's tile ids: a tile's id is
/// `u + v * GLOBE_ROW`.
pub const GLOBE_ROW: u32 = 1024;
