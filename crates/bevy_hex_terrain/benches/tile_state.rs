//! Tile state benchmark on a headless App: the main-thread cost of the per-tile store. Three
//! apps in one process on the same 128 x 80 map (10,240 tiles, held whole by the GPU window):
//! the terrain plugins without the tile state plugin (the baseline, "today" before the store),
//! with it and no writes (a quiet frame), and with a game system rewriting the fog of 10,000
//! tiles every frame (every write a change, so every frame uploads). Prints frame-time
//! percentiles, the ratio to the baseline, the writes' own time and the bytes uploaded a frame.
//!
//! ```text
//! cargo bench --workspace --profile dev --bench tile_state [-- --frames 600]
//! ```

use std::time::{Duration, Instant};

use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;
use bevy_hex_terrain::{ChunkTask, HexTileStatePlugin, HexTileStateStats};

fn percentile(sorted: &[f64], p: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

#[derive(Clone, Copy, PartialEq)]
enum Mode {
    Baseline,
    Quiet,
    Fog,
}

/// Writer timings, ms.
#[derive(Resource, Default)]
struct WriteTimes(Vec<f64>);

/// Rewrites the fog of 10,000 tiles: visible on even frames, explored on odd ones.
fn rewrite_fog(map: Res<HexMap>, mut states: ResMut<TileStates>, mut times: ResMut<WriteTimes>, mut frame: Local<u32>) {
    let start = Instant::now();
    *frame += 1;
    let fog = if frame.is_multiple_of(2) { FogState::Visible } else { FogState::Explored };
    for tile in map.terrain().tiles().take(10_000) {
        let _ = states.set_visibility(tile, fog);
    }
    times.0.push(start.elapsed().as_secs_f64() * 1e3);
}

struct Run {
    frames: Vec<f64>,
    writes: Vec<f64>,
    bytes: Vec<usize>,
}

fn run(mode: Mode, frames: usize) -> Run {
    let config = MapConfig { size: MapSize::Bounded { x: 128, z: 80 }, chunk_size: (16, 16), ..MapConfig::default() };
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, AssetPlugin::default(), TransformPlugin));
    let mut plugins = HexTerrainPlugins::new(config).build().disable::<HexTerrainMaterialPlugin>();
    if mode == Mode::Baseline {
        plugins = plugins.disable::<HexTileStatePlugin>();
    }
    app.add_plugins(plugins).init_resource::<WriteTimes>();
    if mode == Mode::Fog {
        app.add_systems(Update, rewrite_fog.after(HexTerrainSystems::Tiles));
    }
    // The whole map first, so chunk work does not mix into the frames measured.
    for _ in 0..20_000 {
        app.update();
        let busy = app.world_mut().query::<&ChunkTask>().iter(app.world()).next().is_some();
        if !busy && app.world().resource::<ChunkStreamer>().live_chunks() == 40 {
            break;
        }
        std::thread::sleep(Duration::from_millis(1));
    }
    for _ in 0..30 {
        app.update();
    }
    app.world_mut().resource_mut::<WriteTimes>().0.clear();
    let mut run = Run { frames: Vec::new(), writes: Vec::new(), bytes: Vec::new() };
    for _ in 0..frames {
        let start = Instant::now();
        app.update();
        run.frames.push(start.elapsed().as_secs_f64() * 1e3);
        if let Some(stats) = app.world().get_resource::<HexTileStateStats>() {
            run.bytes.push(stats.last_upload_bytes);
        }
    }
    run.writes = std::mem::take(&mut app.world_mut().resource_mut::<WriteTimes>().0);
    run
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let frames = args.iter().position(|a| a == "--frames").and_then(|i| args.get(i + 1)?.parse().ok()).unwrap_or(600);
    println!("tile state: {frames} frames each, 128x80 map (10,240 tiles), headless, main thread");
    // Interleaved repeats, so a noisy neighbour hits every mode alike.
    let mut all: [Vec<f64>; 3] = Default::default();
    let mut writes = Vec::new();
    let mut bytes = (Vec::new(), Vec::new());
    for _ in 0..3 {
        for (i, mode) in [Mode::Baseline, Mode::Quiet, Mode::Fog].into_iter().enumerate() {
            let r = run(mode, frames / 3);
            all[i].extend(r.frames);
            match mode {
                Mode::Fog => {
                    writes.extend(r.writes);
                    bytes.1.extend(r.bytes);
                }
                Mode::Quiet => bytes.0.extend(r.bytes),
                Mode::Baseline => {}
            }
        }
    }
    for v in all.iter_mut().chain([&mut writes]) {
        v.sort_by(f64::total_cmp);
    }
    let base = (percentile(&all[0], 0.5), percentile(&all[0], 0.99));
    println!(
        "| frames | p50 ms | p99 ms | p50 / baseline | p99 / baseline | upload bytes a frame (mean, max) |\n|---|---|---|---|---|---|"
    );
    let names = [
        "terrain plugins, no tile state (baseline)",
        "with tile state, no change",
        "with tile state, 10,000 fog writes",
    ];
    for (i, name) in names.iter().enumerate() {
        let (p50, p99) = (percentile(&all[i], 0.5), percentile(&all[i], 0.99));
        let b = match i {
            1 => &bytes.0,
            2 => &bytes.1,
            _ => &Vec::new(),
        };
        let upload = if b.is_empty() {
            "-".to_owned()
        } else {
            format!("{:.0}, {}", b.iter().sum::<usize>() as f64 / b.len() as f64, b.iter().max().unwrap_or(&0))
        };
        println!("| {name} | {p50:.3} | {p99:.3} | {:.2} | {:.2} | {upload} |", p50 / base.0, p99 / base.1);
    }
    println!(
        "\nthe 10,000 writes alone (inside the game system): p50 {:.3} ms, p99 {:.3} ms, max {:.3} ms",
        percentile(&writes, 0.5),
        percentile(&writes, 0.99),
        percentile(&writes, 1.0)
    );
    println!(
        "fog frames over the baseline: p50 +{:.3} ms, p99 +{:.3} ms",
        percentile(&all[2], 0.5) - base.0,
        percentile(&all[2], 0.99) - base.1
    );
}
