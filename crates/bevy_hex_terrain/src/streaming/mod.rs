//! Chunk streaming around tracked agents (thesis section 3.4, figure 9): which chunks exist
//! ([`planner`], a pure function), their meshes built on Bevy's async compute pool ([`tasks`])
//! and inserted under a per-frame budget ([`insert`]), with figures in [`HexStreamingStats`].

mod build;
pub(crate) mod content;
mod detail;
mod insert;
mod planner;
mod retire;
mod state;
mod stats;
mod tasks;

use bevy::platform::collections::{HashMap, HashSet};
use bevy::prelude::*;
use hex_terrain::{ChunkCoord, Detail};

pub use build::ChunkTask;
pub use content::ChunkContent;
pub(crate) use content::ContentRequest;
pub use detail::DETAIL_HYSTERESIS;
pub(crate) use planner::kept_at_most;
pub use retire::MAX_RETIRED_CHUNKS;
pub use stats::HexStreamingStats;

use crate::HexTerrainSystems;

/// Put this on any entity (a camera, a unit) to keep terrain generated around it. Several agents
/// may exist; chunks around each of them are kept.
///
/// With no agent at all, a bounded map is generated whole and an unbounded one around the
/// world origin.
#[derive(Component, Debug, Clone, Copy, Default, Reflect)]
#[reflect(Component, Default)]
#[require(Transform)]
pub struct HexTerrainAgent {
    /// Chunk radius kept around this agent, overriding [`HexStreamingSettings::load_radius`].
    pub radius: Option<u32>,
}

/// An entity's world position in f64, for agents (and cameras) far from the origin: streaming
/// reads it instead of the `GlobalTransform` when present. With the `big_space` feature, agents
/// and cameras in the terrain's grid get it from their cell and transform every frame.
#[derive(Component, Debug, Clone, Copy, Default, PartialEq, Reflect)]
#[reflect(Component, Default)]
pub struct HexWorldPosition(pub bevy::math::DVec3);

/// Where a chunk task's generation runs.
///
/// Hidden from the docs: only the streaming benchmark changes it, to compare one pool with two.
#[doc(hidden)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Reflect)]
pub enum ChunkThreads {
    /// Each chunk on the one thread of Bevy's async compute pool that runs its task: one pool
    /// for all chunk work.
    #[default]
    AsyncCompute,
    /// Each chunk task also spreads its generation over rayon's global pool (a second pool
    /// competing for the same cores; kept for comparison in the streaming benchmark).
    Rayon,
}

/// Streaming parameters.
#[derive(Resource, Debug, Clone, PartialEq, Reflect)]
#[reflect(Resource)]
pub struct HexStreamingSettings {
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
    /// Where a chunk's generation runs (the streaming benchmark's switch).
    #[doc(hidden)]
    pub chunk_threads: ChunkThreads,
    /// Children of dropped chunks (props, water surfaces) despawned per frame at most: a
    /// dropped chunk is hidden and forgotten at once, and despawned with its last child. At most
    /// 16 wait; beyond them the oldest goes whole.
    pub max_despawns_per_frame: usize,
    /// Level of detail: a chunk whose box is farther than this many hex sizes (multiples of the
    /// map's `layout.hex_size`) from every camera is drawn coarse ([`Detail::Coarse`]: a fan of
    /// six triangles a tile, its outline kept whole, so levels meet without a crack), and full
    /// again once nearer than `1 -` [`DETAIL_HYSTERESIS`] of it. Measured in 3D, so a camera
    /// zoomed out sees every chunk coarse. The cameras are every active `Camera` (with the
    /// `render` feature), or, without one, the [`HexTerrainAgent`]s. A level change is a chunk
    /// task like any other; the old mesh shows until the new one is ready. `None`: every
    /// chunk full.
    pub coarse_distance: Option<f32>,
}

/// The default [`HexStreamingSettings::coarse_distance`], in hex sizes.
pub const DEFAULT_COARSE_DISTANCE: f32 = 52.0;

impl Default for HexStreamingSettings {
    fn default() -> Self {
        Self {
            load_radius: 2,
            prefetch: 1,
            unload_hysteresis: 1,
            max_inserts_per_frame: 4,
            max_tasks_in_flight: 8,
            chunk_threads: ChunkThreads::default(),
            max_despawns_per_frame: 64,
            coarse_distance: Some(DEFAULT_COARSE_DISTANCE),
        }
    }
}

