//! Chunk tasks: the streaming system that applies the planner's decisions (despawn, spawn,
//! start tasks on Bevy's async compute pool), and the task body.

use std::sync::Arc;

use bevy::math::DVec3;
use bevy::platform::collections::{HashMap, HashSet};
use bevy::platform::time::Instant;
use bevy::prelude::*;
use bevy::tasks::AsyncComputeTaskPool;
use hex_terrain::{ChunkCoord, Detail, GenerateOptions, Terrain, Threads};

use super::build::{ChunkBuild, ChunkTask};
use super::content::{BuiltContent, ChunkContent, ContentRequest};
use super::detail::Cameras;
use super::planner::{ChunkState, plan};
use super::state::StreamState;
use super::{ChunkDespawned, ChunkSpawned, ChunkStreamer, ChunkThreads, HexChunk, HexTerrainAgent, HexWorldPosition};
use crate::map::HexMap;
use crate::mesh::chunk_to_mesh;

/// Plans the frame ([`plan`]) and applies it: despawns dropped chunks, spawns missing ones and
/// starts their tasks. An outdated chunk keeps showing its old mesh until the new one arrives.
pub(crate) fn stream(
    mut commands: Commands,
    state: StreamState,
    agents: Query<(&GlobalTransform, &HexTerrainAgent, Option<&HexWorldPosition>)>,
    cameras: Cameras,
    chunks: ChunkQuery,
    content: Res<ContentRequest>,
    (mut despawned, mut spawned): (MessageWriter<ChunkDespawned>, MessageWriter<ChunkSpawned>),
) {
    let StreamState { mut streamer, mut stats, map, settings } = state;
    if map.is_waiting_for_asset() {
        return;
    }
    let terrain = map.terrain().clone();
    let generation = map.generation();
    // Forget entities despawned by someone else.
    streamer.chunks.retain(|_, e| chunks.contains(*e));
    let viewers = cameras.positions().unwrap_or_else(|| {
        agents.iter().map(|(t, _, world)| world.map_or_else(|| t.translation().as_dvec3(), |w| w.0)).collect()
    });
    let agents: Vec<(ChunkCoord, u32)> = agents
        .iter()
        .filter_map(|(t, a, world)| {
            let p = world.map_or_else(|| t.translation().as_dvec3(), |w| w.0);
            // The tile of the plane (not wrapped): on a wrapping map the agent's chunk is the copy
            // under it, east or west of the map. An agent past the world's edge loads nothing.
            let tile = terrain.unwrapped_tile_at(p.x, p.z)?;
            // The chunk the tile falls in, also past a bounded map's edge (the map's chunks near
            // an agent standing off it still load): the geometry's, not the map query's.
            Some((terrain.geometry().chunk_of(tile), a.radius.unwrap_or(settings.load_radius)))
        })
        .collect();
    let existing: HashMap<ChunkCoord, ChunkState> = streamer
        .chunks
        .iter()
        .filter_map(|(&c, &e)| {
            let (chunk, task, ..) = chunks.get(e).ok()?;
            Some((c, {
                let building = task.filter(|t| map.is_current(c, Some(t.generation)));
                ChunkState {
                    current: map.is_current(c, chunk.generation),
                    building: building.is_some(),
                    detail: building.map_or(chunk.detail, |t| t.detail),
                }
            }))
        })
        .collect();
    let plan = plan(&terrain, &settings, &agents, &viewers, &existing, &mut streamer.boxes);

    for c in plan.drop {
        let Some(e) = streamer.chunks.remove(&c) else { continue };
        if chunks.get(e).is_ok_and(|(_, task, ..)| task.is_some()) {
            stats.cancelled();
        }
        let children = chunks.get(e).ok().and_then(|(.., children)| children).map_or(0, |c| c.len());
        super::retire::retire(&mut commands, &mut streamer, e, children);
        streamer.loaded.remove(&c);
        streamer.current.remove(&c);
        despawned.write(ChunkDespawned { coord: c });
    }

    let pool = AsyncComputeTaskPool::get();
    let snapshot = *content;
    let threads = match settings.chunk_threads {
        ChunkThreads::AsyncCompute => Threads::Current,
        ChunkThreads::Rayon => Threads::Pool,
    };
    // Chunks of the map whose task starts this frame, with the level it builds.
    let mut started = HashSet::new();
    for (c, detail) in plan.start {
        // On a wrapping map, chunks standing for the same chunk of the map share one mesh of a
        // level: copy it when a twin shows the current one, wait while one is being built.
        let canonical = terrain.wrap_chunk(c).0;
        let twin = if started.contains(&(canonical, detail)) {
            Twin::Building
        } else {
            twin(&map, &streamer, &chunks, c, detail)
        };
        match twin {
            Twin::Building => continue,
            Twin::Showing(mesh, content, vertices, mesh_bytes) => {
                let chunk =
                    HexChunk { generation: Some(generation), vertices, mesh_bytes, detail, ..new_chunk(&terrain, c) };
                let shown = (mesh, content, chunk, chunk_transform(&terrain, c));
                let first = !streamer.loaded.contains(&c);
                let e = match streamer.chunks.get(&c) {
                    Some(&e) => commands.entity(e).insert(shown).id(),
                    None => commands.spawn((Name::new(format!("hex chunk {} {}", c.x, c.z)), shown)).id(),
                };
                streamer.chunks.insert(c, e);
                streamer.loaded.insert(c);
                streamer.current.insert(c);
                let event = ChunkSpawned { entity: e, coord: c, first };
                spawned.write(event);
                commands.trigger(event);
                continue;
            }
            Twin::None => {}
        }
        started.insert((canonical, detail));
        let task = ChunkTask {
            task: pool.spawn(build_chunk(terrain.clone(), c, generation, threads, snapshot, detail)),
            generation,
            requested: Instant::now(),
            detail,
        };
        stats.started();
        match streamer.chunks.get(&c) {
            // Replacing an older task drops it.
            Some(&e) => {
                commands.entity(e).insert(task);
            }
            None => {
                let e = commands
                    .spawn((
                        Name::new(format!("hex chunk {} {}", c.x, c.z)),
                        new_chunk(&terrain, c),
                        chunk_transform(&terrain, c),
                        task,
                    ))
                    .id();
                streamer.chunks.insert(c, e);
            }
        }
    }
    if streamer.wanted != plan.wanted {
        streamer.wanted = plan.wanted;
    }
    if streamer.detail != plan.detail {
        streamer.detail = plan.detail;
    }
}

