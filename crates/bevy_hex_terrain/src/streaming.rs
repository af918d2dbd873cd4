//! Chunk streaming around tracked agents (thesis section 3.4, figure 9), with meshes built on
//! the async compute pool and inserted under a per-frame budget.

use std::collections::VecDeque;
use std::sync::Arc;

use bevy::platform::collections::HashMap;
use bevy::platform::time::Instant;
use bevy::prelude::*;
use bevy::tasks::futures::check_ready;
use bevy::tasks::{AsyncComputeTaskPool, Task};
use hex_terrain::{ChunkCoord, Terrain};

use crate::map::HexMap;
use crate::mesh::chunk_to_mesh;

/// Put this on any entity (a camera, a unit) to keep terrain generated around it. Several agents
/// may exist; chunks around each of them are kept.
///
/// With no agent at all, a bounded map is generated whole and an unbounded one around the
/// world origin.
#[derive(Component, Debug, Clone, Copy, Default, Reflect)]
#[reflect(Component, Default)]
pub struct HexTerrainAgent {
    /// Chunk radius kept around this agent, overriding [`HexTerrainSettings::load_radius`].
    pub radius: Option<u32>,
}

/// Streaming parameters.
#[derive(Resource, Debug, Clone, Reflect)]
#[reflect(Resource)]
pub struct HexTerrainSettings {
    /// Chunks within this many chunks (Chebyshev distance) of an agent exist.
    pub load_radius: u32,
    /// Extra ring generated ahead, so the ring an agent can reach next exists before it
    /// arrives.
    pub prefetch: u32,
    /// Chunks are dropped only beyond `load_radius + prefetch + unload_hysteresis`, so an agent
    /// pacing on a chunk border does not make chunks blink.
    pub unload_hysteresis: u32,
    /// Finished meshes inserted per frame at most (the rest wait for the next frame).
    pub max_inserts_per_frame: usize,
    /// Chunk tasks running at once at most; the nearest missing chunks go first.
    pub max_tasks_in_flight: usize,
}

impl Default for HexTerrainSettings {
    fn default() -> Self {
        Self { load_radius: 2, prefetch: 1, unload_hysteresis: 1, max_inserts_per_frame: 4, max_tasks_in_flight: 8 }
    }
}

/// A terrain chunk entity.
#[derive(Component, Debug, Clone, Reflect)]
#[reflect(Component)]
pub struct HexChunk {
    /// Chunk column and row.
    pub coord: IVec2,
    /// Map generation of the mesh it shows (see [`HexMap::generation`]); `None` until its first
    /// mesh arrives.
    pub generation: Option<u64>,
    /// Vertices of its mesh.
    pub vertices: usize,
    /// Bytes of its mesh's vertex and index data.
    pub mesh_bytes: usize,
}

impl HexChunk {
    /// The chunk coordinate.
    #[must_use]
    pub fn chunk(&self) -> ChunkCoord {
        ChunkCoord::new(self.coord.x, self.coord.y)
    }
}

/// What a chunk task returns.
pub struct ChunkBuild {
    generation: u64,
    mesh: Mesh,
    vertices: usize,
    mesh_bytes: usize,
}

/// A chunk mesh being built on the async compute pool. Dropping it (despawning the chunk)
/// cancels the work.
#[derive(Component)]
pub struct ChunkTask {
    task: Task<ChunkBuild>,
    generation: u64,
    requested: Instant,
}

/// A chunk's mesh was inserted (first time or regenerated).
#[derive(Message, Debug, Clone, Copy, Reflect)]
pub struct ChunkSpawned {
    /// The chunk entity.
    pub entity: Entity,
    /// Chunk column and row.
    pub coord: IVec2,
}

/// A chunk left the world.
#[derive(Message, Debug, Clone, Copy, Reflect)]
pub struct ChunkDespawned {
    /// Chunk column and row.
    pub coord: IVec2,
}

/// Every wanted chunk has its mesh for the current map generation: units can be placed.
/// Sent each time the terrain settles (at start, after an agent moved on, after a reload).
#[derive(Message, Debug, Clone, Copy, Reflect)]
pub struct TerrainReady {
    /// The map generation now complete.
    pub generation: u64,
}