/// A terrain chunk entity.
#[derive(Component, Debug, Clone, Reflect)]
#[reflect(Component)]
#[require(Transform)]
#[cfg_attr(feature = "render", require(Visibility))]
pub struct HexChunk {
    /// Chunk column and row. On a wrapping map, chunks past the map's east or west edge have
    /// their own coordinates and show the mesh of the map's chunk they stand for
    /// ([`Terrain::wrap_chunk`](hex_terrain::Terrain::wrap_chunk)), generated once for all.
    pub coord: ChunkCoord,
    /// World position of the chunk's mesh origin, in f64 (the entity's `Transform` holds it in
    /// f32; with the `big_space` feature, its cell and a small transform).
    pub origin: bevy::math::DVec3,
    /// Map generation of the mesh it shows (see [`HexMap::generation`](crate::HexMap::generation));
    /// `None` until its first mesh arrives.
    pub generation: Option<u64>,
    /// Vertices of its mesh.
    pub vertices: usize,
    /// Bytes of its mesh's vertex and index data.
    pub mesh_bytes: usize,
    /// The level of detail of its mesh (see [`HexStreamingSettings::coarse_distance`]).
    pub detail: Detail,
}

/// A chunk's mesh was inserted: the first time (`first`), or again after an edit, a hot reload
/// or a level-of-detail change. Sent as a message (read every chunk's with a
/// `MessageReader<ChunkSpawned>`) and triggered as an entity event on the chunk entity (observe
/// one chunk with `commands.entity(chunk).observe(|event: On<ChunkSpawned>| ...)`, or all with
/// a global observer).
#[derive(Message, EntityEvent, Debug, Clone, Copy, PartialEq, Reflect)]
pub struct ChunkSpawned {
    /// The chunk entity.
    pub entity: Entity,
    /// Chunk column and row.
    pub coord: ChunkCoord,
    /// Whether this is the entity's first mesh (false when it is rebuilt).
    pub first: bool,
}

/// A chunk left the world.
#[derive(Message, Debug, Clone, Copy, Reflect)]
pub struct ChunkDespawned {
    /// Chunk column and row.
    pub coord: ChunkCoord,
}

/// A map's terrain is on screen for the first time: every wanted chunk shows its mesh. Sent
/// once per map taking effect (per [`HexMap::map_id`](crate::HexMap::map_id): the plugin's
/// first map, [`LoadHexMap`](crate::LoadHexMap)), never for the placeholder shown while a map
/// file loads (it streams nothing), never again for the same map's edits, hot reloads or newly
/// streamed chunks (those are [`TerrainSettled`]). The place to put the players on the map. On
/// a globe ([`HexGlobePlugin`](crate::HexGlobePlugin)) the same per
/// [`HexGlobe::map_id`](crate::HexGlobe::map_id), the frame after the last chunk's mesh is in.
#[derive(Message, Debug, Clone, Copy, PartialEq, Eq, Reflect)]
pub struct TerrainReady {
    /// The map now on screen.
    pub map_id: u64,
    /// Its generation (see [`HexMap::generation`](crate::HexMap::generation)).
    pub generation: u64,
}

/// Every wanted chunk shows its mesh for the current map generation. Sent each time the terrain
/// settles: the first time for a map (with [`TerrainReady`], in the same frame), and again after
/// an edit, a hot reload or an agent moving on to new chunks.
#[derive(Message, Debug, Clone, Copy, PartialEq, Eq, Reflect)]
pub struct TerrainSettled {
    /// The map generation now complete.
    pub generation: u64,
}

