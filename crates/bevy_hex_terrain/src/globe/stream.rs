//! Streaming a globe: the chunks with ground in sight of an agent (within its horizon, and the
//! peaks beyond it) are kept, each meshed on Bevy's async compute pool; the others are despawned,
//! so the far side of the globe is neither built nor drawn. A chunk far from every agent is drawn
//! coarse ([`HexGlobeSettings::coarse_distance`]), so the whole planet in view does not draw
//! every inner vertex.

use std::collections::BTreeSet;

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use bevy::tasks::futures::check_ready;
use bevy::tasks::{AsyncComputeTaskPool, Task};
use hex_terrain::{Biome, Detail, GlobeChunk, GlobeMesh, GlobeProp, GlobeTerrain, GlobeTile, TileKind};

use super::props::GlobeChunkProps;
use super::{HexGlobe, chunks_within};
use crate::{HexPropSettings, HexTerrainAgent, TerrainReady, TerrainSettled};

/// A chunk of the globe on screen (or on its way): which one, the globe generation its mesh
/// shows (`None` until its first mesh arrives) and how finely.
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq, Reflect)]
#[reflect(Component)]
#[require(Transform)]
#[cfg_attr(feature = "render", require(Visibility))]
pub struct HexGlobeChunk {
    /// The chunk.
    pub chunk: GlobeChunk,
    /// The [`HexGlobe::generation`] its mesh was built for.
    pub generation: Option<u64>,
    /// The level of detail of its mesh ([`GlobeMesh::coarse`] when coarse).
    pub detail: Detail,
}

/// A chunk's mesh (with its origin and props) being built, for a globe generation and a level
/// of detail.
#[derive(Component)]
pub(super) struct GlobeChunkTask {
    task: Task<(Mesh, Vec3, Vec<GlobeProp>)>,
    generation: u64,
    detail: Detail,
}

/// The globe streaming's settings (a game may insert it before or after the plugin).
#[derive(Resource, Debug, Clone, Copy, PartialEq, Reflect)]
#[reflect(Resource, Default)]
pub struct HexGlobeSettings {
    /// Level of detail: a chunk with no ground within this many hex sizes (multiples of the
    /// map's `layout.hex_size`) of every agent, measured in 3D on the sphere of height 0, is
    /// drawn coarse ([`Detail::Coarse`]: a fan a tile from its center to its corners, the
    /// chunk's outline kept whole, so levels meet without a crack), and full again once ground
    /// of it is nearer than `1 -` [`DETAIL_HYSTERESIS`](crate::DETAIL_HYSTERESIS) of it. So a
    /// camera at a planet's distance draws every chunk coarse. Its props stand on the coarse
    /// surface. Without an agent every chunk is full; `None`: every chunk full.
    pub coarse_distance: Option<f32>,
}

impl Default for HexGlobeSettings {
    fn default() -> Self {
        Self { coarse_distance: Some(crate::DEFAULT_COARSE_DISTANCE) }
    }
}

