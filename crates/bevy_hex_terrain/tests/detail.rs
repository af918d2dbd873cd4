//! Headless `App` tests of levels of detail: far chunks are drawn coarse, each chunk's mesh is
//! the core's at its level, a level change keeps the old mesh until the new one is in, twins of
//! a wrapping map share a mesh only at one level, and coarse chunks' props stand on the coarse
//! surface. Without a camera, levels are measured from the agents.

use std::collections::HashMap;

use bevy::prelude::*;
use bevy_hex_terrain::hex_terrain::{Detail, Terrain};
use bevy_hex_terrain::prelude::*;

mod common;

use common::*;

/// The app of [`common::app`], levels measured `coarse_distance` hex sizes out.
fn lod_app(config: MapConfig, radius: u32, coarse_distance: f32) -> App {
    let settings = HexStreamingSettings { coarse_distance: Some(coarse_distance), ..settings(radius) };
    app_with(config.into(), settings, None)
}

/// Every chunk with a mesh: its level and mesh positions' bits.
fn shown(app: &mut App) -> HashMap<ChunkCoord, (Detail, Vec<[u32; 3]>)> {
    let chunks: Vec<(ChunkCoord, Detail, Handle<Mesh>)> = app
        .world_mut()
        .query::<(&HexChunk, &Mesh3d)>()
        .iter(app.world())
        .map(|(c, m)| (c.coord, c.detail, m.0.clone()))
        .collect();
    let meshes = app.world().resource::<Assets<Mesh>>();
    chunks
        .into_iter()
        .map(|(c, d, h)| {
            let mesh = meshes.get(&h).unwrap();
            let p = mesh.attribute(Mesh::ATTRIBUTE_POSITION).unwrap().as_float3().unwrap();
            (c, (d, p.iter().map(|v| v.map(f32::to_bits)).collect()))
        })
        .collect()
}

/// The core's positions of a chunk at a level.
fn core_positions(terrain: &Terrain, chunk: ChunkCoord, detail: Detail) -> Vec<[u32; 3]> {
    let mesh = terrain.generate_chunk_detail(chunk, detail).unwrap();
    mesh.buffers.positions.iter().map(|v| v.map(f32::to_bits)).collect()
}

/// Every wanted chunk shows the level the streamer wants for it.
fn levels_settled(app: &mut App) -> bool {
    if !ready(app) {
        return false;
    }
    let streamer = app.world().resource::<ChunkStreamer>();
    let wanted: Vec<(ChunkCoord, Option<Detail>)> =
        streamer.wanted().map(|(c, _)| (c, streamer.wanted_detail(c))).collect();
    let shown = shown(app);
    wanted.iter().all(|(c, d)| shown.get(c).map(|s| Some(s.0)) == Some(*d))
}

