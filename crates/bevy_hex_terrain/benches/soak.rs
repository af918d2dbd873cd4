//! Soak: an agent flies over an unbounded map for the equivalent of an hour of brisk play (at
//! least 10,000 chunk loads, 216,000 frames) with the whole look on (climate, relief, water
//! surfaces, props) and the game's tile state changing every frame (the fog follows the agent,
//! its territory grows along its path, the tile under it is hovered), and a hot reload of the
//! map file every few hundred chunks, one of them a broken edit, while the process's resident
//! memory is sampled. Headless: Bevy's default plugins with no window and no GPU backend, so the
//! terrain, water and prop materials, their assets and every chunk entity are those of a game;
//! only the drawing is left out.
//!
//! ```text
//! cargo bench --workspace --profile dev --bench soak [-- --chunks 10000]
//! ```
//!
//! Prints chunks loaded, reloads, resident memory (peak and current), live entities, mesh and
//! material assets, water surfaces, props, stored tiles and tasks in flight after warm-up, in
//! the middle and at the end, and fails when anything grows beyond noise after warm-up (memory
//! beyond what the stored tiles of the explored strip take), a task outlives the run, no water
//! or prop was shown, or an error other than the broken edit's is reported.

use std::time::{Duration, Instant};

use bevy::app::PluginsState;
use bevy::prelude::*;
use bevy::render::RenderPlugin;
use bevy::render::settings::WgpuSettings;
use bevy::window::ExitCondition;
use bevy::winit::WinitPlugin;
use bevy_hex_terrain::HexTerrainMaterial;
use bevy_hex_terrain::prelude::*;
use bevy_hex_terrain::{ChunkContent, ChunkTask, HexStreamingSettings};

/// Tiles around the agent in sight: the fog follows it.
const SIGHT: u32 = 3;
/// Bytes a stored tile may take (a sparse store's entry, its hash table's slack): the explored
/// strip is game state, not a leak.
const STORED_TILE_BYTES: f64 = 64.0;

/// Kibibytes of a `/proc/self/status` line (`VmRSS`, `VmHWM`).
fn status_kib(key: &str) -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix(key)?.trim_start_matches(':').trim().strip_suffix("kB")?.trim().parse().ok())
        .unwrap_or(0)
}

#[derive(Resource, Default)]
struct Errors(Vec<String>);

fn collect_errors(mut reader: MessageReader<HexMapError>, mut errors: ResMut<Errors>) {
    errors.0.extend(reader.read().map(ToString::to_string));
}

/// One sample of the counts that must stay flat.
#[derive(Debug, Clone, Copy)]
struct Sample {
    chunks: u64,
    reloads: u32,
    rss_mib: f64,
    peak_mib: f64,
    entities: u32,
    meshes: usize,
    materials: usize,
    tasks: usize,
    live: usize,
    water: usize,
    props: usize,
    /// Props the live chunks place (their content): every prop entity must be one of them.
    placed: usize,
    /// Props whose parent is not a live chunk.
    orphans: usize,
    stored: usize,
}

fn sample(app: &mut App, reloads: u32) -> Sample {
    // Props are spawned, and dropped chunks' children despawned, a budget a frame: let them
    // settle (the agent stands still meanwhile) so every prop can be matched with its chunk.
    for _ in 0..600 {
        let pending = app.world().resource::<bevy_hex_terrain::HexPropStats>().pending;
        if pending == 0 && app.world().resource::<ChunkStreamer>().retiring_chunks() == 0 {
            break;
        }
        app.update();
    }
    let tasks = app.world_mut().query::<&ChunkTask>().iter(app.world()).count();
    let water = app.world_mut().query::<&HexWater>().iter(app.world()).count();
    let props = app.world_mut().query::<&HexProp>().iter(app.world()).count();
    let placed = app.world_mut().query::<&ChunkContent>().iter(app.world()).map(|c| c.props.len()).sum();
    let mut parents = app.world_mut().query_filtered::<&ChildOf, With<HexProp>>();
    let parents: Vec<Entity> = parents.iter(app.world()).map(ChildOf::parent).collect();
    let orphans = parents.iter().filter(|&&p| app.world().get::<HexChunk>(p).is_none()).count();
    let world = app.world();
    Sample {
        chunks: world.resource::<HexStreamingStats>().meshes_inserted(),
        reloads,
        rss_mib: status_kib("VmRSS") as f64 / 1024.0,
        peak_mib: status_kib("VmHWM") as f64 / 1024.0,
        entities: world.entities().count_spawned(),
        meshes: world.resource::<Assets<Mesh>>().len(),
        materials: world.resource::<Assets<HexTerrainMaterial>>().len(),
        tasks,
        live: world.resource::<ChunkStreamer>().live_chunks(),
        water,
        props,
        placed,
        orphans,
        stored: world.resource::<TileStates>().stored_tiles(),
    }
}

