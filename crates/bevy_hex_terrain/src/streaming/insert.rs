//! Inserting finished chunk meshes, under a per-frame budget, and reporting when the terrain
//! settles.

use bevy::prelude::*;
use bevy::tasks::futures::check_ready;

use super::content::ChunkContent;
use super::state::StreamState;
use super::{ChunkSpawned, ChunkStreamer, ChunkTask, HexChunk, TerrainReady, TerrainSettled};
use crate::map::GameSetUp;

/// Inserts finished meshes, at most [`HexStreamingSettings::max_inserts_per_frame`] a frame,
/// and reports [`TerrainSettled`] when these inserts make every wanted chunk current, with
/// [`TerrainReady`] the first time for a map.
pub(crate) fn insert_ready(
    mut commands: Commands,
    state: StreamState,
    mut meshes: ResMut<Assets<Mesh>>,
    mut tasks: Query<(Entity, &mut HexChunk, Option<&mut ChunkTask>)>,
    mut spawned: MessageWriter<ChunkSpawned>,
    mut messages: (MessageWriter<TerrainReady>, MessageWriter<TerrainSettled>, MessageWriter<GameSetUp>),
) {
    let StreamState { mut streamer, mut stats, map, settings } = state;
    let generation = map.generation();
    if streamer.current_generation != generation {
        // A new config changes every chunk, an edit some: those that are no longer current.
        let shown = streamer.current_generation;
        streamer.current_generation = generation;
        streamer.current.retain(|&c| map.is_current(c, Some(shown)));
    }
    // Settling is judged before and after this frame's inserts, so a reload or a newly wanted
    // chunk whose meshes all arrive within one frame is reported too.
    let complete = |s: &ChunkStreamer| !s.wanted.is_empty() && s.wanted.keys().all(|c| s.current.contains(c));
    let was_complete = complete(&streamer);
    let mut budget = settings.max_inserts_per_frame.max(1);
    let terrain = map.terrain().clone();
    // Meshes inserted this frame, by the chunk of the map they show and their level (wrapping
    // maps share them).
    let mut inserted: Vec<(hex_terrain::ChunkCoord, hex_terrain::Detail, Handle<Mesh>, ChunkContent, usize, usize)> =
        Vec::new();
    for (entity, mut chunk, task) in &mut tasks {
        if budget == 0 {
            break;
        }
        let Some(mut task) = task else { continue };
        let Some(build) = check_ready(&mut task.task) else { continue };
        let requested = task.requested;
        commands.entity(entity).remove::<ChunkTask>();
        if !map.is_current(chunk.coord, Some(build.generation)) {
            // Outdated by a reload or an edit while it ran; the next frame starts a current one.
            continue;
        }
        budget -= 1;
        let handle = meshes.add(build.mesh);
        let content = ChunkContent {
            water: build.content.water.map(|water| meshes.add(water)),
            water_triangles: build.content.water_triangles,
            props: build.content.props,
        };
        let canonical = terrain.wrap_chunk(chunk.coord).0;
        inserted.push((canonical, build.detail, handle.clone(), content.clone(), build.vertices, build.mesh_bytes));
        // A hot reload may move a chunk's origin (another hex size): place it again.
        chunk.origin = super::tasks::chunk_origin(&terrain, chunk.coord);
        commands.entity(entity).insert((Mesh3d(handle), content, Transform::from_translation(chunk.origin.as_vec3())));
        let first = chunk.generation.is_none();
        chunk.generation = Some(build.generation);
        chunk.vertices = build.vertices;
        chunk.mesh_bytes = build.mesh_bytes;
        chunk.detail = build.detail;
        streamer.loaded.insert(chunk.coord);
        streamer.current.insert(chunk.coord);
        stats.inserted(requested.elapsed().as_secs_f32());
        let event = ChunkSpawned { entity, coord: chunk.coord, first };
        spawned.write(event);
        commands.trigger(event);
    }

    // Copies of those chunks past a wrapping map's edge waiting for the mesh (at its level) show
    // it too.
    if terrain.wrap().is_some() && !inserted.is_empty() {
        for (entity, mut chunk, task) in &mut tasks {
            let canonical = terrain.wrap_chunk(chunk.coord).0;
            let detail = streamer.wanted_detail(chunk.coord).unwrap_or(chunk.detail);
            let Some(&(_, detail, ref handle, ref content, vertices, mesh_bytes)) =
                inserted.iter().find(|(c, d, ..)| *c == canonical && *d == detail)
            else {
                continue;
            };
            if map.is_current(chunk.coord, chunk.generation)
                || task.is_some_and(|t| map.is_current(chunk.coord, Some(t.generation)))
            {
                continue;
            }
            chunk.origin = super::tasks::chunk_origin(&terrain, chunk.coord);
            commands.entity(entity).insert((
                Mesh3d(handle.clone()),
                content.clone(),
                Transform::from_translation(chunk.origin.as_vec3()),
            ));
            let first = chunk.generation.is_none();
            chunk.generation = Some(generation);
            chunk.vertices = vertices;
            chunk.mesh_bytes = mesh_bytes;
            chunk.detail = detail;
            streamer.loaded.insert(chunk.coord);
            streamer.current.insert(chunk.coord);
            let event = ChunkSpawned { entity, coord: chunk.coord, first };
            spawned.write(event);
            commands.trigger(event);
        }
    }

    let now = complete(&streamer);
    if now && !(was_complete && streamer.settled) {
        let (ready, settled, set_up) = &mut messages;
        settled.write(TerrainSettled { generation });
        let map_id = map.map_id();
        if streamer.ready_map != Some(map_id) {
            streamer.ready_map = Some(map_id);
            ready.write(TerrainReady { map_id, generation });
            // A map that came with a setup: its starts are there too.
            if map.terrain().setup().is_some() {
                set_up.write(GameSetUp { map_id, generation });
            } else if map.terrain().bounds().is_some() {
                info!(
                    "hex terrain: map {:?} has no game setup (no `setup` in its file): send SetUpGame to place starts",
                    map.config().name
                );
            }
        }
    }
    if streamer.settled != now {
        streamer.settled = now;
    }
}