#[test]
fn far_chunks_are_coarse_and_a_level_change_keeps_the_old_mesh_until_the_new_one() {
    let mut app = lod_app(unbounded((8, 8)), 3, 12.0);
    let agent = spawn_agent(&mut app, Vec3::new(6.0, 0.0, 6.0));
    run_until(&mut app, "levels settled", levels_settled);
    let terrain = app.world().resource::<HexMap>().terrain().clone();
    let before = shown(&mut app);
    let center = agent_chunk(&app, Vec3::new(6.0, 0.0, 6.0));
    let mut levels = [0; 2];
    for (c, (detail, positions)) in &before {
        assert_eq!(positions, &core_positions(&terrain, *c, *detail), "chunk {c:?} at {detail:?}");
        levels[*detail as usize] += 1;
        // 8 flat columns are 12 units, 8 rows 13.9: from (6, 6), the nearest point of a neighbor
        // chunk is at most 8.5 units away, of a chunk two out at least 17.
        match c.distance(center) {
            0 | 1 => assert_eq!(*detail, Detail::Full, "chunk {c:?} near the agent"),
            _ => assert_eq!(*detail, Detail::Coarse, "chunk {c:?} far from the agent"),
        }
    }
    assert!(levels[0] > 0 && levels[1] > 0, "levels {levels:?}");
    // A coarse chunk has far fewer triangles than a full one.
    let triangles = |app: &mut App, detail: Detail| -> f64 {
        let handles: Vec<Handle<Mesh>> = app
            .world_mut()
            .query::<(&HexChunk, &Mesh3d)>()
            .iter(app.world())
            .filter(|(c, _)| c.detail == detail)
            .map(|(_, m)| m.0.clone())
            .collect();
        let meshes = app.world().resource::<Assets<Mesh>>();
        let t: usize = handles.iter().map(|h| meshes.get(h).unwrap().indices().unwrap().len() / 3).sum();
        t as f64 / handles.len() as f64
    };
    let (coarse, full) = (triangles(&mut app, Detail::Coarse), triangles(&mut app, Detail::Full));
    assert!(coarse < 0.5 * full, "{coarse} vs {full} triangles a chunk");

    // Two chunks east: chunks switch levels. Every frame, every chunk that showed a mesh still
    // shows one (the old until the new is in), and no chunk is despawned for its level.
    let to = Vec3::new(6.0 + 24.0, 0.0, 6.0);
    app.world_mut().entity_mut(agent).insert(Transform::from_translation(to));
    let mut frames = 0;
    let mut despawned = Vec::new();
    run_until(&mut app, "levels settled after the move", |app| {
        frames += 1;
        let now = shown(app);
        let messages = app.world().resource::<Messages<bevy_hex_terrain::ChunkDespawned>>();
        despawned.extend(messages.iter_current_update_messages().map(|m| m.coord));
        for c in before.keys() {
            let kept = c.distance(agent_chunk(app, to)) <= 3 + 1;
            if kept && !despawned.contains(c) {
                assert!(now.contains_key(c), "chunk {c:?} lost its mesh in frame {frames}");
            }
        }
        frames > 2 && levels_settled(app)
    });
    let after = shown(&mut app);
    let center = agent_chunk(&app, to);
    assert_eq!(after[&center].0, Detail::Full);
    // Chunks that changed level show the core's mesh of their new level.
    let mut switched = 0;
    for (c, (detail, positions)) in &after {
        assert_eq!(positions, &core_positions(&terrain, *c, *detail), "chunk {c:?} at {detail:?} after the move");
        if before.get(c).is_some_and(|b| b.0 != *detail) {
            switched += 1;
        }
    }
    assert!(switched >= 6, "{switched} chunks changed level");
    assert!(!despawned.iter().any(|c| after.contains_key(c)), "a chunk was despawned to change its level");
}

#[test]
fn coarse_chunks_carry_their_props_on_the_coarse_surface() {
    let mut config = unbounded((8, 8));
    config.noise.scale = 40.0;
    let mut app = lod_app(config, 2, 12.0);
    app.insert_resource(HexPropSettings { max_per_chunk: 200, ..default() });
    spawn_agent(&mut app, Vec3::new(6.0, 0.0, 6.0));
    run_until(&mut app, "levels settled", levels_settled);
    run_until(&mut app, "props settled", props_settled);
    let terrain = app.world().resource::<HexMap>().terrain().clone();
    let chunks: Vec<(ChunkCoord, Detail, ChunkContent)> = app
        .world_mut()
        .query::<(&HexChunk, &ChunkContent)>()
        .iter(app.world())
        .map(|(c, content)| (c.coord, c.detail, content.clone()))
        .collect();
    let mut levels = [0; 2];
    for (c, detail, content) in chunks {
        let full = terrain
            .generate(terrain.chunk_rect(c).unwrap(), bevy_hex_terrain::hex_terrain::GenerateOptions::DIAGNOSTICS);
        let mut expected = terrain.props_on(&full, 200, 1.0, detail);
        expected.extend(terrain.marker_props(&full));
        assert_eq!(&content.props[..], &expected[..], "chunk {c:?} at {detail:?}");
        levels[detail as usize] += content.props.len();
    }
    assert!(levels[0] > 0 && levels[1] > 0, "props by level {levels:?}");
}

