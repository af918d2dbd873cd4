//! Streaming benchmark on a headless App: an agent crossing one chunk per second for 60
//! simulated seconds at 60 frames a second (paced in real time, so chunk tasks get the time a
//! game would give them). Prints chunk latency (request to mesh inserted), main-thread time in
//! the terrain systems per frame, live chunks and memory per chunk.
//!
//! ```text
//! cargo bench -p bevy_hex_terrain --bench streaming [-- --seconds 60]
//! ```

use std::time::{Duration, Instant};

use bevy::prelude::*;
use bevy_hex_terrain::ChunkStreamer;
use bevy_hex_terrain::hex_terrain::MapSize;
use bevy_hex_terrain::prelude::*;

#[derive(Resource, Default)]
struct FrameTimes {
    start: Option<Instant>,
    samples: Vec<f64>,
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

fn main() {
    let seconds: u32 =
        std::env::args().skip_while(|a| a != "--seconds").nth(1).and_then(|s| s.parse().ok()).unwrap_or(60);
    let config = MapConfig { size: MapSize::Unbounded, chunk_size: (16, 16), ..MapConfig::default() };
    let chunk_width = 16.0 * 1.5 * config.layout.hex_size;
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins,
        AssetPlugin::default(),
        TransformPlugin,
        HexTerrainPlugin { map: config.into(), settings: HexTerrainSettings::default() },
    ))
    .init_resource::<FrameTimes>()
    // Brackets around the terrain sets: the time between them is the terrain systems' share
    // of the frame.
    .add_systems(Update, (|mut t: ResMut<FrameTimes>| t.start = Some(Instant::now())).before(HexTerrainSystems::Map))
    .add_systems(
        Update,
        (|mut t: ResMut<FrameTimes>| {
            if let Some(s) = t.start.take() {
                t.samples.push(s.elapsed().as_secs_f64() * 1e3);
            }
        })
        .after(HexTerrainSystems::Render),
    );
    let agent = app.world_mut().spawn((HexTerrainAgent::default(), Transform::default())).id();
    let frames = seconds * 60;
    let frame = Duration::from_secs_f64(1.0 / 60.0);
    let mut live_max = 0;
    for f in 0..frames {
        let start = Instant::now();
        let x = f as f32 / 60.0 * chunk_width;
        app.world_mut().entity_mut(agent).insert(Transform::from_xyz(x, 0.0, 0.0));
        app.update();
        live_max = live_max.max(app.world().resource::<ChunkStreamer>().live_chunks());
        if let Some(rest) = frame.checked_sub(start.elapsed()) {
            std::thread::sleep(rest);
        }
    }
    let mut times = app.world().resource::<FrameTimes>().samples.clone();
    times.sort_by(f64::total_cmp);
    let streamer = app.world().resource::<ChunkStreamer>();
    let mut latencies: Vec<f64> = streamer.latencies.iter().map(|&s| f64::from(s) * 1e3).collect();
    latencies.sort_by(f64::total_cmp);
    let live = streamer.live_chunks();
    let started = streamer.tasks_started;
    let bytes: Vec<usize> = app.world_mut().query::<&HexChunk>().iter(app.world()).map(|c| c.mesh_bytes).collect();
    let per_chunk = bytes.iter().sum::<usize>() as f64 / bytes.len().max(1) as f64;
    println!("streaming: {seconds} s at 60 fps, agent crossing one 16x16-tile chunk per second, default settings");
    println!("| figure | value |\n|---|---|");
    println!("| chunks generated | {started} |");
    println!(
        "| chunk latency p50 / p99 (request to mesh inserted) | {:.1} ms / {:.1} ms |",
        percentile(&latencies, 0.5),
        percentile(&latencies, 0.99)
    );
    println!(
        "| terrain systems per frame p50 / p99 / max | {:.3} ms / {:.3} ms / {:.3} ms |",
        percentile(&times, 0.5),
        percentile(&times, 0.99),
        times.last().copied().unwrap_or(f64::NAN)
    );
    println!("| live chunks at the end / at most | {live} / {live_max} |");
    println!("| mesh memory per chunk | {:.0} KiB |", per_chunk / 1024.0);
}
