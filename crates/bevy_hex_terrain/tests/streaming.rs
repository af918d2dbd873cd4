//! Headless `App` tests (`MinimalPlugins` + `AssetPlugin`): streaming, seams, hot reload, queries.

use std::collections::HashMap;
use std::time::Duration;

use bevy::mesh::VertexAttributeValues;
use bevy::prelude::*;
use bevy_hex_terrain::hex_terrain::Terrain;
use bevy_hex_terrain::prelude::*;
use bevy_hex_terrain::{ChunkThreads, HexMapAsset, HexMapHandle};

mod common;

use common::*;

#[test]
fn chunks_appear_around_the_agent_and_only_there() {
    let mut app = app(unbounded((8, 8)), 1);
    let at = Vec3::new(30.0, 0.0, -20.0);
    spawn_agent(&mut app, at);
    run_until(&mut app, "terrain ready", ready);
    let center = agent_chunk(&app, at);
    // radius 1 plus the prefetch ring
    assert_eq!(chunk_coords(&mut app), window(center, 2));
    assert_eq!(meshed_chunks(&mut app).len(), 25);
    let streamer = app.world().resource::<ChunkStreamer>();
    assert_eq!(streamer.loaded_chunks().count(), 25);
}

#[test]
fn moving_spawns_ahead_and_despawns_behind() {
    let mut app = app(unbounded((8, 8)), 1);
    let agent = spawn_agent(&mut app, Vec3::ZERO);
    run_until(&mut app, "terrain ready", ready);
    // 8 columns of flat hexes are 12 world units; move 6 chunks east.
    let to = Vec3::new(6.0 * 12.0, 0.0, 0.0);
    app.world_mut().entity_mut(agent).insert(Transform::from_translation(to));
    run_until(&mut app, "terrain ready after the move", |app| {
        let c = agent_chunk(app, to);
        window(c, 2).is_subset(&meshed_chunks(app).keys().copied().collect()) && ready(app)
    });
    let center = agent_chunk(&app, to);
    let coords = chunk_coords(&mut app);
    assert!(window(center, 2).is_subset(&coords));
    // Nothing beyond radius + prefetch + hysteresis remains.
    for c in &coords {
        assert!((c.x - center.x).abs() <= 3 && (c.z - center.z).abs() <= 3, "stale chunk {c:?} kept");
    }
    assert!(!coords.contains(&ChunkCoord::new(0, 0)) || center.x <= 3, "the start chunk was dropped");
}

#[test]
fn long_walk_keeps_chunk_count_and_meshes_bounded() {
    let mut app = app(unbounded((4, 4)), 1);
    let agent = spawn_agent(&mut app, Vec3::ZERO);
    let mut max_live = 0;
    // 4 flat columns are 6 world units: 700 chunk steps east, 3500 chunks generated in all.
    // Each step waits for the chunks around the agent (however long the machine takes).
    for step in 0..700 {
        let at = Vec3::new(step as f32 * 6.0, 0.0, 0.0);
        app.world_mut().entity_mut(agent).insert(Transform::from_translation(at));
        run_until(&mut app, "the chunks around the agent", wanted_chunks_loaded);
        let live = app.world().resource::<ChunkStreamer>().live_chunks();
        max_live = max_live.max(live);
    }
    run_until(&mut app, "terrain ready at the end", ready);
    let started = app.world().resource::<HexStreamingStats>().tasks_started();
    assert!(started > 2000, "walked over {started} chunk builds");
    // radius + prefetch + hysteresis = 3: at most a 7x7 window.
    assert!(max_live <= 49, "live chunks peaked at {max_live}");
    for _ in 0..5 {
        app.update();
    }
    let meshes = app.world().resource::<Assets<Mesh>>().len();
    // A terrain and at most a water mesh a chunk.
    assert!(meshes <= 2 * 49, "{meshes} meshes alive: despawned chunks must free theirs");
}

