//! The world builder in a headless App on Civ6 Huge (106x66, climate and rivers), every chunk
//! loaded, paced at 60 frames a second: a radius-3 stroke every half second on land all over the
//! map, alternately raising and lowering. Prints, for each stroke, the frames from sending
//! `HexMapEdit` to every chunk of its change showing its new mesh, and the terrain systems'
//! main-thread time per frame (wall time less the time waiting for a core, from the thread's
//! schedstat) while editing.
//!
//! ```text
//! cargo bench -p bevy_hex_terrain --profile dev --bench editor
//! ```

use std::time::{Duration, Instant};

use bevy::prelude::*;
use bevy_hex_terrain::hex_terrain::{Brush, Stroke, Tool};
use bevy_hex_terrain::prelude::*;

/// The calling thread's total time waiting for a core, in ns (see the streaming benchmark).
fn waiting_ns() -> u64 {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").unwrap_or_default();
    text.split_whitespace().nth(1).and_then(|f| f.parse().ok()).unwrap_or(0)
}

#[derive(Resource, Default)]
struct FrameTimes {
    start: Option<(Instant, u64)>,
    /// Main thread on a core in the terrain systems, ms, per frame.
    cpu: Vec<f64>,
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    sorted.get(((sorted.len().max(1) - 1) as f64 * p).round() as usize).copied().unwrap_or(f64::NAN)
}

fn main() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/maps/civ6/huge.map.ron");
    let config = MapConfig::load(path).expect("the Huge preset");
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, AssetPlugin::default(), TransformPlugin))
        .add_plugins(HexTerrainPlugins::from_config(config).build().disable::<HexTerrainMaterialPlugin>())
        .init_resource::<FrameTimes>()
        .add_systems(
            Update,
            (|mut t: ResMut<FrameTimes>| t.start = Some((Instant::now(), waiting_ns()))).before(HexTerrainSystems::Map),
        )
        .add_systems(
            Update,
            (|mut t: ResMut<FrameTimes>| {
                if let Some((wall, waited)) = t.start.take() {
                    let waiting = waiting_ns().saturating_sub(waited) as f64 * 1e-6;
                    let cpu = (wall.elapsed().as_secs_f64() * 1e3 - waiting).max(0.0);
                    t.cpu.push(cpu);
                }
            })
            .after(HexTerrainSystems::Render),
        );
    app.edit_schedule(Update, |s| {
        s.set_executor(bevy::ecs::schedule::SingleThreadedExecutor::new());
    });
    let frame = Duration::from_secs_f64(1.0 / 60.0);
    let step = |app: &mut App| {
        let start = Instant::now();
        app.update();
        if let Some(rest) = frame.checked_sub(start.elapsed()) {
            std::thread::sleep(rest);
        }
    };
    // No agent: the bounded map is loaded whole.
    let all_current = |app: &mut App| {
        let map = app.world().resource::<HexMap>().clone();
        let mut chunks = app.world_mut().query::<&HexChunk>();
        let n = chunks.iter(app.world()).count();
        n > 0 && chunks.iter(app.world()).all(|c| map.is_current(c.coord, c.generation))
    };
    while !all_current(&mut app) {
        step(&mut app);
    }
    let terrain = app.world().resource::<HexMap>().terrain().clone();
    let land: Vec<Hex> = terrain
        .tiles()
        .filter(|&t| {
            let [c, r] = terrain.offset_of(t);
            c % 7 == 3 && r % 5 == 2 && terrain.tile_kind(t) == Some(TileKind::Land)
        })
        .take(20)
        .collect();
    app.world_mut().resource_mut::<FrameTimes>().cpu.clear();
    let mut frames = Vec::new();
    let mut chunks = Vec::new();
    let mut seen = app.world().resource::<Messages<HexMapEdited>>().get_cursor();
    for (i, &tile) in land.iter().enumerate() {
        let tool = if i % 2 == 0 { Tool::Raise(0.08) } else { Tool::Lower(0.08) };
        app.world_mut().write_message(HexMapEdit::Stroke(Stroke { tool, brush: Brush::Range(3), tile }));
        let mut n = 0;
        let mut edited = None;
        loop {
            step(&mut app);
            n += 1;
            let messages = app.world().resource::<Messages<HexMapEdited>>();
            if let Some(e) = seen.read(messages).last() {
                edited = Some(e.change.chunks.len());
            }
            if edited.is_some() && all_current(&mut app) {
                break;
            }
            assert!(n < 600, "stroke {i} not shown after 10 s");
        }
        frames.push(n);
        chunks.push(edited.unwrap_or(0));
        // The rest of the half second.
        for _ in n..30 {
            step(&mut app);
        }
    }
    let mut cpu = app.world().resource::<FrameTimes>().cpu.clone();
    cpu.sort_by(f64::total_cmp);
    frames.sort_unstable();
    chunks.sort_unstable();
    println!("world builder on Civ6 Huge, every chunk loaded, 60 fps: {} radius-3 strokes", land.len());
    println!(
        "  frames from the message to every changed chunk showing its new mesh: median {}, max {}",
        frames[frames.len() / 2],
        frames[frames.len() - 1]
    );
    println!("  chunks rebuilt per stroke: median {}, max {}", chunks[chunks.len() / 2], chunks[chunks.len() - 1]);
    println!(
        "  terrain systems, main thread on a core, per frame: p50 {:.3} ms, p99 {:.3} ms, max {:.3} ms ({} frames)",
        percentile(&cpu, 0.5),
        percentile(&cpu, 0.99),
        cpu.last().copied().unwrap_or(f64::NAN),
        cpu.len()
    );
}