/// Streaming bookkeeping and figures.
#[derive(Resource, Debug, Default)]
pub struct ChunkStreamer {
    chunks: HashMap<ChunkCoord, Entity>,
    wanted: HashMap<ChunkCoord, u32>,
    /// Chunks showing a mesh of `current_generation`.
    current: bevy::platform::collections::HashSet<ChunkCoord>,
    current_generation: u64,
    /// Whether every wanted chunk was current at the end of the last frame.
    settled: bool,
    /// Request-to-insert latency of recent chunks, in seconds (last 1024).
    pub latencies: VecDeque<f32>,
    /// Chunk tasks started so far.
    pub tasks_started: u64,
    /// Chunk tasks dropped before finishing (their chunk was no longer wanted).
    pub tasks_cancelled: u64,
}

impl ChunkStreamer {
    /// Chunk entities alive.
    #[must_use]
    pub fn live_chunks(&self) -> usize {
        self.chunks.len()
    }

    /// The entity of a chunk, if it exists.
    #[must_use]
    pub fn entity(&self, chunk: ChunkCoord) -> Option<Entity> {
        self.chunks.get(&chunk).copied()
    }

    /// Chunks wanted around the agents last frame, with their distance to the nearest agent.
    pub fn wanted(&self) -> impl Iterator<Item = (ChunkCoord, u32)> + '_ {
        self.wanted.iter().map(|(&c, &d)| (c, d))
    }

    /// Decides which chunks must exist, starts tasks for missing or outdated ones (nearest
    /// first, a bounded number at a time) and despawns the ones left behind.
    pub(crate) fn update(
        mut commands: Commands,
        mut streamer: ResMut<ChunkStreamer>,
        mut map: ResMut<HexMap>,
        settings: Res<HexTerrainSettings>,
        agents: Query<(&GlobalTransform, &HexTerrainAgent)>,
        chunks: Query<(&HexChunk, Option<&ChunkTask>)>,
        mut despawned: MessageWriter<ChunkDespawned>,
    ) {
        if map.is_waiting_for_asset() {
            return;
        }
        let terrain = map.terrain().clone();
        let generation = map.generation();
        let ahead = settings.prefetch;
        let mut centers: Vec<(ChunkCoord, u32)> = agents
            .iter()
            .map(|(t, a)| {
                let p = t.translation();
                (terrain.chunk_of(terrain.tile_at(p.x, p.z)), a.radius.unwrap_or(settings.load_radius))
            })
            .collect();
        let mut wanted: HashMap<ChunkCoord, u32> = HashMap::default();
        if centers.is_empty() {
            if terrain.bounds().is_some() {
                wanted.extend(terrain.chunks().into_iter().map(|c| (c, 0)));
            } else {
                centers.push((ChunkCoord::default(), settings.load_radius));
            }
        }
        for &(center, radius) in &centers {
            let r = (radius + ahead) as i32;
            for dz in -r..=r {
                for dx in -r..=r {
                    let c = ChunkCoord::new(center.x + dx, center.z + dz);
                    if terrain.chunk_rect(c).is_none() {
                        continue;
                    }
                    let d = c.distance(center);
                    wanted.entry(c).and_modify(|e| *e = (*e).min(d)).or_insert(d);
                }
            }
        }

        // Drop chunks beyond every agent's keep distance (or outside the map after a reload).
        let keep = |c: ChunkCoord| {
            if terrain.chunk_rect(c).is_none() {
                return false;
            }
            if centers.is_empty() {
                return true;
            }
            centers.iter().any(|&(center, radius)| c.distance(center) <= radius + ahead + settings.unload_hysteresis)
        };
        let mut dropped = Vec::new();
        for (&c, &e) in &streamer.chunks {
            if !wanted.contains_key(&c) && !keep(c) {
                dropped.push((c, e));
            }
        }
        for (c, e) in dropped {
            streamer.chunks.remove(&c);
            if chunks.get(e).is_ok_and(|(_, task)| task.is_some()) {
                streamer.tasks_cancelled += 1;
            }
            if let Ok(mut entity) = commands.get_entity(e) {
                entity.despawn();
            }
            map.loaded.remove(&c);
            streamer.current.remove(&c);
            despawned.write(ChunkDespawned { coord: IVec2::new(c.x, c.z) });
        }

        // Start work for missing or outdated chunks, nearest first.
        let in_flight = chunks.iter().filter(|(_, t)| t.is_some_and(|t| t.generation == generation)).count();
        let mut budget = settings.max_tasks_in_flight.saturating_sub(in_flight);
        // Forget entities despawned by someone else.
        streamer.chunks.retain(|_, e| chunks.contains(*e));
        let mut todo: Vec<(u32, ChunkCoord)> = wanted
            .iter()
            .filter(|&(c, _)| match streamer.chunks.get(c).and_then(|&e| chunks.get(e).ok()) {
                None => true,
                Some((chunk, task)) => {
                    chunk.generation != Some(generation) && task.is_none_or(|t| t.generation != generation)
                }
            })
            .map(|(&c, &d)| (d, c))
            .collect();
        todo.sort_unstable_by_key(|&(d, c)| (d, c));
        let pool = AsyncComputeTaskPool::get();
        for (_, c) in todo {
            if budget == 0 {
                break;
            }
            budget -= 1;
            let task = ChunkTask {
                task: pool.spawn(build_chunk(terrain.clone(), c, generation)),
                generation,
                requested: Instant::now(),
            };
            streamer.tasks_started += 1;
            match streamer.chunks.get(&c) {
                // An outdated chunk keeps showing its old mesh until the new one arrives.
                Some(&e) => {
                    commands.entity(e).insert(task);
                }
                None => {
                    let coord = IVec2::new(c.x, c.z);
                    let e = commands
                        .spawn((
                            Name::new(format!("hex chunk {} {}", c.x, c.z)),
                            HexChunk { coord, generation: None, vertices: 0, mesh_bytes: 0 },
                            Transform::IDENTITY,
                            task,
                        ))
                        .id();
                    streamer.chunks.insert(c, e);
                }
            }
        }
        if streamer.wanted != wanted {
            streamer.wanted = wanted;
        }
    }

    /// Inserts finished meshes, at most [`HexTerrainSettings::max_inserts_per_frame`] a frame,
    /// and reports [`TerrainReady`] when these inserts make every wanted chunk current.
    #[expect(clippy::too_many_arguments, reason = "a system's parameters")]
    pub(crate) fn insert_ready(
        mut commands: Commands,
        mut streamer: ResMut<ChunkStreamer>,
        mut map: ResMut<HexMap>,
        settings: Res<HexTerrainSettings>,
        mut meshes: ResMut<Assets<Mesh>>,
        mut tasks: Query<(Entity, &mut HexChunk, &mut ChunkTask)>,
        mut spawned: MessageWriter<ChunkSpawned>,
        mut ready: MessageWriter<TerrainReady>,
    ) {
        let generation = map.generation();
        if streamer.current_generation != generation {
            streamer.current_generation = generation;
            streamer.current.clear();
        }
        // Settling is judged before and after this frame's inserts, so a reload or a newly wanted
        // chunk whose meshes all arrive within one frame is reported too.
        let complete = |s: &ChunkStreamer| !s.wanted.is_empty() && s.wanted.keys().all(|c| s.current.contains(c));
        let was_complete = complete(&streamer);
        let mut budget = settings.max_inserts_per_frame.max(1);
        for (entity, mut chunk, mut task) in &mut tasks {
            if budget == 0 {
                break;
            }
            let Some(build) = check_ready(&mut task.task) else { continue };
            let requested = task.requested;
            commands.entity(entity).remove::<ChunkTask>();
            if build.generation != generation {
                // Outdated by a reload while it ran; the next update starts a current one.
                continue;
            }
            budget -= 1;
            commands.entity(entity).insert(Mesh3d(meshes.add(build.mesh)));
            chunk.generation = Some(build.generation);
            chunk.vertices = build.vertices;
            chunk.mesh_bytes = build.mesh_bytes;
            map.loaded.insert(chunk.chunk());
            streamer.current.insert(chunk.chunk());
            if streamer.latencies.len() == 1024 {
                streamer.latencies.pop_front();
            }
            streamer.latencies.push_back(requested.elapsed().as_secs_f32());
            spawned.write(ChunkSpawned { entity, coord: chunk.coord });
        }

        let now = complete(&streamer);
        if now && !(was_complete && streamer.settled) {
            ready.write(TerrainReady { generation });
        }
        streamer.settled = now;
    }
}

/// The body of a chunk task: core generation plus the Bevy mesh, off the main thread.
async fn build_chunk(terrain: Arc<Terrain>, chunk: ChunkCoord, generation: u64) -> ChunkBuild {
    let Some(generated) = terrain.generate_chunk(chunk) else {
        return ChunkBuild {
            generation,
            mesh: Mesh::new(bevy::mesh::PrimitiveTopology::TriangleList, default()),
            vertices: 0,
            mesh_bytes: 0,
        };
    };
    let vertices = generated.buffers.vertex_count();
    let mesh_bytes = vertices * (12 + 12 + 8 + 8) + generated.buffers.indices.len() * 4;
    ChunkBuild { generation, mesh: chunk_to_mesh(generated), vertices, mesh_bytes }
}