#[test]
fn neighboring_chunks_share_identical_border_vertices() {
    let mut app = app(unbounded((6, 6)), 1);
    spawn_agent(&mut app, Vec3::ZERO);
    run_until(&mut app, "terrain ready", ready);
    let handles = meshed_chunks(&mut app);
    let meshes = app.world().resource::<Assets<Mesh>>();
    let terrain = app.world().resource::<HexMap>().terrain().clone();
    // Positions are relative to each chunk's origin: vertices meet at the same world position (to
    // a thousandth of a unit; they are a quarter unit apart), with the same height and normal bits.
    let vertices = |coord: ChunkCoord| -> HashMap<[i64; 2], (u32, [u32; 3])> {
        let [ox, _, oz] = terrain.chunk_origin(coord).unwrap();
        let mesh = meshes.get(&handles[&coord]).unwrap();
        let p = mesh.attribute(Mesh::ATTRIBUTE_POSITION).unwrap().as_float3().unwrap();
        let n = mesh.attribute(Mesh::ATTRIBUTE_NORMAL).unwrap().as_float3().unwrap();
        let key =
            |x: f32, z: f32| [((ox + f64::from(x)) * 1e3).round() as i64, ((oz + f64::from(z)) * 1e3).round() as i64];
        p.iter().zip(n).map(|(p, n)| (key(p[0], p[2]), (p[1].to_bits(), n.map(f32::to_bits)))).collect()
    };
    let mut shared_total = 0;
    for (a, b) in [
        (ChunkCoord::new(0, 0), ChunkCoord::new(1, 0)),
        (ChunkCoord::new(0, 0), ChunkCoord::new(0, 1)),
        (ChunkCoord::new(-1, -1), ChunkCoord::new(-1, 0)),
    ] {
        let (va, vb) = (vertices(a), vertices(b));
        let mut shared = 0;
        for (xz, bits) in &va {
            if let Some(other) = vb.get(xz) {
                assert_eq!(bits, other, "vertex at {xz:?} differs between chunks {a:?} and {b:?}");
                shared += 1;
            }
        }
        assert!(shared >= 6 * 2, "chunks {a:?} and {b:?} share {shared} vertices");
        shared_total += shared;
    }
    assert!(shared_total > 0);
}

#[test]
fn map_queries_agree_with_the_core_crate() {
    let config = MapConfig { size: MapSize::Bounded { x: 20, z: 14 }, chunk_size: (8, 8), ..MapConfig::default() };
    let mut app = app(config.clone(), 1);
    // No agent: a bounded map is generated whole.
    run_until(&mut app, "whole map ready", ready);
    assert_eq!(chunk_coords(&mut app).len(), 3 * 2);
    let core = Terrain::new(config).unwrap();
    let map = app.world().resource::<HexMap>();
    for tile in core.tiles().step_by(7) {
        assert_eq!(map.tile_info(tile).unwrap(), core.tile_info(tile).unwrap());
        let center = map.tile_center(tile).unwrap();
        assert_eq!(center.to_array(), core.tile_center(tile).unwrap().map(|v| v as f32));
        assert_eq!(map.tile_at(center).unwrap(), tile);
        assert!(map.contains(tile));
        assert_eq!(map.neighbors(tile).unwrap(), tile.all_neighbors().map(|n| map.contains(n).then_some(n)));
        // Each query's f32 and f64 forms agree.
        let normal = map.surface_normal(center).unwrap();
        assert_eq!(normal, map.surface_normal_f64(center.as_dvec3()).unwrap().as_vec3());
        let far = Vec3::new(center.x + 1000.0, 0.0, center.z);
        assert_eq!(map.wrap_near(center, far), map.wrap_near_f64(center.as_dvec3(), far.as_dvec3()).as_vec3());
        let ray = Ray3d::new(center + Vec3::new(2.0, 30.0, 1.0), Dir3::new(-Vec3::new(2.0, 30.0, 1.0)).unwrap());
        let hit = map.raycast(ray, 100.0).unwrap();
        assert_eq!(hit.tile, tile);
        assert!((hit.point - center).length() < 0.05);
        assert!(app.world().resource::<ChunkStreamer>().is_chunk_loaded(map.chunk_of(tile).unwrap()));
    }
    // Queries answer for tiles outside the map and far from any loaded chunk too.
    let far = Hex::new(500, -300);
    assert!(!map.contains(far));
    assert_eq!(map.tile_info(far).unwrap(), core.tile_info(far).unwrap());
}

