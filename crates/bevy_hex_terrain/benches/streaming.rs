//! Streaming benchmark on a headless App: an agent crossing one chunk per second for 60
//! simulated seconds at 60 frames a second (paced in real time, so chunk tasks get the time a
//! game would give them). Prints chunk latency (request to mesh inserted), main-thread time in
//! the terrain systems per frame (wall time, split by the thread's clocks into time on a core,
//! time waiting for one and time asleep in the kernel, and the time on a core of each set), live chunks and memory per chunk; with chunk generation on
//! Bevy's async compute pool alone (the default) and, in the same process, with each chunk task
//! also spreading over rayon's pool. Fog of war is drawn; every frame the hovered tile moves, and
//! every half second the tiles around the agent are revealed, as a player's cursor and scouts
//! would. A control (the same fixed work every frame, on the same thread right after the
//! terrain systems, on the same clock) shows what the machine alone does to a frame's time.
//!
//! ```text
//! cargo bench -p bevy_hex_terrain --bench streaming [-- --seconds 60] [--no-props]
//! ```

use std::time::{Duration, Instant};

use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;
use bevy_hex_terrain::{ChunkThreads, HexPropStats};

#[path = "support/clocks.rs"]
mod clocks;
use clocks::{Clocks, control, percentile};

#[derive(Resource, Default)]
struct FrameTimes {
    /// Wall time of the terrain systems, ms.
    samples: Vec<f64>,
    /// Of which the main thread ran on a core, ms.
    cpu: Vec<f64>,
    /// Of which the main thread waited for a core (runnable, not running), ms.
    waiting: Vec<f64>,
    /// Of which the main thread slept in the kernel (neither running nor runnable: a page fault
    /// waiting for a lock, a blocking call), ms.
    blocked: Vec<f64>,
    /// This frame's clocks before the first set, between each two and after the last
    /// (`SETS.len() + 1` of them once the frame is done).
    marks: Vec<Clocks>,
    /// Time on a core of each set, ms, per frame.
    sets: Vec<[f64; SETS.len()]>,
    /// Time on a core of the control (a fixed workload run after the terrain systems each
    /// frame, see [`control`]), ms, per frame.
    control: Vec<f64>,
    /// The control's memory.
    scratch: Vec<u64>,
}

/// The terrain sets in their order, for the split of a frame.
const SETS: [(&str, HexTerrainSystems); 6] = [
    ("map", HexTerrainSystems::Map),
    ("stream", HexTerrainSystems::Stream),
    ("insert", HexTerrainSystems::Insert),
    ("children", HexTerrainSystems::Children),
    ("tiles", HexTerrainSystems::Tiles),
    ("render", HexTerrainSystems::Render),
];

/// Figures of one walk.
struct Walk {
    started: u64,
    latencies: Vec<f64>,
    times: Vec<f64>,
    cpu: Vec<f64>,
    waiting: Vec<f64>,
    blocked: Vec<f64>,
    live: usize,
    live_max: usize,
    per_chunk: f64,
    /// Meshes inserted, tasks started and tasks cancelled in the frame whose terrain systems
    /// took longest on a core, and its prop entities and entities before and after it.
    worst: (u64, u64, u64, [usize; 2], [u32; 2]),
    /// Time on a core of each set per frame, ms.
    sets: Vec<[f64; SETS.len()]>,
    /// The index of the frame whose terrain systems took longest on a core.
    worst_frame: usize,
    /// Props whose fog was looked at, per frame.
    fog_checks: Vec<f64>,
    /// Prop entities at the end, and props waiting to be spawned at most.
    props_live: usize,
    pending_max: usize,
    /// The first frame with [`FULL_WORLD`] props live (`None` if never).
    full_from: Option<usize>,
    /// Time on a core of the frames from it on, ms, sorted.
    cpu_full: Vec<f64>,
    /// Time on a core of the control, ms, sorted.
    control: Vec<f64>,
}

/// Props live from which the world counts as full: the issue's "a frame that moves a hover with
/// 20,000 props live". Before it, the world fills: Bevy's table of prop entities doubles (at
/// 8,192 and 16,384 props), each time copying every prop in one frame.
const FULL_WORLD: usize = 20_000;