#[test]
fn twins_of_a_wrapping_map_share_a_mesh_only_at_one_level() {
    // 32 columns of 8: four chunk columns; chunk column 4 stands for column 0.
    let mut config = MapConfig { size: MapSize::Bounded { x: 32, z: 16 }, chunk_size: (8, 8), ..MapConfig::default() };
    config.wrap = true;
    let mut app = lod_app(config, 2, 20.0);
    // Over chunk column 3, near the east edge: column 4 (the copy of 0) is near, column 0 far.
    let at = Vec3::new(3.0 * 12.0 + 6.0, 0.0, 6.0);
    spawn_agent(&mut app, at);
    run_until(&mut app, "levels settled", levels_settled);
    let terrain = app.world().resource::<HexMap>().terrain().clone();
    let shown = shown(&mut app);
    let (near, far) = (ChunkCoord::new(4, 0), ChunkCoord::new(0, 0));
    assert_eq!(terrain.wrap_chunk(near).0, far);
    assert_eq!(shown[&near].0, Detail::Full);
    assert_eq!(shown[&far].0, Detail::Coarse);
    assert_eq!(shown[&near].1, core_positions(&terrain, far, Detail::Full));
    assert_eq!(shown[&far].1, core_positions(&terrain, far, Detail::Coarse));
    let handles = meshed_chunks(&mut app);
    assert_ne!(handles[&near], handles[&far]);
}

/// The prop entities and their heights, by chunk.
fn prop_entities(app: &mut App) -> HashMap<Entity, (Entity, f32)> {
    app.world_mut()
        .query::<(Entity, &ChildOf, &Transform, &HexProp)>()
        .iter(app.world())
        .map(|(e, parent, t, _)| (e, (parent.parent(), t.translation.y)))
        .collect()
}

#[test]
fn a_level_change_moves_the_props_in_place() {
    let mut config = unbounded((8, 8));
    config.noise.scale = 40.0;
    let mut app = lod_app(config, 2, 12.0);
    let budget = 16;
    app.insert_resource(HexPropSettings { max_per_chunk: 200, max_spawns_per_frame: budget, ..default() });
    let agent = spawn_agent(&mut app, Vec3::new(6.0, 0.0, 6.0));
    run_until(&mut app, "levels settled", levels_settled);
    run_until(&mut app, "props settled", props_settled);
    let levels = |app: &mut App| -> HashMap<Entity, Detail> {
        app.world_mut().query::<(Entity, &HexChunk)>().iter(app.world()).map(|(e, c)| (e, c.detail)).collect()
    };
    let (before, levels_before) = (prop_entities(&mut app), levels(&mut app));
    // One chunk east: a column of chunks turns full, another coarse, none is dropped.
    app.world_mut().entity_mut(agent).insert(Transform::from_translation(Vec3::new(18.0, 0.0, 6.0)));
    let count = |app: &mut App| app.world_mut().query::<&HexProp>().iter(app.world()).count();
    let retire = app.world().resource::<HexStreamingSettings>().max_despawns_per_frame;
    let (mut last, mut most, mut frames) = (count(&mut app), 0, 0);
    let mut step = |app: &mut App| {
        frames += 1;
        let now = count(app);
        most = most.max(now.abs_diff(last));
        last = now;
        frames
    };
    run_until(&mut app, "levels settled after the move", |app| step(app) > 2 && levels_settled(app));
    run_until(&mut app, "props settled after the move", |app| {
        step(app);
        props_settled(app)
    });
    assert!(most <= budget + retire, "{most} props came or went in one frame (budget {budget})");
    let (after, levels_after) = (prop_entities(&mut app), levels(&mut app));
    // Every chunk that changed level kept its prop entities, each moved onto its new surface.
    let mut moved = 0;
    let mut switched = 0;
    for (chunk, level) in &levels_after {
        if levels_before.get(chunk).is_none_or(|l| l == level) {
            continue;
        }
        switched += 1;
        let old: Vec<(&Entity, &(Entity, f32))> = before.iter().filter(|(_, (c, _))| c == chunk).collect();
        for (e, (_, y)) in old {
            let (_, now) =
                after.get(e).unwrap_or_else(|| panic!("prop {e} of a chunk that changed level was despawned"));
            moved += usize::from(now != y);
        }
    }
    assert!(switched >= 4, "{switched} chunks changed level");
    assert!(moved > 0, "no prop moved onto the new surface");
}