const MAP: &str = "soak.map.ron";
/// An hour of play at 60 frames a second.
const PLAY_FRAMES: u64 = 60 * 3600;

fn map_text(seed: u32) -> String {
    format!(
        "(name: \"soak\", seed: {seed}, size: Unbounded, noise: (octaves: 8, scale: 60.0), chunk_size: (16, 16), \
         climate: (enabled: true), relief: (peaks: 0.6, ridges: 0.5, hills: 0.5))"
    )
}

/// With `RUST_BACKTRACE` set, the first error that captures a backtrace (the broken edit's)
/// loads and keeps the binary's debug info to symbolize it: about 700 MiB of a dev build, once.
/// That is not the terrain's memory, so the soak runs itself again without it.
fn rerun_without_backtraces() -> Option<i32> {
    let value = std::env::var("RUST_BACKTRACE").ok()?;
    if value == "0" {
        return None;
    }
    println!(
        "RUST_BACKTRACE={value}: running again with RUST_BACKTRACE=0 (backtrace symbolization is not terrain memory)"
    );
    let exe = std::env::current_exe().ok()?;
    let status =
        std::process::Command::new(exe).args(std::env::args().skip(1)).env("RUST_BACKTRACE", "0").status().ok()?;
    Some(status.code().unwrap_or(1))
}

/// The game's turn, every frame: what was visible becomes explored and the agent's
/// surroundings visible, its tile is hovered, and every 30 frames its ring becomes the territory
/// of one of eight players (a new one every 50 s of play).
fn play(app: &mut App, position: Vec3, frame: u64) {
    let Some(here) = app.world().resource::<HexMap>().tile_at(position) else { return };
    let mut states = app.world_mut().resource_mut::<TileStates>();
    states.hide_visible();
    for tile in here.range(SIGHT) {
        let _ = states.set_visibility(tile, FogState::Visible);
    }
    states.replace_highlight(Highlight::Hovered, [here]);
    if frame.is_multiple_of(30) {
        let owner = (frame / 3000 % 8) as u32;
        for tile in here.range(1) {
            let _ = states.set_owner(tile, Some(owner));
        }
    }
}

