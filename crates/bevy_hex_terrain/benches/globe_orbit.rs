//! Orbit benchmark on a headless App: a `GlobeCamera` (the streaming agent) flies round the Huge
//! Continents globe (frequency 26, 6,762 tiles) over both poles at a region's altitude, 20
//! degrees a second for 60 simulated seconds at 60 frames a second (paced in real time, so the
//! chunk tasks get the time a game would give them), with props (`HexPropSettings`' defaults:
//! up to 384 a chunk, 64 spawned a frame) and fog of war drawn. Every frame the hovered tile moves
//! (a tile state write), and every half second a scout's sight under the camera is revealed (a
//! fog change over a hundred tiles, whose props are shown). Chunks far from the camera are drawn
//! coarse (`HexGlobeSettings`' default distance); the triangles drawn are counted. Prints the main thread's time in the globe's systems per frame
//! (on a core, and wall time), its split by set, the chunk latency (spawned to mesh inserted) and
//! the chunks kept, beside a control (the same fixed work every frame on the same thread and
//! clock: what the machine alone does to a frame's time).
//!
//! ```text
//! cargo bench -p bevy_hex_terrain --bench globe_orbit [-- --seconds 60] [--altitude 14]
//! ```

use std::collections::HashMap;
use std::time::{Duration, Instant};

use bevy::prelude::*;
use bevy_hex_terrain::hex_terrain::{GlobeSize, GlobeTile};
use bevy_hex_terrain::prelude::*;
use bevy_hex_terrain::{GlobeStreamer, HexGlobeProp, HexTileStateSystems, Highlight};

#[path = "support/clocks.rs"]
mod clocks;
use clocks::{Clocks, control, percentile};

/// The globe's sets in their order (`Place` runs after `Map`, here after `Insert`).
const SETS: [(&str, HexTerrainSystems); 4] = [
    ("map", HexTerrainSystems::Map),
    ("stream", HexTerrainSystems::Stream),
    ("insert", HexTerrainSystems::Insert),
    ("place", HexTerrainSystems::Place),
];

#[derive(Resource, Default)]
struct FrameTimes {
    marks: Vec<Clocks>,
    /// Wall time and time on a core of the globe's systems, ms, per frame.
    wall: Vec<f64>,
    cpu: Vec<f64>,
    /// Time on a core of each set, ms, per frame.
    sets: Vec<[f64; SETS.len()]>,
    control: Vec<f64>,
    scratch: Vec<u64>,
    /// Time on a core packing the tile states' rows for the GPU (after `Update`), ms, per frame.
    pack: Vec<f64>,
    pack_mark: Option<Clocks>,
    /// When each chunk entity was spawned, and the latencies of those meshed, ms.
    spawned: HashMap<Entity, Instant>,
    latencies: Vec<f64>,
}

fn sorted(v: &[f64]) -> Vec<f64> {
    let mut v = v.to_vec();
    v.sort_by(f64::total_cmp);
    v
}

fn spread(v: &[f64]) -> String {
    let v = sorted(v);
    format!(
        "{:.3} / {:.3} / {:.3} ms",
        percentile(&v, 0.5),
        percentile(&v, 0.99),
        v.last().copied().unwrap_or(f64::NAN)
    )
}

