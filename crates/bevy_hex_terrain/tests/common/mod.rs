//! Helpers shared by the headless `App` tests.
#![allow(dead_code, reason = "each test file uses its own subset")]

use std::collections::{HashMap, HashSet};
use std::time::Duration;

use bevy::asset::AssetPlugin;
use bevy::prelude::*;
use bevy_hex_terrain::HexTerrainPlugins;
use bevy_hex_terrain::prelude::*;

pub fn unbounded(chunk: (u32, u32)) -> MapConfig {
    MapConfig { size: MapSize::Unbounded, chunk_size: chunk, ..MapConfig::default() }
}

pub fn settings(radius: u32) -> HexStreamingSettings {
    HexStreamingSettings {
        load_radius: radius,
        prefetch: 1,
        unload_hysteresis: 1,
        max_inserts_per_frame: 16,
        max_tasks_in_flight: 16,
        ..default()
    }
}

/// A headless app: the terrain plugins showing `map` without the material (which the headless
/// build, `--no-default-features`, does not have), with the streaming `settings` inserted
/// before the plugins are added (a value inserted first is kept).
pub fn app_with(map: MapSource, settings: HexStreamingSettings, asset_dir: Option<&std::path::Path>) -> App {
    app_with_plugins(HexTerrainPlugins::new(map), settings, asset_dir)
}

/// As [`app_with`], with the plugins set up by the caller.
pub fn app_with_plugins(
    plugins: HexTerrainPlugins,
    settings: HexStreamingSettings,
    asset_dir: Option<&std::path::Path>,
) -> App {
    let mut app = App::new();
    // The tests reload files themselves (`AssetServer::reload`): the file watcher (on whenever
    // Bevy's `file_watcher` feature is, as in the examples' build) would add reloads of its own
    // at times that depend on the machine.
    let assets = AssetPlugin {
        file_path: asset_dir.map_or("assets".into(), |d| d.display().to_string()),
        watch_for_changes_override: Some(false),
        ..default()
    };
    app.add_plugins((MinimalPlugins, assets, TransformPlugin)).insert_resource(settings);
    #[cfg(feature = "render")]
    app.add_plugins(plugins.build().disable::<HexTerrainMaterialPlugin>());
    #[cfg(not(feature = "render"))]
    app.add_plugins(plugins);
    app
}

pub fn app(config: MapConfig, radius: u32) -> App {
    app_with(config.into(), settings(radius), None)
}

pub fn spawn_agent(app: &mut App, at: Vec3) -> Entity {
    app.world_mut().spawn((HexTerrainAgent::default(), Transform::from_translation(at))).id()
}

/// Updates until `done` holds, letting the task pool work between frames. The frame cap (20
/// seconds of sleep at the least) only catches a hang: a slow machine takes more frames, never
/// a different answer.
pub fn run_until(app: &mut App, what: &str, mut done: impl FnMut(&mut App) -> bool) {
    for _ in 0..20_000 {
        app.update();
        if done(app) {
            return;
        }
        std::thread::sleep(Duration::from_millis(1));
    }
    panic!("gave up waiting for {what}");
}

pub fn ready(app: &mut App) -> bool {
    let messages = app.world().resource::<Messages<TerrainSettled>>();
    let mut cursor = messages.get_cursor();
    cursor.read(messages).last().is_some_and(|r| r.generation == app.world().resource::<HexMap>().generation())
        && app.world_mut().query::<&bevy_hex_terrain::ChunkTask>().iter(app.world()).next().is_none()
}

/// Whether every loaded chunk shows all of its props and no dropped chunk's children remain
/// (props are spawned, and dropped chunks' children despawned, a budget a frame).
pub fn props_settled(app: &mut App) -> bool {
    app.world().get_resource::<bevy_hex_terrain::HexPropStats>().is_none_or(|s| s.pending == 0)
        && app.world().resource::<ChunkStreamer>().retiring_chunks() == 0
}

pub fn chunk_coords(app: &mut App) -> HashSet<ChunkCoord> {
    app.world_mut().query::<&HexChunk>().iter(app.world()).map(|c| c.coord).collect()
}

pub fn meshed_chunks(app: &mut App) -> HashMap<ChunkCoord, Handle<Mesh>> {
    app.world_mut().query::<(&HexChunk, &Mesh3d)>().iter(app.world()).map(|(c, m)| (c.coord, m.0.clone())).collect()
}

pub fn window(center: ChunkCoord, r: i32) -> HashSet<ChunkCoord> {
    (-r..=r).flat_map(|dz| (-r..=r).map(move |dx| ChunkCoord::new(center.x + dx, center.z + dz))).collect()
}

pub fn agent_chunk(app: &App, at: Vec3) -> ChunkCoord {
    let map = app.world().resource::<HexMap>();
    map.chunk_of(map.tile_at(at).unwrap()).unwrap()
}

/// Every message of type `M` sent so far (kept in a resource, so none is missed between updates).
#[derive(Resource)]
pub struct Seen<M: Message + Clone>(pub Vec<M>);

pub fn keep<M: Message + Clone>(app: &mut App) {
    app.insert_resource(Seen::<M>(Vec::new())).add_systems(Last, |mut r: MessageReader<M>, mut s: ResMut<Seen<M>>| {
        s.0.extend(r.read().cloned());
    });
}

pub fn seen<M: Message + Clone>(app: &App) -> Vec<M> {
    app.world().resource::<Seen<M>>().0.clone()
}

/// Hot-reloads the followed map file as the asset server would: its asset replaced by the same
/// config changed by `change`.
pub fn reload_asset(app: &mut App, change: impl FnOnce(&mut MapConfig)) {
    use bevy_hex_terrain::{HexMapAsset, HexMapHandle};
    let handle = app.world().resource::<HexMapHandle>().handle().unwrap().clone();
    let mut config = app.world().resource::<Assets<HexMapAsset>>().get(&handle).unwrap().config.clone();
    change(&mut config);
    app.world_mut()
        .resource_mut::<Assets<HexMapAsset>>()
        .insert(handle.id(), HexMapAsset { config, image: None, ruleset: None, appearance_fallback: false })
        .unwrap();
}
