//! The whole game setup (starts, normalisation, resources, wonders, report) on Civ6 Huge
//! (106x66, climate and rivers) with 12 players, each part's median over 21 runs, then the same
//! setup on the Huge Continents globe (frequency 26, 6,762 tiles) in the same process, and the
//! ratio; beside the figures Unciv published for its huge maps (it runs on the JVM: they cannot
//! run in this process, so they are printed as published, with where they come from).
//!
//! `cargo bench -p hex_terrain_bench --bench setup`

use std::time::Duration;

use hex_terrain::{GlobeTerrain, MapConfig, MapSize, Setup, SetupConfig, SetupTimings, Terrain};
use hex_terrain_bench::{median, ms};

const RUNS: usize = 21;

fn main() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/maps/civ6/huge.map.ron");
    let config = MapConfig::load(path).expect("the Huge preset");
    let terrain = Terrain::new(config.clone()).expect("a valid config");
    let setup = SetupConfig { players: 12, ..SetupConfig::default() };
    let mut runs: Vec<SetupTimings> = Vec::with_capacity(RUNS);
    let mut last = None;
    for _ in 0..RUNS {
        let (placed, timings) =
            Setup::build_timed(terrain.pipeline().stages(), &setup, config.seed).expect("12 starts fit on Huge");
        runs.push(timings);
        last = Some(placed);
    }
    let part = |f: fn(&SetupTimings) -> Duration| median(runs.iter().map(f).collect());
    println!("game setup, {} ({} tiles), 12 players: median of {RUNS} runs", config.name, 106 * 66);
    println!("  survey (every tile's type, biome, yields)  {}", ms(part(|t| t.survey)));
    println!("  ring values and regions                   {}", ms(part(|t| t.regions)));
    println!("  starts (placement and refinement)         {}", ms(part(|t| t.starts)));
    println!("  wonders and resources                     {}", ms(part(|t| t.placement)));
    println!("  normalisation                             {}", ms(part(|t| t.normalize)));
    println!("  report (path costs, land masses)          {}", ms(part(|t| t.report)));
    println!("  whole setup                               {}", ms(part(SetupTimings::total)));
    if let Some(placed) = last {
        let r = placed.report();
        println!(
            "  spread {:.1} % (bound {:.0} %), {} resources, {} wonders, {} shortfalls",
            r.spread * 100.0,
            r.bound * 100.0,
            r.resources,
            r.wonders,
            r.shortfalls.len()
        );
    }
    // The Huge Continents globe, placed again on its compiled tiles each run.
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/maps/globe/continents.map.ron");
    let mut globe_config = MapConfig::load(path).expect("the Continents globe");
    globe_config.size = MapSize::Globe { frequency: 26 };
    globe_config.setup = None;
    let globe = GlobeTerrain::new(globe_config).expect("a valid globe");
    let globe_runs: Vec<Duration> = (0..RUNS)
        .map(|_| {
            let start = std::time::Instant::now();
            let placed = globe.with_setup(Some(setup.clone())).expect("12 starts fit on the Huge globe");
            let took = start.elapsed();
            std::hint::black_box(placed.setup().map(|s| s.starts().len()));
            took
        })
        .collect();
    let (flat, round) = (part(SetupTimings::total), median(globe_runs));
    println!(
        "game setup, Huge Continents globe ({} tiles), 12 players: {} ({:.2}x the flat map's)",
        globe.grid().tile_count(),
        ms(round),
        round.as_secs_f64() / flat.as_secs_f64()
    );
    println!("Unciv, as published (huge maps, its own machines):");
    println!("  start placement, Huge, 9 civs + 18 city-states: 1055 ms (3314 ms before)   yairm210/Unciv#4620");
    println!("  regions, Huge, 10 civs: 69.5 ms + 28.1 ms to assign them               yairm210/Unciv#5556");
    println!("  spreadResources, Huge hexagonal Pangaea: 516 ms                        yairm210/Unciv#4805");
}