/// The chunks the globe streaming keeps, by chunk.
#[derive(Resource, Debug, Default)]
pub struct GlobeStreamer {
    chunks: HashMap<GlobeChunk, Entity>,
    /// How many chunks the agents want, and how many of them show the current globe.
    wanted: usize,
    current: usize,
    /// Whether every wanted chunk showed the globe last frame, and the globe whose
    /// [`TerrainReady`] was sent.
    was_settled: bool,
    ready_map: Option<u64>,
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

/// The angle from the direction of an agent `distance` from a globe's center within which the
/// sphere of `radius` lies nearer than `within` to it (the law of cosines); `None` when none of
/// it does.
fn near_angle(radius: f32, distance: f32, within: f32) -> Option<f32> {
    let cos = (distance * distance + radius * radius - within * within) / (2.0 * distance * radius);
    (distance > 0.0 && cos <= 1.0).then(|| cos.max(-1.0).acos())
}

/// The angle kept around an agent on or under the ground, radians.
pub const NEAR_ANGLE: f32 = 0.2;

/// Keeps the chunks in sight of the agents (the whole globe without an agent), despawning the
/// others and starting a task for each new or outdated one (or at another level of detail);
/// reports [`TerrainSettled`] when every wanted chunk shows the globe, with [`TerrainReady`] the
/// first time for a globe.
pub(super) fn stream(
    mut commands: Commands,
    globe: Res<HexGlobe>,
    (settings, props): (Res<HexGlobeSettings>, Res<HexPropSettings>),
    mut streamer: ResMut<GlobeStreamer>,
    agents: Query<&GlobalTransform, With<HexTerrainAgent>>,
    chunks: Query<(&HexGlobeChunk, Option<&GlobeChunkTask>)>,
    mut reports: (MessageWriter<TerrainReady>, MessageWriter<TerrainSettled>),
) {
    let Some(terrain) = globe.globe() else { return };
    let (radius, max_elevation) = (terrain.radius() as f32, terrain.config().terrain.max_elevation);
    // The chunks with ground within the coarse distance of an agent (`keep`), and within the
    // nearer distance at which a coarse chunk turns full (`enter`).
    let full_within = |distance: f32| -> BTreeSet<GlobeChunk> {
        agents
            .iter()
            .flat_map(|t| {
                let p = t.translation();
                let direction = p.try_normalize().unwrap_or(Vec3::Y);
                match near_angle(radius, p.length(), distance) {
                    Some(angle) => chunks_within(terrain, direction, angle),
                    None => Vec::new(),
                }
            })
            .collect()
    };
    let hex = terrain.config().layout.hex_size;
    let (keep, enter) = match settings.coarse_distance {
        Some(d) if !agents.is_empty() => {
            (Some(full_within(d * hex)), Some(full_within(d * hex * (1.0 - crate::DETAIL_HYSTERESIS as f32))))
        }
        _ => (None, None),
    };
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
        let shown = streamer.chunks.get(&chunk).and_then(|&e| chunks.get(e).ok());
        // Full near an agent (kept full out to the coarse distance), else coarse.
        let full_now = shown.is_some_and(|(c, _)| c.generation.is_some() && c.detail == Detail::Full);
        let detail = match (&keep, &enter) {
            (Some(keep), Some(enter)) if !(enter.contains(&chunk) || full_now && keep.contains(&chunk)) => {
                Detail::Coarse
            }
            _ => Detail::Full,
        };
        let entity = match streamer.chunks.get(&chunk) {
            Some(&entity) => {
                let Some((shown, task)) = shown else { continue };
                let shows = globe.is_current(chunk, shown.generation) && shown.detail == detail;
                current += usize::from(shows);
                // A chunk an edit left alone keeps its mesh; a task for the globe as it is now,
                // at the level wanted, is left to finish.
                if shows || task.is_some_and(|t| globe.is_current(chunk, Some(t.generation)) && t.detail == detail) {
                    continue;
                }
                entity
            }
            None => {
                let entity = commands.spawn(HexGlobeChunk { chunk, generation: None, detail }).id();
                streamer.chunks.insert(chunk, entity);
                entity
            }
        };
        let terrain = terrain.clone();
        let (cap, density) = (props.max_per_chunk, props.density);
        let task = AsyncComputeTaskPool::get().spawn(async move {
            let full = terrain.generate(chunk);
            let origin = Vec3::from_array(full.origin.map(|c| c as f32));
            // Which props stand is decided on the full surface, whatever the level.
            let mut props = terrain.props(&full, cap, density);
            let mesh = match detail {
                Detail::Full => full,
                Detail::Coarse => {
                    let coarse = full.coarse();
                    coarse.stand_on(&mut props);
                    coarse
                }
            };
            // The game setup's resources and wonders, never thinned, on the level's own surface.
            props.extend(terrain.marker_props(&mesh));
            (globe_mesh(mesh, detail, |tile| texture_layer(&terrain, tile)), origin, props)
        });
        commands.entity(entity).insert(GlobeChunkTask { task, generation, detail });
    }
    streamer.wanted = wanted.len();
    streamer.current = current;
    // Settled: every wanted chunk shows the globe (the frame after the last mesh came in).
    let settled = streamer.is_settled();
    if settled && !streamer.was_settled {
        let (ready, done) = &mut reports;
        done.write(TerrainSettled { generation });
        if streamer.ready_map != Some(globe.map_id()) {
            streamer.ready_map = Some(globe.map_id());
            ready.write(TerrainReady { map_id: globe.map_id(), generation });
        }
    }
    streamer.was_settled = settled;
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
        chunk.detail = task.detail;
        commands.entity(entity).remove::<GlobeChunkTask>().insert((
            Mesh3d(meshes.add(mesh)),
            Transform::from_translation(origin),
            GlobeChunkProps::new(props),
        ));
    }
}