#[test]
fn bounded_maps_never_spawn_chunks_outside() {
    let config = MapConfig { size: MapSize::Bounded { x: 20, z: 14 }, chunk_size: (8, 8), ..MapConfig::default() };
    let mut app = app(config.clone(), 2);
    // An agent at the map's corner and one far outside it.
    spawn_agent(&mut app, Vec3::ZERO);
    spawn_agent(&mut app, Vec3::new(-500.0, 0.0, 300.0));
    run_until(&mut app, "terrain ready", ready);
    let core = Terrain::new(config).unwrap();
    let coords = chunk_coords(&mut app);
    assert!(!coords.is_empty());
    for c in coords {
        assert!(core.chunk_rect(c).is_some(), "chunk {c:?} lies outside the map");
    }
}

#[test]
fn far_teleport_cancels_stale_work() {
    let mut s = settings(3);
    s.max_tasks_in_flight = 40;
    s.max_inserts_per_frame = 1;
    let mut app = app_with(unbounded((16, 16)).into(), s, None);
    let agent = spawn_agent(&mut app, Vec3::ZERO);
    app.update();
    let started = app.world().resource::<HexStreamingStats>().tasks_started();
    assert_eq!(started, 40, "a bounded number of tasks at once");
    let far = Vec3::new(100_000.0, 0.0, -80_000.0);
    app.world_mut().entity_mut(agent).insert(Transform::from_translation(far));
    app.update();
    app.update();
    let cancelled = app.world().resource::<HexStreamingStats>().tasks_cancelled();
    assert!(cancelled > 0, "work for the old place was dropped");
    let center = agent_chunk(&app, far);
    for c in chunk_coords(&mut app) {
        assert!((c.x - center.x).abs() <= 5 && (c.z - center.z).abs() <= 5, "stale chunk {c:?} survived the teleport");
    }
    run_until(&mut app, "terrain ready at the destination", ready);
}

/// A fresh asset folder of this test process.
fn asset_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("hex-terrain-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write(dir: &std::path::Path, name: &str, text: &str) {
    std::fs::write(dir.join(name), text).unwrap();
}