/// Which chunks exist, which are wanted and which show a mesh: the streaming bookkeeping,
/// written by the streaming systems and read through its getters.
#[derive(Resource, Debug, Default, Reflect)]
#[reflect(Resource, Debug, Default)]
pub struct ChunkStreamer {
    chunks: HashMap<ChunkCoord, Entity>,
    wanted: HashMap<ChunkCoord, u32>,
    /// The level each wanted chunk is to be drawn at.
    detail: HashMap<ChunkCoord, Detail>,
    /// Chunks whose mesh is in the world (of any generation).
    loaded: HashSet<ChunkCoord>,
    /// Chunks showing a mesh of `current_generation`.
    current: HashSet<ChunkCoord>,
    current_generation: u64,
    /// Whether every wanted chunk was current at the end of the last frame.
    settled: bool,
    /// The map [`TerrainReady`] was last sent for.
    ready_map: Option<u64>,
    /// Dropped chunks whose children are being despawned.
    #[reflect(ignore)]
    retiring: retire::Retiring,
    /// The wanted chunks' boxes, which their level of detail is measured from.
    #[reflect(ignore)]
    boxes: detail::ChunkBoxes,
}

impl ChunkStreamer {
    /// Whether every wanted chunk showed the current map at the end of the last frame (the
    /// screenshot plugin waits for it).
    #[cfg(feature = "render")]
    pub(crate) fn is_settled(&self) -> bool {
        self.settled
    }

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

    /// The distance (in chunks) of a wanted chunk to the nearest agent, `None` if not wanted.
    #[must_use]
    pub fn wanted_distance(&self, chunk: ChunkCoord) -> Option<u32> {
        self.wanted.get(&chunk).copied()
    }

    /// The level of detail a wanted chunk is to be drawn at (its mesh may still show another
    /// while its new one is built), `None` if not wanted.
    #[must_use]
    pub fn wanted_detail(&self, chunk: ChunkCoord) -> Option<Detail> {
        self.detail.get(&chunk).copied()
    }

    /// Whether a chunk's mesh is in the world.
    #[must_use]
    pub fn is_chunk_loaded(&self, chunk: ChunkCoord) -> bool {
        self.loaded.contains(&chunk)
    }

    /// The chunks whose meshes are in the world.
    pub fn loaded_chunks(&self) -> impl Iterator<Item = ChunkCoord> + '_ {
        self.loaded.iter().copied()
    }

    /// Dropped chunks, hidden, whose children are still being despawned (see
    /// [`HexStreamingSettings::max_despawns_per_frame`]).
    #[must_use]
    pub fn retiring_chunks(&self) -> usize {
        self.retiring.len()
    }
}

/// Chunk streaming: [`ChunkStreamer`], [`HexStreamingStats`], the chunk messages, and the systems
/// in [`HexTerrainSystems::Stream`] and [`HexTerrainSystems::Insert`]. Needs [`HexMapPlugin`](crate::HexMapPlugin).
/// Its settings are the [`HexStreamingSettings`] resource: a value inserted before the plugin
/// is added is kept.
#[derive(Debug, Clone, Copy, Default)]
pub struct HexStreamingPlugin;

impl Plugin for HexStreamingPlugin {
    fn build(&self, app: &mut App) {
        if !app.is_plugin_added::<crate::HexMapPlugin>() {
            panic!("HexStreamingPlugin needs HexMapPlugin: add HexTerrainPlugins (or HexMapPlugin before it)");
        }
        if !app.world().contains_resource::<Assets<Mesh>>() {
            app.init_asset::<Mesh>();
        }
        app.init_resource::<HexStreamingSettings>()
            .init_resource::<ChunkStreamer>()
            .init_resource::<HexStreamingStats>()
            .init_resource::<ContentRequest>()
            .add_message::<ChunkSpawned>()
            .add_message::<ChunkDespawned>()
            .add_message::<TerrainReady>()
            .add_message::<TerrainSettled>()
            .register_type::<HexTerrainAgent>()
            .register_type::<HexWorldPosition>()
            .register_type::<HexStreamingSettings>()
            .register_type::<HexChunk>()
            .register_type::<ChunkContent>()
            .register_type::<ChunkSpawned>()
            .register_type::<ChunkDespawned>()
            .register_type::<TerrainReady>()
            .register_type::<TerrainSettled>()
            .register_type::<ChunkStreamer>()
            .register_type::<HexStreamingStats>()
            .add_systems(
                Update,
                (
                    (tasks::stream, retire::reap).chain().in_set(HexTerrainSystems::Stream),
                    insert::insert_ready.in_set(HexTerrainSystems::Insert),
                ),
            );
    }
}