/// A tile's layer of the material's texture array: its terrain's (or feature's) look.
fn texture_layer(terrain: &GlobeTerrain, tile: GlobeTile) -> u32 {
    terrain.tile_info(tile).map_or(0, |info| {
        let ruleset = terrain.ruleset();
        let t = info.terrain;
        u32::from(t.feature.map_or(&ruleset.terrain(t.terrain).look, |f| &ruleset.feature(f).look).texture)
    })
}

/// A globe chunk's Bevy mesh: positions, normals, u32 indices, vertex colors (the biome colors
/// with a climate, else each vertex's kind's; sRGB to linear; on a coarse mesh each tile in its
/// center's color, as a fan a tile would smear its corners' across it), in the first UV each
/// vertex's tile (`id % GLOBE_ROW`, `id / GLOBE_ROW`) for the material's tile states and
/// outlines, and in the second UV's first component its tile's texture layer (`layer`). A point
/// on a tile border is one vertex for each tile holding it (the same position and normal), so
/// every corner of a triangle names the triangle's tile.
pub(crate) fn globe_mesh(mesh: GlobeMesh, detail: Detail, layer: impl Fn(GlobeTile) -> u32) -> Mesh {
    let b = mesh.buffers;
    let srgb: Vec<[u8; 3]> = if b.colors.is_empty() {
        let kinds = [TileKind::Sea, TileKind::Land, TileKind::Mountain];
        b.tile_kinds.iter().map(|&k| Biome::of_kind(kinds[(k as usize).min(2)]).color()).collect()
    } else {
        b.colors.iter().map(|c| [c[0], c[1], c[2]]).collect()
    };
    let colors: Vec<[f32; 4]> = srgb
        .iter()
        .map(|&[r, g, bl]| {
            let c = Color::srgb_u8(r, g, bl).to_linear();
            [c.red, c.green, c.blue, 1.0]
        })
        .collect();
    // A tile's triangles come one after the other: a vertex is copied when a tile other than the
    // last one to use it takes it.
    let count = b.positions.len();
    let mut copy_of = vec![(u32::MAX, 0u32); count];
    let capacity = count + count / 2;
    let (mut positions, mut normals, mut vertex_colors, mut uvs, mut layers) = (
        Vec::with_capacity(capacity),
        Vec::with_capacity(capacity),
        Vec::with_capacity(capacity),
        Vec::with_capacity(capacity),
        Vec::with_capacity(capacity),
    );
    let mut indices = Vec::with_capacity(b.indices.len());
    // A tile's triangles come together: its layer is asked once a run.
    let mut tile_layer = (u32::MAX, 0.0);
    for (triangle, tile) in b.indices.chunks_exact(3).zip(&mesh.triangle_tiles) {
        // A coarse mesh's triangles start at their tile's center.
        let tile_color = (detail == Detail::Coarse).then(|| colors[triangle[0] as usize]);
        if tile_layer.0 != tile.0 {
            tile_layer = (tile.0, layer(*tile) as f32);
        }
        for &v in triangle {
            let (last, copy) = &mut copy_of[v as usize];
            if *last != tile.0 {
                *last = tile.0;
                *copy = positions.len() as u32;
                positions.push(b.positions[v as usize]);
                normals.push(b.normals[v as usize]);
                vertex_colors.push(tile_color.unwrap_or(colors[v as usize]));
                uvs.push([(tile.0 % GLOBE_ROW) as f32, (tile.0 / GLOBE_ROW) as f32]);
                layers.push([tile_layer.1, 0.0]);
            }
            indices.push(*copy);
        }
    }
    Mesh::new(PrimitiveTopology::TriangleList, RenderAssetUsages::default())
        .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, positions)
        .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, normals)
        .with_inserted_attribute(Mesh::ATTRIBUTE_COLOR, vertex_colors)
        .with_inserted_attribute(Mesh::ATTRIBUTE_UV_0, uvs)
        .with_inserted_attribute(Mesh::ATTRIBUTE_UV_1, layers)
        .with_inserted_indices(Indices::U32(indices))
}

/// Tiles a row of the globe's textures holds, and of the first UV's tile ids: a tile's id is
/// `u + v * GLOBE_ROW`.
pub const GLOBE_ROW: u32 = 1024;