fn main() {
    let arg = |name: &str| std::env::args().skip_while(|a| a != name).nth(1).and_then(|s| s.parse::<f32>().ok());
    let seconds = arg("--seconds").unwrap_or(60.0) as u32;
    let altitude = arg("--altitude").unwrap_or(14.0);
    let mut config = MapConfig::from_ron(include_str!("../assets/maps/globe/continents.map.ron")).expect("the preset");
    config.size = MapSize::Globe { frequency: GlobeSize::Huge.frequency() };
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, AssetPlugin::default(), TransformPlugin, HexGlobePlugin::from_config(config)))
        .insert_resource(HexTileStateStyle { fog_of_war: true, ..default() })
        .init_resource::<FrameTimes>()
        .add_systems(Update, (|mut t: ResMut<FrameTimes>| t.marks = vec![Clocks::now()]).before(HexTerrainSystems::Map))
        .add_systems(
            Update,
            (|mut t: ResMut<FrameTimes>| {
                t.marks.push(Clocks::now());
                if t.marks.len() != SETS.len() + 1 {
                    return;
                }
                let split = std::array::from_fn(|k| t.marks[k + 1].since(t.marks[k])[1]);
                t.sets.push(split);
                let [wall, cpu, ..] = t.marks[SETS.len()].since(t.marks[0]);
                t.wall.push(wall);
                t.cpu.push(cpu);
                let before = Clocks::now();
                std::hint::black_box(control(&mut t.scratch));
                let cpu = Clocks::now().since(before)[1];
                t.control.push(cpu);
            })
            .after(HexTerrainSystems::Place),
        )
        .add_systems(
            Last,
            |mut t: ResMut<FrameTimes>,
             added: Query<Entity, Added<HexGlobeChunk>>,
             meshed: Query<Entity, (With<HexGlobeChunk>, Added<Mesh3d>)>| {
                let now = Instant::now();
                for e in &added {
                    t.spawned.insert(e, now);
                }
                for e in &meshed {
                    if let Some(at) = t.spawned.remove(&e) {
                        t.latencies.push((now - at).as_secs_f64() * 1e3);
                    }
                }
            },
        );
    app.add_systems(
        PostUpdate,
        (|mut t: ResMut<FrameTimes>| t.pack_mark = Some(Clocks::now())).before(HexTileStateSystems::Pack),
    )
    .add_systems(
        PostUpdate,
        (|mut t: ResMut<FrameTimes>| {
            if let Some(mark) = t.pack_mark.take() {
                let cpu = Clocks::now().since(mark)[1];
                t.pack.push(cpu);
            }
        })
        .after(HexTileStateSystems::Pack),
    );
    for k in 0..SETS.len() - 1 {
        app.add_systems(
            Update,
            (|mut t: ResMut<FrameTimes>| t.marks.push(Clocks::now())).after(SETS[k].1).before(SETS[k + 1].1),
        );
    }
    app.configure_sets(Update, HexTerrainSystems::Place.after(HexTerrainSystems::Insert));
    app.edit_schedule(Update, |s| {
        s.set_executor(bevy::ecs::schedule::SingleThreadedExecutor::new());
    });
    let start = GlobeCamera { altitude, ..GlobeCamera::above(0.3, 0.2) };
    let camera = app.world_mut().spawn((start, HexTerrainAgent::default())).id();
    // The first globe in, its chunks meshed, before the clock starts.
    while !app.world().resource::<GlobeStreamer>().is_settled() {
        app.update();
    }
    *app.world_mut().resource_mut::<FrameTimes>() = FrameTimes::default();
    let frame = Duration::from_secs_f64(1.0 / 60.0);
    // Round an axis through the equator: over both poles.
    let axis = Vec3::new(0.3, 0.0, 1.0).normalize();
    let (mut kept, mut props, mut triangles) = (Vec::new(), Vec::new(), Vec::new());
    for f in 0..seconds * 60 {
        let begun = Instant::now();
        let turn = Quat::from_axis_angle(axis, (20.0 * f as f32 / 60.0).to_radians());
        app.world_mut().get_mut::<GlobeCamera>(camera).unwrap().orientation = turn * start.orientation;
        let globe = app.world().resource::<HexGlobe>().globe().unwrap().clone();
        let under = (turn * start.orientation * Vec3::Z).as_dvec3().to_array();
        let mut states = app.world_mut().resource_mut::<GlobeTileStates>();
        if let Some(tile) = globe.tile_at(under) {
            states.replace_highlight(Highlight::Hovered, [GlobeTile((tile.0 + f % 9) % globe.grid().tile_count())]);
            if f % 30 == 0 {
                for (t, _) in globe.grid().within(tile, 6) {
                    states.set_visibility(t, FogState::Visible).unwrap();
                }
            }
        }
        app.update();
        kept.push(app.world().resource::<GlobeStreamer>().chunks().count() as f64);
        props.push(app.world_mut().query::<&HexGlobeProp>().iter(app.world()).count() as f64);
        let mut chunks = app.world_mut().query::<(&HexGlobeChunk, &Mesh3d)>();
        let meshes = app.world().resource::<Assets<Mesh>>();
        let (drawn, coarse): (usize, usize) = chunks.iter(app.world()).fold((0, 0), |(n, c), (chunk, mesh)| {
            let count = meshes.get(&mesh.0).and_then(Mesh::indices).map_or(0, |i| i.len() / 3);
            (n + count, c + usize::from(chunk.detail == Detail::Coarse))
        });
        // The same chunks' triangles at full detail: 6 n^2 a hexagon, 5 n^2 a pentagon.
        let n = globe.config().subdivisions() as usize;
        let full: usize = app
            .world()
            .resource::<GlobeStreamer>()
            .chunks()
            .flat_map(|c| globe.chunk_tiles(c))
            .map(|t| if globe.grid().is_pentagon(t) { 5 * n * n } else { 6 * n * n })
            .sum();
        triangles.push((drawn as f64, coarse as f64, full as f64));
        if let Some(rest) = frame.checked_sub(begun.elapsed()) {
            std::thread::sleep(rest);
        }
    }
    let t = app.world().resource::<FrameTimes>();
    println!(
        "globe orbit: the Huge Continents globe (f = 26), {seconds} s at 60 fps, altitude {altitude}, 20 degrees a second over both poles"
    );
    println!("| figure | p50 / p99 / max |\n|---|---|");
    let total: Vec<f64> = t.cpu.iter().zip(&t.pack).map(|(a, b)| a + b).collect();
    println!("| globe systems and the tile states' packing per frame on a core | {} |", spread(&total));
    println!("| globe systems per frame on a core | {} |", spread(&t.cpu));
    println!("| globe systems per frame, wall time | {} |", spread(&t.wall));
    for (k, (name, _)) in SETS.iter().enumerate() {
        let v: Vec<f64> = t.sets.iter().map(|s| s[k]).collect();
        println!("| set {name} on a core | {} |", spread(&v));
    }
    println!("| packing the tile states for the GPU (and the props' fog) on a core | {} |", spread(&t.pack));
    println!("| the control (the same work each frame) on a core | {} |", spread(&t.control));
    println!("| chunk latency (spawned to mesh inserted) | {} |", spread(&t.latencies));
    let counts = |v: &[f64]| {
        let v = sorted(v);
        format!("{:.0} / {:.0} / {:.0}", percentile(&v, 0.5), percentile(&v, 0.99), v.last().copied().unwrap_or(0.0))
    };
    println!("| chunks kept | {} |", counts(&kept));
    println!("| props standing | {} |", counts(&props));
    println!("| chunks drawn coarse | {} |", counts(&triangles.iter().map(|t| t.1).collect::<Vec<_>>()));
    println!("| triangles drawn | {} |", counts(&triangles.iter().map(|t| t.0).collect::<Vec<_>>()));
    println!(
        "| the same chunks' triangles at full detail | {} |",
        counts(&triangles.iter().map(|t| t.2).collect::<Vec<_>>())
    );
    println!("chunks meshed: {}", t.latencies.len());
}