/// Walks an agent east for `seconds` with chunk generation running on `threads`.
fn walk(seconds: u32, threads: ChunkThreads, props: bool) -> Walk {
    let config = MapConfig { size: MapSize::Unbounded, chunk_size: (16, 16), ..MapConfig::default() };
    let chunk_width = 16.0 * 1.5 * config.layout.hex_size;
    let mut app = App::new();
    let settings = HexStreamingSettings { chunk_threads: threads, ..HexStreamingSettings::default() };
    app.add_plugins((MinimalPlugins, AssetPlugin::default(), TransformPlugin))
        .insert_resource(settings)
        .add_plugins(HexTerrainPlugins::new(config).build().disable::<HexTerrainMaterialPlugin>())
        .init_resource::<FrameTimes>()
        .insert_resource(HexPropSettings { enabled: props, ..HexPropSettings::default() })
        // Fog of war drawn, so props on unexplored tiles are hidden and fog writes are checked.
        .insert_resource(HexTileStateStyle { fog_of_war: true, ..HexTileStateStyle::default() })
        // Clocks before the first set, between each two and after the last: the time between
        // the first and the last is the terrain systems' share of the frame, and each interval
        // a set's.
        .add_systems(Update, (|mut t: ResMut<FrameTimes>| t.marks = vec![Clocks::now()]).before(HexTerrainSystems::Map))
        .add_systems(
            Update,
            (|mut t: ResMut<FrameTimes>| {
                t.marks.push(Clocks::now());
                if t.marks.len() != SETS.len() + 1 {
                    return;
                }
                let mut split = [0.0; SETS.len()];
                for (k, d) in split.iter_mut().enumerate() {
                    *d = t.marks[k + 1].since(t.marks[k])[1];
                }
                t.sets.push(split);
                let [wall, cpu, waiting, blocked] = t.marks[SETS.len()].since(t.marks[0]);
                t.samples.push(wall);
                t.cpu.push(cpu);
                t.waiting.push(waiting);
                t.blocked.push(blocked);
                // The control, on the same thread in the same frame, timed with the same clock.
                let before = Clocks::now();
                std::hint::black_box(control(&mut t.scratch));
                let cpu = Clocks::now().since(before)[1];
                t.control.push(cpu);
            })
            .after(HexTerrainSystems::Render),
        );
    // The terrain systems are one chain: run the frame on the main thread, so the clocks of the
    // main thread tell its work from waiting. A mark between each two sets: the split of the
    // frame.
    for k in 0..SETS.len() - 1 {
        app.add_systems(
            Update,
            (|mut t: ResMut<FrameTimes>| t.marks.push(Clocks::now())).after(SETS[k].1).before(SETS[k + 1].1),
        );
    }
    app.edit_schedule(Update, |s| {
        s.set_executor(bevy::ecs::schedule::SingleThreadedExecutor::new());
    });
    let agent = app.world_mut().spawn((HexTerrainAgent::default(), Transform::default())).id();
    let frames = seconds * 60;
    let frame = Duration::from_secs_f64(1.0 / 60.0);
    let mut live_max = 0;
    let counts = |app: &App| {
        let s = app.world().resource::<HexStreamingStats>();
        (s.meshes_inserted(), s.tasks_started(), s.tasks_cancelled())
    };
    let (mut worst, mut worst_time, mut worst_frame) = ((0, 0, 0, [0; 2], [0; 2]), 0.0, 0);
    let (mut fog_checks, mut pending_max, mut full_from) = (Vec::new(), 0, None);
    // Prop entities live, counted once a frame after it (nothing spawns props between frames).
    let mut prop_query = app.world_mut().query::<&HexProp>();
    let mut props_live = prop_query.iter(app.world()).count();
    for f in 0..frames {
        let start = Instant::now();
        let x = f as f32 / 60.0 * chunk_width;
        app.world_mut().entity_mut(agent).insert(Transform::from_xyz(x, 0.0, 0.0));
        cursor_and_scouts(app.world_mut(), x, f);
        let before = counts(&app);
        let (props_before, entities_before) = (props_live, app.world().entities().count_spawned());
        let checks = app.world().resource::<HexPropStats>().fog_checks;
        app.update();
        let after = counts(&app);
        fog_checks.push((app.world().resource::<HexPropStats>().fog_checks - checks) as f64);
        pending_max = pending_max.max(app.world().resource::<HexPropStats>().pending);
        props_live = prop_query.iter(app.world()).count();
        let entities_after = app.world().entities().count_spawned();
        if full_from.is_none() && props_live >= FULL_WORLD {
            full_from = Some(app.world().resource::<FrameTimes>().cpu.len().saturating_sub(1));
        }
        if let Some(&t) = app.world().resource::<FrameTimes>().cpu.last()
            && t > worst_time
        {
            worst_time = t;
            worst = (
                after.0 - before.0,
                after.1 - before.1,
                after.2 - before.2,
                [props_before, props_live],
                [entities_before, entities_after],
            );
            worst_frame = app.world().resource::<FrameTimes>().sets.len().saturating_sub(1);
        }
        live_max = live_max.max(app.world().resource::<ChunkStreamer>().live_chunks());
        if let Some(rest) = frame.checked_sub(start.elapsed()) {
            std::thread::sleep(rest);
        }
    }
    let sorted = |v: &Vec<f64>| {
        let mut v = v.clone();
        v.sort_by(f64::total_cmp);
        v
    };
    let recorded = app.world().resource::<FrameTimes>();
    let (times, cpu) = (sorted(&recorded.samples), sorted(&recorded.cpu));
    let cpu_full = sorted(&recorded.cpu[full_from.unwrap_or(recorded.cpu.len()).min(recorded.cpu.len())..].to_vec());
    let (waiting, blocked) = (sorted(&recorded.waiting), sorted(&recorded.blocked));
    let sets = recorded.sets.clone();
    let control = sorted(&recorded.control);
    let stats = app.world().resource::<HexStreamingStats>();
    let mut latencies: Vec<f64> = stats.latencies().map(|s| f64::from(s) * 1e3).collect();
    latencies.sort_by(f64::total_cmp);
    let started = stats.tasks_started();
    let live = app.world().resource::<ChunkStreamer>().live_chunks();
    let bytes: Vec<usize> = app.world_mut().query::<&HexChunk>().iter(app.world()).map(|c| c.mesh_bytes).collect();
    let per_chunk = bytes.iter().sum::<usize>() as f64 / bytes.len().max(1) as f64;
    fog_checks.sort_by(f64::total_cmp);
    Walk {
        started,
        latencies,
        times,
        cpu,
        waiting,
        blocked,
        live,
        live_max,
        per_chunk,
        worst,
        sets,
        worst_frame,
        fog_checks,
        full_from,
        cpu_full,
        control,
        props_live,
        pending_max,
    }
}