/// What the twins of a chunk (chunks of a wrapping map standing for the same map chunk) offer it.
enum Twin {
    /// No twin shows or builds the current mesh (always, off a wrapping map).
    None,
    /// A twin's task builds the current mesh.
    Building,
    /// A twin shows the current mesh at the level wanted: its handle, content, vertices and
    /// bytes.
    Showing(Mesh3d, ChunkContent, usize, usize),
}

/// The chunk entities' streaming state, as [`stream`] reads it.
type ChunkQuery<'w, 's> = Query<
    'w,
    's,
    (
        &'static HexChunk,
        Option<&'static ChunkTask>,
        Option<&'static Mesh3d>,
        Option<&'static ChunkContent>,
        Option<&'static Children>,
    ),
>;

/// What `c`'s twins offer for the current map at level `detail`.
fn twin(map: &HexMap, streamer: &ChunkStreamer, chunks: &ChunkQuery, c: ChunkCoord, detail: Detail) -> Twin {
    let terrain = map.terrain();
    let (canonical, _) = terrain.wrap_chunk(c);
    if terrain.wrap().is_none() {
        return Twin::None;
    }
    let mut found = Twin::None;
    for (&other, &e) in &streamer.chunks {
        if other == c || terrain.wrap_chunk(other).0 != canonical {
            continue;
        }
        let Ok((chunk, task, mesh, content, _)) = chunks.get(e) else { continue };
        if let (true, true, Some(mesh)) = (map.is_current(c, chunk.generation), chunk.detail == detail, mesh) {
            return Twin::Showing(mesh.clone(), content.cloned().unwrap_or_default(), chunk.vertices, chunk.mesh_bytes);
        }
        if task.is_some_and(|t| map.is_current(c, Some(t.generation)) && t.detail == detail) {
            found = Twin::Building;
        }
    }
    found
}

/// A chunk's mesh origin in f64 (zero for a chunk outside the map, which has no mesh).
pub(super) fn chunk_origin(terrain: &Terrain, coord: ChunkCoord) -> DVec3 {
    terrain.chunk_origin(coord).map_or(DVec3::ZERO, DVec3::from_array)
}

/// A chunk entity's component before its first mesh.
fn new_chunk(terrain: &Terrain, coord: ChunkCoord) -> HexChunk {
    HexChunk {
        coord,
        origin: chunk_origin(terrain, coord),
        generation: None,
        vertices: 0,
        mesh_bytes: 0,
        detail: Detail::Full,
    }
}

/// A chunk's transform: its mesh origin (exact near the world's origin; far out, the
/// `big_space` feature places chunks in cells instead).
fn chunk_transform(terrain: &Terrain, coord: ChunkCoord) -> Transform {
    Transform::from_translation(chunk_origin(terrain, coord).as_vec3())
}

/// The body of a chunk task: core generation plus the Bevy mesh, the water surface and the
/// props, off the main thread. A coarse chunk is generated full (with the lattice points
/// coarsening needs), its water and props built from the full mesh, then coarsened.
async fn build_chunk(
    terrain: Arc<Terrain>,
    chunk: ChunkCoord,
    generation: u64,
    threads: Threads,
    snapshot: ContentRequest,
    detail: Detail,
) -> ChunkBuild {
    let options = GenerateOptions { diagnostics: detail == Detail::Coarse, threads };
    let Some(generated) = terrain.chunk_rect(chunk).map(|rect| terrain.generate(rect, options)) else {
        return ChunkBuild {
            generation,
            mesh: Mesh::new(bevy::mesh::PrimitiveTopology::TriangleList, default()),
            vertices: 0,
            mesh_bytes: 0,
            content: BuiltContent::empty(),
            detail,
        };
    };
    let content = BuiltContent::build(&terrain, &generated, snapshot, detail);
    let drawn = match detail {
        Detail::Full => generated,
        // Generated with diagnostics above, so never the fallback.
        Detail::Coarse => terrain.coarsen(&generated, false).unwrap_or(generated),
    };
    let vertices = drawn.buffers.vertex_count();
    let mesh_bytes = vertices * (12 + 12 + 8) + drawn.buffers.indices.len() * 4;
    ChunkBuild { generation, mesh: chunk_to_mesh(drawn), vertices, mesh_bytes, content, detail }
}