fn main() {
    if let Some(code) = rerun_without_backtraces() {
        std::process::exit(code);
    }
    let target: u64 =
        std::env::args().skip_while(|a| a != "--chunks").nth(1).and_then(|s| s.parse().ok()).unwrap_or(10_000);
    let dir = std::env::temp_dir().join(format!("hex-terrain-soak-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    std::fs::write(dir.join(MAP), map_text(1)).expect("the map file");

    let mut app = App::new();
    app.add_plugins(
        DefaultPlugins
            .set(AssetPlugin {
                file_path: dir.display().to_string(),
                watch_for_changes_override: Some(false),
                ..default()
            })
            .set(WindowPlugin { primary_window: None, exit_condition: ExitCondition::DontExit, ..default() })
            .set(RenderPlugin { render_creation: WgpuSettings { backends: None, ..default() }.into(), ..default() })
            .disable::<WinitPlugin>(),
    )
    .add_plugins(HexTerrainPlugins::new(MAP))
    .init_resource::<Errors>()
    .add_systems(Update, collect_errors);
    let agent = app.world_mut().spawn((HexTerrainAgent::default(), Transform::default())).id();
    while app.plugins_state() == PluginsState::Adding {
        bevy::tasks::tick_global_task_pools_on_main_thread();
    }
    app.finish();
    app.cleanup();

    // A 16-column chunk of flat hexes is 24 world units: the agent crosses one every 90 frames
    // (1.5 s at 60 fps), turning north for a stretch every 40 chunks so it does not only walk
    // along one row of the world.
    let chunk_width = 24.0;
    let started = Instant::now();
    let (mut reloads, mut broken_sent, mut next_reload) = (0u32, false, 300u64);
    let mut position = Vec3::ZERO;
    let mut frame = 0u64;
    let mut samples: Vec<(&str, Sample)> = Vec::new();
    // Resident memory every 500 chunk loads, to show its shape.
    let (mut series, mut next_point) = (Vec::new(), 0u64);
    loop {
        frame += 1;
        let leg = (frame / 90) % 48;
        let step = chunk_width / 90.0;
        if leg < 40 {
            position.x += step;
        } else {
            position.z -= step;
        }
        app.world_mut().entity_mut(agent).insert(Transform::from_translation(position));
        play(&mut app, position, frame);
        app.update();
        std::thread::sleep(Duration::from_micros(500));
        let chunks = app.world().resource::<HexStreamingStats>().meshes_inserted();
        if chunks >= next_reload {
            next_reload += 300;
            reloads += 1;
            // The seventh edit is broken: it must be reported and keep the terrain.
            let text = if reloads == 7 { map_text(reloads).replace("size:", "size") } else { map_text(reloads) };
            broken_sent |= reloads == 7;
            std::fs::write(dir.join(MAP), text).expect("the map file");
            app.world().resource::<AssetServer>().reload(MAP);
        }
        if chunks >= next_point {
            series.push(format!("{}k: {:.0}", chunks / 1000, status_kib("VmRSS") as f64 / 1024.0));
            next_point += 500;
        }
        if samples.is_empty() && chunks > 0 {
            samples.push(("start (first chunk)", sample(&mut app, reloads)));
        }
        if samples.len() == 1 && chunks >= target / 10 {
            samples.push(("after warm-up", sample(&mut app, reloads)));
        }
        if samples.len() == 2 && frame >= PLAY_FRAMES / 2 {
            samples.push(("middle", sample(&mut app, reloads)));
        }
        if chunks >= target && frame >= PLAY_FRAMES {
            break;
        }
    }
    // Let the last tasks land.
    for _ in 0..600 {
        app.update();
        std::thread::sleep(Duration::from_millis(1));
        if app.world_mut().query::<&ChunkTask>().iter(app.world()).next().is_none() {
            break;
        }
    }
    samples.push(("end", sample(&mut app, reloads)));
    let elapsed = started.elapsed().as_secs_f64();
    let _ = std::fs::remove_dir_all(&dir);

    let settings = HexStreamingSettings::default();
    println!(
        "soak: {target} chunk loads of 16x16 tiles, {frame} frames ({:.0} s of play at 60 fps) in {elapsed:.0} s, \
         load radius {} + prefetch {}",
        frame as f64 / 60.0,
        settings.load_radius,
        settings.prefetch
    );
    println!(
        "| when | chunks loaded | reloads | RSS | peak RSS | entities | mesh assets | material assets | water \
         surfaces | props | stored tiles | tasks in flight | live chunks |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|"
    );
    for (when, s) in &samples {
        println!(
            "| {when} | {} | {} | {:.0} MiB | {:.0} MiB | {} | {} | {} | {} | {} | {} | {} | {} |",
            s.chunks,
            s.reloads,
            s.rss_mib,
            s.peak_mib,
            s.entities,
            s.meshes,
            s.materials,
            s.water,
            s.props,
            s.stored,
            s.tasks,
            s.live
        );
    }
    println!("RSS (MiB) by chunk loads: {}", series.join(", "));
    let errors = &app.world().resource::<Errors>().0;
    println!("errors reported: {}", errors.len());
    for e in errors {
        println!("  {e}");
    }

    let (warm, end) = (samples[1].1, samples[samples.len() - 1].1);
    let mut failures = Vec::new();
    // Flat: no more than noise (a few chunks' worth of meshes, allocator slack) above warm-up,
    // besides the tiles the game stored (the explored strip, the territory).
    let state_mib = end.stored.saturating_sub(warm.stored) as f64 * STORED_TILE_BYTES / (1 << 20) as f64;
    if end.rss_mib > warm.rss_mib * 1.15 + 32.0 + state_mib {
        failures.push(format!(
            "resident memory grew from {:.0} to {:.0} MiB ({state_mib:.0} MiB of it allowed for {} more stored tiles)",
            warm.rss_mib,
            end.rss_mib,
            end.stored - warm.stored
        ));
    }
    if samples.iter().all(|(_, s)| s.water == 0) || samples.iter().all(|(_, s)| s.props == 0) {
        failures.push("no water surface or no prop was ever shown: the look was not whole".into());
    }
    let bound =
        |what: &str, w: usize, e: usize, slack: usize| (e > w + slack).then(|| format!("{what} grew from {w} to {e}"));
    // Props follow the landscape (a forest holds more than a sea, and every reload is another
    // seed): what must hold is that every prop belongs to a live chunk's content, and that the
    // other entities stay flat.
    let others = |s: &Sample| s.entities as usize - s.props - s.water;
    failures.extend(bound("entities other than props and water", others(&warm), others(&end), 16));
    for (when, s) in &samples {
        if s.props != s.placed || s.orphans != 0 {
            failures.push(format!("{when}: {} props for {} placed, {} without a chunk", s.props, s.placed, s.orphans));
        }
    }
    failures.extend(bound("mesh assets", warm.meshes, end.meshes, 16));
    failures.extend(bound("material assets", warm.materials, end.materials, 0));
    if end.tasks != 0 {
        failures.push(format!("{} chunk tasks still in flight at the end", end.tasks));
    }
    if !broken_sent || errors.len() != 1 || !errors[0].contains("malformed") {
        failures.push(format!("expected exactly the broken edit's error, got {errors:?}"));
    }
    if failures.is_empty() {
        println!("flat after warm-up, no task left, only the broken edit's error: pass");
    } else {
        for f in &failures {
            println!("FAIL: {f}");
        }
        std::process::exit(1);
    }
}