/// What a player does every frame: the cursor moves the hovered tile (a tile-state write each
/// frame), and every half second the scouts around the agent reveal the tiles within 10 of it
/// (a fog change).
fn cursor_and_scouts(world: &mut World, x: f32, frame: u32) {
    let terrain = world.resource::<HexMap>().terrain().clone();
    let mut states = world.resource_mut::<TileStates>();
    if let Some(tile) = terrain.tile_at(f64::from(x) + f64::from(frame % 9), 3.0) {
        states.replace_highlight(Highlight::Hovered, [tile]);
    }
    if frame.is_multiple_of(30)
        && let Some(center) = terrain.tile_at(f64::from(x), 0.0)
    {
        for tile in center.range(10) {
            // Tiles outside the state's window are refused; the scouts reveal what it holds.
            let _ = states.set_visibility(tile, FogState::Visible);
        }
    }
}

fn main() {
    let seconds: u32 =
        std::env::args().skip_while(|a| a != "--seconds").nth(1).and_then(|s| s.parse().ok()).unwrap_or(60);
    // The default (one pool: each chunk on one thread of the async compute pool) beside the
    // old way (each chunk task also fanning out over rayon's pool), in one process, after a
    // short walk that warms up the process (pools, allocator, first page faults).
    // `--no-props` walks without props (what they cost the main thread).
    let props = !std::env::args().any(|a| a == "--no-props");
    drop(walk(5, ChunkThreads::AsyncCompute, props));
    let rayon = walk(seconds, ChunkThreads::Rayon, props);
    let ours = walk(seconds, ChunkThreads::AsyncCompute, props);
    println!("streaming: {seconds} s at 60 fps, agent crossing one 16x16-tile chunk per second, default settings");
    println!("| figure | async compute pool only (default) | chunk tasks also on rayon |\n|---|---|---|");
    let row = |name: &str, f: &dyn Fn(&Walk) -> String| println!("| {name} | {} | {} |", f(&ours), f(&rayon));
    row("chunks generated", &|w| w.started.to_string());
    row("chunk latency p50 / p99 (request to mesh inserted)", &|w| {
        format!("{:.1} ms / {:.1} ms", percentile(&w.latencies, 0.5), percentile(&w.latencies, 0.99))
    });
    let spread = |v: &[f64]| {
        format!(
            "{:.3} ms / {:.3} ms / {:.3} ms",
            percentile(v, 0.5),
            percentile(v, 0.99),
            v.last().copied().unwrap_or(f64::NAN)
        )
    };
    row("terrain systems per frame, wall time, p50 / p99 / max", &|w| spread(&w.times));
    row("of which the main thread on a core, p50 / p99 / max", &|w| spread(&w.cpu));
    row(&format!("the same from the first frame with {FULL_WORLD} props live on"), &|w| {
        format!("{} (from frame {})", spread(&w.cpu_full), w.full_from.map_or("-".into(), |f| f.to_string()))
    });
    row("frames over 2 ms on a core, of all and from the world full", &|w| {
        let over = |v: &[f64]| v.iter().filter(|&&t| t > 2.0).count();
        format!("{} of {}; {} of {}", over(&w.cpu), w.cpu.len(), over(&w.cpu_full), w.cpu_full.len())
    });
    row("the control (the same work each frame, after the terrain systems) on a core, p50 / p99 / max", &|w| {
        spread(&w.control)
    });
    row("the control's frames over 2 ms on a core", &|w| {
        format!("{} of {}", w.control.iter().filter(|&&t| t > 2.0).count(), w.control.len())
    });
    row("of which waiting for a core, p50 / p99 / max", &|w| spread(&w.waiting));
    row("of which asleep in the kernel, p50 / p99 / max", &|w| spread(&w.blocked));
    row("the slowest frame on a core: its index; meshes inserted / tasks started / cancelled", &|w| {
        format!("frame {}; {} / {} / {}", w.worst_frame, w.worst.0, w.worst.1, w.worst.2)
    });
    row("in it, prop entities and entities before -> after", &|w| {
        format!("{} -> {}, {} -> {}", w.worst.3[0], w.worst.3[1], w.worst.4[0], w.worst.4[1])
    });
    for (k, (name, _)) in SETS.iter().enumerate() {
        row(&format!("set {name} on a core: p50 / p99 / max, and in the slowest frame"), &|w| {
            let mut v: Vec<f64> = w.sets.iter().map(|s| s[k]).collect();
            let slowest = v.get(w.worst_frame).copied().unwrap_or(f64::NAN);
            v.sort_by(f64::total_cmp);
            format!(
                "{:.3} ms / {:.3} ms / {:.3} ms; {:.3} ms",
                percentile(&v, 0.5),
                percentile(&v, 0.99),
                v.last().copied().unwrap_or(f64::NAN),
                slowest
            )
        });
    }
    row("live chunks at the end / at most", &|w| format!("{} / {}", w.live, w.live_max));
    row("mesh memory per chunk", &|w| format!("{:.0} KiB", w.per_chunk / 1024.0));
    row("props live at the end / waiting to spawn at most", &|w| format!("{} / {}", w.props_live, w.pending_max));
    row("props whose fog was checked per frame, p50 / p99 / max (a hover every frame)", &|w| {
        format!(
            "{:.0} / {:.0} / {:.0}",
            percentile(&w.fog_checks, 0.5),
            percentile(&w.fog_checks, 0.99),
            w.fog_checks.last().copied().unwrap_or(f64::NAN)
        )
    });
    println!(
        "p99 latency ratio (async compute only / with rayon): {:.2}",
        percentile(&ours.latencies, 0.99) / percentile(&rayon.latencies, 0.99)
    );
}