#[test]
fn hot_reload_regenerates_every_chunk_and_a_bad_edit_keeps_the_terrain() {
    let dir = asset_dir("plugin");
    write(&dir, "test.map.ron", "(seed: 5, size: Bounded(x: 16, z: 16), chunk_size: (8, 8))");
    let mut app = app_with("test.map.ron".into(), HexStreamingSettings::default(), Some(&dir));
    run_until(&mut app, "first map", |app| app.world().resource::<HexMap>().config().seed == 5 && ready(app));
    let first = meshed_chunks(&mut app);
    assert_eq!(first.len(), 4);
    let generation = app.world().resource::<HexMap>().generation();

    // An edit: the asset changes, every chunk gets a mesh of the new generation.
    reload_asset(&mut app, |config| {
        config.seed = 6;
    });
    run_until(&mut app, "reloaded map", |app| {
        let g = app.world().resource::<HexMap>().generation();
        g > generation && ready(app)
    });
    let reloaded = app.world().resource::<HexMap>().generation();
    for chunk in app.world_mut().query::<&HexChunk>().iter(app.world()) {
        assert_eq!(chunk.generation, Some(reloaded), "chunk {:?} regenerated", chunk.coord);
    }
    let second = meshed_chunks(&mut app);
    assert!(second.iter().all(|(c, h)| first[c] != *h), "new meshes replaced the old ones");

    // A broken edit: logged and reported, the terrain stays. The report is typed: malformed
    // RON, the file, the line and the column.
    write(&dir, "test.map.ron", "(seed: 7, size: Bounded(x: 16, z: 16), chunk_size: (8, 8)");
    app.world().resource::<AssetServer>().reload("test.map.ron");
    let mut malformed = None;
    run_until(&mut app, "the error report", |app| {
        let messages = app.world().resource::<Messages<HexMapError>>();
        let found = messages.get_cursor().read(messages).find(|m| matches!(m, HexMapError::Malformed { .. })).cloned();
        malformed = malformed.take().or(found);
        malformed.is_some()
    });
    for _ in 0..10 {
        app.update();
    }
    let map = app.world().resource::<HexMap>();
    assert_eq!(map.generation(), reloaded);
    assert_eq!(map.config().seed, 6);
    assert_eq!(meshed_chunks(&mut app), second, "the terrain is unchanged");
    match malformed {
        Some(HexMapError::Malformed { map, line, column, .. }) => {
            assert_eq!(map, "map test.map.ron");
            assert_eq!(line, 1);
            assert!(column > 1, "column {column}");
        }
        other => panic!("not a malformed-file error: {other:?}"),
    }

    // An out-of-range value is refused the same way, naming the field.
    write(&dir, "test.map.ron", "(seed: 8, size: Bounded(x: 16, z: 16), noise: (octaves: 0))");
    app.world().resource::<AssetServer>().reload("test.map.ron");
    let mut message = String::new();
    let mut field = None;
    run_until(&mut app, "the error report", |app| {
        let messages = app.world().resource::<Messages<HexMapError>>();
        if let Some(m) = messages.get_cursor().read(messages).find(|m| m.to_string().contains("octaves")) {
            message = m.to_string();
            field = m.field().map(String::from);
        }
        !message.is_empty()
    });
    assert!(message.contains("noise.octaves"), "{message}");
    assert_eq!(field.as_deref(), Some("noise.octaves"), "typed: the field");
    assert_eq!(app.world().resource::<HexMap>().config().seed, 6);

    // An out-of-range blend only affects looks: the map applies, clamped, with the flat-color
    // fallback flagged for the material.
    write(&dir, "test.map.ron", "(seed: 9, size: Bounded(x: 16, z: 16), chunk_size: (8, 8), appearance: (blend: 1.5))");
    app.world().resource::<AssetServer>().reload("test.map.ron");
    run_until(&mut app, "the clamped map", |app| app.world().resource::<HexMap>().config().seed == 9);
    let map = app.world().resource::<HexMap>();
    assert_eq!(map.config().appearance.blend, 1.0);
    assert!(map.appearance_fallback());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Counts the frames in which a system saw `HexMap` changed.
#[derive(Resource, Default)]
struct MapChanges(usize);

#[test]
fn streaming_never_marks_the_map_changed() {
    let mut app = app(unbounded((4, 4)), 1);
    app.init_resource::<MapChanges>().add_systems(
        Update,
        (|mut n: ResMut<MapChanges>| n.0 += 1).run_if(resource_changed::<HexMap>).after(HexTerrainSystems::Insert),
    );
    let agent = spawn_agent(&mut app, Vec3::ZERO);
    run_until(&mut app, "terrain ready", ready);
    // The first frame sees the resource as added; from here on only chunks change.
    app.world_mut().resource_mut::<MapChanges>().0 = 0;
    let before = app.world().resource::<HexStreamingStats>().meshes_inserted();
    // Each step waits for the chunks around the agent (not for a number of frames, which would
    // measure the machine's speed): the count of inserts is then the walk's, on any machine.
    for step in 1..40 {
        let at = Vec3::new(step as f32 * 6.0, 0.0, 0.0);
        app.world_mut().entity_mut(agent).insert(Transform::from_translation(at));
        run_until(&mut app, "the chunks around the agent", wanted_chunks_loaded);
    }
    let inserted = app.world().resource::<HexStreamingStats>().meshes_inserted() - before;
    assert!(inserted > 100, "chunks streamed in: {inserted}");
    assert_eq!(app.world().resource::<MapChanges>().0, 0, "HexMap was marked changed while streaming");
}

/// Every chunk the streamer wants (around the agents) has its mesh.
fn wanted_chunks_loaded(app: &mut App) -> bool {
    let streamer = app.world().resource::<ChunkStreamer>();
    streamer.wanted().next().is_some() && streamer.wanted().all(|(c, _)| streamer.is_chunk_loaded(c))
}

fn generation(app: &App) -> u64 {
    app.world().resource::<HexMap>().generation()
}

fn errors(app: &App) -> Vec<String> {
    let messages = app.world().resource::<Messages<HexMapError>>();
    messages.get_cursor().read(messages).map(ToString::to_string).collect()
}

#[test]
fn load_hex_map_switches_to_a_config_or_a_file_and_refuses_a_bad_one() {
    let dir = asset_dir("switch");
    write(&dir, "a.map.ron", "(seed: 21, size: Bounded(x: 8, z: 8), chunk_size: (8, 8))");
    write(&dir, "b.map.ron", "(seed: 22, size: Bounded(x: 12, z: 8), chunk_size: (8, 8))");
    let mut app = app_with("a.map.ron".into(), HexStreamingSettings::default(), Some(&dir));
    run_until(&mut app, "map a", |app| app.world().resource::<HexMap>().config().seed == 21 && ready(app));

    // A config applies at once and is streamed.
    let config = MapConfig { seed: 23, size: MapSize::Bounded { x: 10, z: 10 }, chunk_size: (8, 8), ..default() };
    app.world_mut().write_message(LoadHexMap(config.into()));
    run_until(&mut app, "the config", |app| app.world().resource::<HexMap>().config().seed == 23 && ready(app));
    assert_eq!(chunk_coords(&mut app).len(), 4);
    assert!(app.world().resource::<HexMapHandle>().handle().is_none(), "no file is followed");

    // A file is loaded, then applied.
    app.world_mut().write_message(LoadHexMap("b.map.ron".into()));
    run_until(&mut app, "map b", |app| app.world().resource::<HexMap>().config().seed == 22 && ready(app));
    assert_eq!(chunk_coords(&mut app).len(), 2);

    // Back to a file loaded before: no load event comes, it applies all the same.
    app.world_mut().write_message(LoadHexMap("a.map.ron".into()));
    run_until(&mut app, "map a again", |app| app.world().resource::<HexMap>().config().seed == 21 && ready(app));

    // A bad config is refused with its field named; the terrain stays.
    let g = generation(&app);
    let mut bad = MapConfig { seed: 24, ..default() };
    bad.noise.octaves = 0;
    app.world_mut().write_message(LoadHexMap(bad.into()));
    run_until(&mut app, "the refusal", |app| errors(app).iter().any(|m| m.contains("noise.octaves")));
    assert_eq!(generation(&app), g);
    assert_eq!(app.world().resource::<HexMap>().config().seed, 21);

    // A missing file is refused too.
    app.world_mut().write_message(LoadHexMap("no_such.map.ron".into()));
    run_until(&mut app, "the missing file", |app| errors(app).iter().any(|m| m.contains("no_such")));
    for _ in 0..5 {
        app.update();
    }
    assert_eq!(generation(&app), g);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn chunk_tasks_on_rayon_give_the_same_meshes() {
    let config = MapConfig { size: MapSize::Bounded { x: 20, z: 14 }, chunk_size: (8, 8), ..MapConfig::default() };
    let mut meshes = Vec::new();
    for threads in [ChunkThreads::AsyncCompute, ChunkThreads::Rayon] {
        let mut s = settings(1);
        s.chunk_threads = threads;
        let mut app = app_with(config.clone().into(), s, None);
        run_until(&mut app, "whole map ready", ready);
        let handles = meshed_chunks(&mut app);
        let assets = app.world().resource::<Assets<Mesh>>();
        let mut positions: Vec<(ChunkCoord, Vec<[f32; 3]>)> = handles
            .iter()
            .map(|(c, h)| {
                let p = assets.get(h).unwrap().attribute(Mesh::ATTRIBUTE_POSITION).unwrap().as_float3().unwrap();
                (*c, p.to_vec())
            })
            .collect();
        positions.sort_by_key(|(c, _)| *c);
        meshes.push(positions);
    }
    assert_eq!(meshes[0].len(), 6);
    assert_eq!(meshes[0], meshes[1]);
}

#[test]
fn reload_teleport_and_switch_in_one_frame_leave_only_the_new_state() {
    let dir = asset_dir("race");
    write(&dir, "a.map.ron", "(seed: 31, size: Unbounded, chunk_size: (8, 8))");
    write(&dir, "b.map.ron", "(seed: 32, size: Unbounded, chunk_size: (8, 8), terrain: (inner_rings: 2))");
    let mut s = settings(2);
    s.max_inserts_per_frame = 2;
    let mut app = app_with("a.map.ron".into(), s, Some(&dir));
    let agent = spawn_agent(&mut app, Vec3::ZERO);
    run_until(&mut app, "map a", |app| app.world().resource::<HexMap>().config().seed == 31 && ready(app));
    let start = app.world().resource::<HexStreamingStats>().tasks_started();
    // Send a reload of map a, so tasks of a new generation are in flight...
    let handle = app.world().resource::<HexMapHandle>().handle().unwrap().clone();
    let mut config = app.world().resource::<Assets<HexMapAsset>>().get(&handle).unwrap().config.clone();
    config.seed = 33;
    let reloaded = HexMapAsset { config: config.clone(), image: None, ruleset: None, appearance_fallback: false };
    app.world_mut().resource_mut::<Assets<HexMapAsset>>().insert(handle.id(), reloaded.clone()).unwrap();
    run_until(&mut app, "reload tasks", |app| app.world().resource::<HexStreamingStats>().tasks_started() > start);
    assert!(app.world_mut().query::<&bevy_hex_terrain::ChunkTask>().iter(app.world()).next().is_some());
    // ...then, in one frame: another reload, a far teleport and a switch to map b.
    config.seed = 34;
    let again = HexMapAsset { config, image: None, ruleset: None, appearance_fallback: false };
    app.world_mut().resource_mut::<Assets<HexMapAsset>>().insert(handle.id(), again).unwrap();
    let far = Vec3::new(9_000.0, 0.0, -7_000.0);
    app.world_mut().entity_mut(agent).insert(Transform::from_translation(far));
    app.world_mut().write_message(LoadHexMap("b.map.ron".into()));
    run_until(&mut app, "map b at the destination", |app| {
        app.world().resource::<HexMap>().config().seed == 32 && ready(app)
    });
    for _ in 0..5 {
        app.update();
    }

    // Exactly the chunks of map b around the agent, every one of the current generation, every
    // mesh the one the core makes for map b.
    let map = app.world().resource::<HexMap>();
    let (terrain, generation) = (map.terrain().clone(), map.generation());
    let center = terrain.chunk_of(terrain.tile_at(f64::from(far.x), f64::from(far.z)).unwrap()).unwrap();
    assert_eq!(chunk_coords(&mut app), window(center, 3), "radius 2 plus the prefetch ring");
    for chunk in app.world_mut().query::<&HexChunk>().iter(app.world()) {
        assert_eq!(chunk.generation, Some(generation), "chunk {:?} is of an old map", chunk.coord);
    }
    let handles = meshed_chunks(&mut app);
    assert_eq!(handles.len(), 49);
    let levels: HashMap<ChunkCoord, Detail> =
        app.world_mut().query::<&HexChunk>().iter(app.world()).map(|c| (c.coord, c.detail)).collect();
    let meshes = app.world().resource::<Assets<Mesh>>();
    for (coord, handle) in &handles {
        let mesh = meshes.get(handle).unwrap();
        let positions = mesh.attribute(Mesh::ATTRIBUTE_POSITION).unwrap().as_float3().unwrap();
        // The core's mesh of map b at the level the chunk is drawn at.
        let expected = terrain.generate_chunk_detail(*coord, levels[coord]).unwrap();
        assert_eq!(positions, expected.buffers.positions.as_slice(), "chunk {coord:?} shows a stale mesh");
    }
    assert!(errors(&app).is_empty(), "{:?}", errors(&app));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Every [`HexMapError`] message of the run.
#[derive(Resource, Default)]
struct AllErrors(Vec<String>);

/// Collects every [`HexMapError`] into [`AllErrors`].
fn keep_errors(app: &mut App) {
    app.init_resource::<AllErrors>().add_systems(
        Last,
        |mut r: MessageReader<HexMapError>, mut all: ResMut<AllErrors>| {
            all.0.extend(r.read().map(ToString::to_string));
        },
    );
}

#[test]
fn a_file_reload_applies_once_and_a_broken_one_is_reported_once() {
    let dir = asset_dir("once");
    write(&dir, "once.map.ron", "(seed: 41, size: Bounded(x: 8, z: 8), chunk_size: (8, 8))");
    let mut app = app_with("once.map.ron".into(), HexStreamingSettings::default(), Some(&dir));
    keep_errors(&mut app);
    run_until(&mut app, "the map", |app| app.world().resource::<HexMap>().config().seed == 41 && ready(app));
    let g = generation(&app);
    let settle = |app: &mut App| {
        for _ in 0..40 {
            app.update();
            std::thread::sleep(Duration::from_millis(5));
        }
    };

    // Bevy announces a reload as Modified and again as LoadedWithDependencies: one new generation.
    write(&dir, "once.map.ron", "(seed: 42, size: Bounded(x: 8, z: 8), chunk_size: (8, 8))");
    app.world().resource::<AssetServer>().reload("once.map.ron");
    run_until(&mut app, "the reload", |app| app.world().resource::<HexMap>().config().seed == 42 && ready(app));
    settle(&mut app);
    assert_eq!(generation(&app), g + 1, "one reload, one regeneration");

    // Bevy retries a failed reload once: one report.
    write(&dir, "once.map.ron", "(seed: 43, size Bounded(x: 8, z: 8))");
    app.world().resource::<AssetServer>().reload("once.map.ron");
    run_until(&mut app, "the report", |app| !app.world().resource::<AllErrors>().0.is_empty());
    settle(&mut app);
    let reported = &app.world().resource::<AllErrors>().0;
    assert_eq!(reported.len(), 1, "{reported:?}");
    assert!(reported[0].contains("1:"), "{}", reported[0]);
    assert_eq!(generation(&app), g + 1);

    // Fixed, then broken the same way again: reported again.
    write(&dir, "once.map.ron", "(seed: 44, size: Bounded(x: 8, z: 8), chunk_size: (8, 8))");
    app.world().resource::<AssetServer>().reload("once.map.ron");
    run_until(&mut app, "the fix", |app| app.world().resource::<HexMap>().config().seed == 44 && ready(app));
    // Bevy announces the fixed file twice (Modified, then LoadedWithDependencies), maybe frames
    // apart: let both arrive before breaking it again, or the late one counts as a new load
    // between the failure and its retry.
    settle(&mut app);
    write(&dir, "once.map.ron", "(seed: 43, size Bounded(x: 8, z: 8))");
    app.world().resource::<AssetServer>().reload("once.map.ron");
    run_until(&mut app, "the second report", |app| app.world().resource::<AllErrors>().0.len() == 2);
    settle(&mut app);
    assert_eq!(app.world().resource::<AllErrors>().0.len(), 2);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn hostile_heightmap_paths_in_a_map_file_are_refused_and_keep_the_terrain() {
    let dir = asset_dir("hostile");
    write(&dir, "good.map.ron", "(seed: 51, size: Bounded(x: 8, z: 8), chunk_size: (8, 8))");
    write(&dir, "text.png", "this is not a PNG");
    let mut app = app_with("good.map.ron".into(), HexStreamingSettings::default(), Some(&dir));
    keep_errors(&mut app);
    run_until(&mut app, "the good map", |app| app.world().resource::<HexMap>().config().seed == 51 && ready(app));
    let g = generation(&app);
    for (i, path) in ["../outside.png", "missing.png", "text.png", "a.png#label", "/dev/zero", "::"].iter().enumerate()
    {
        let name = format!("hostile{i}.map.ron");
        write(&dir, &name, &format!("(size: Bounded(x: 8, z: 8), source: Image(path: {path:?}, sea_level: 0.3))"));
        app.world_mut().write_message(LoadHexMap(name.clone().into()));
        run_until(&mut app, "the refusal", |app| {
            app.world().resource::<AllErrors>().0.iter().any(|m| m.contains(&name))
        });
        assert_eq!(generation(&app), g, "{path}: the terrain stays");
        assert_eq!(app.world().resource::<HexMap>().config().seed, 51);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A bounded map with climate, rivers and lakes: the plugin's queries give the core's biomes,
/// rivers and lakes, and every chunk mesh carries the core's vertex colors (sRGB to linear,
/// water in alpha), whichever chunk a vertex is in.
#[test]
fn climate_and_river_maps_give_biomes_rivers_lakes_and_vertex_colors() {
    let mut config = MapConfig { size: MapSize::Bounded { x: 30, z: 22 }, chunk_size: (8, 8), ..MapConfig::default() };
    config.climate.enabled = true;
    config.rivers.enabled = true;
    config.rivers.threshold = 3.0;
    let mut app = app(config.clone(), 1);
    run_until(&mut app, "whole map ready", ready);
    let core = Terrain::new(config).unwrap();
    assert!(!core.rivers().is_empty(), "the test map has rivers");
    let map = app.world().resource::<HexMap>();
    for tile in core.tiles() {
        assert_eq!(map.tile_info(tile).unwrap(), core.tile_info(tile).unwrap());
        assert_eq!(map.river(tile), core.river(tile));
        assert_eq!(map.lake(tile), core.lake(tile));
    }
    let whole = core.generate_map().unwrap();
    // Chunk positions are relative to the chunk's origin: match vertices by world position,
    // to a thousandth of a unit (vertices are a quarter unit apart).
    let key = |x: f64, z: f64| [(x * 1e3).round() as i64, (z * 1e3).round() as i64];
    let expected: HashMap<[i64; 2], [u8; 4]> = whole
        .buffers
        .positions
        .iter()
        .zip(&whole.buffers.colors)
        .map(|(p, &c)| (key(f64::from(p[0]), f64::from(p[2])), c))
        .collect();
    let handles = meshed_chunks(&mut app);
    assert_eq!(handles.len(), 4 * 3);
    let meshes = app.world().resource::<Assets<Mesh>>();
    let mut wet = 0;
    for (&coord, handle) in &handles {
        let [ox, _, oz] = core.chunk_origin(coord).unwrap();
        let mesh = meshes.get(handle).unwrap();
        let p = mesh.attribute(Mesh::ATTRIBUTE_POSITION).unwrap().as_float3().unwrap();
        let Some(VertexAttributeValues::Float32x4(c)) = mesh.attribute(Mesh::ATTRIBUTE_COLOR) else {
            panic!("a chunk of a climate map has no vertex colors");
        };
        for (p, c) in p.iter().zip(c) {
            let [r, g, b, a] = expected[&key(ox + f64::from(p[0]), oz + f64::from(p[2]))];
            let linear = Color::srgb_u8(r, g, b).to_linear();
            assert_eq!([linear.red, linear.green, linear.blue, f32::from(a) / 255.0], *c);
            wet += usize::from(a > 0);
        }
    }
    assert!(wet > 0, "no vertex shows river or lake water");
}

/// The plugin's components bring what they need (`#[require]`): an agent spawned alone has a
/// transform, and every chunk, water surface and prop has a transform (and, with the renderer,
/// a visibility) without the plugin or the game inserting them.
#[test]
fn components_bring_what_they_need() {
    let mut app = app(MapConfig { size: MapSize::Bounded { x: 16, z: 16 }, chunk_size: (8, 8), ..default() }, 2);
    let agent = app.world_mut().spawn(HexTerrainAgent::default()).id();
    assert!(app.world().get::<Transform>(agent).is_some(), "an agent alone has a transform");
    run_until(&mut app, "terrain ready", ready);
    app.update();
    let world = app.world_mut();
    let chunks: Vec<Entity> = world.query_filtered::<Entity, With<HexChunk>>().iter(world).collect();
    let waters: Vec<Entity> = world.query_filtered::<Entity, With<HexWater>>().iter(world).collect();
    let props: Vec<Entity> = world.query_filtered::<Entity, With<HexProp>>().iter(world).collect();
    assert!(!chunks.is_empty() && !waters.is_empty(), "{} chunks, {} waters", chunks.len(), waters.len());
    for e in chunks.iter().chain(&waters).chain(&props) {
        assert!(world.get::<Transform>(*e).is_some(), "{e:?} has no transform");
        #[cfg(feature = "render")]
        assert!(world.get::<Visibility>(*e).is_some(), "{e:?} has no visibility");
    }
}
