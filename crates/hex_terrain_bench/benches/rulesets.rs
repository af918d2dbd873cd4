//! Meshing a map under its own terrain ruleset beside the same map under the default one, in
//! one run: the World map (Civ6 Standard size, climate and rivers) chunk by chunk with the
//! default ruleset, the Civilization-style one and the fantasy one; the median over the runs and
//! each one's ratio to the default. A tile's terrain and feature cost a sample of its center and
//! its neighbors: each chunk asks each of its tiles (and the ring around them) once.
//!
//! `cargo bench -p hex_terrain_bench --bench rulesets` (9 runs; `HEXTERRAIN_RUNS` for more)

use std::time::{Duration, Instant};

use hex_terrain::{MapConfig, Terrain};
use hex_terrain_bench::{median, ms};

fn main() {
    let runs: usize = std::env::var("HEXTERRAIN_RUNS").ok().and_then(|s| s.parse().ok()).unwrap_or(9);
    let maps = concat!(env!("CARGO_MANIFEST_DIR"), "/../bevy_hex_terrain/assets/maps/");
    let terrains: Vec<(&str, Terrain)> = [("default", "world"), ("civ5", "world_civ5"), ("fantasy", "world_fantasy")]
        .into_iter()
        .map(|(name, file)| {
            let config = MapConfig::load(format!("{maps}{file}.map.ron")).expect("a shipped map");
            (name, Terrain::new(config).expect("a valid map"))
        })
        .collect();
    let mut times: Vec<Vec<Duration>> = vec![Vec::new(); terrains.len()];
    // Runs in the outer loop, so every ruleset meets the machine in the same state.
    for _ in 0..runs {
        for ((_, terrain), row) in terrains.iter().zip(&mut times) {
            let start = Instant::now();
            for chunk in terrain.chunks() {
                std::hint::black_box(terrain.generate_chunk(chunk));
            }
            row.push(start.elapsed());
        }
    }
    let medians: Vec<Duration> = times.into_iter().map(median).collect();
    println!("World map meshed chunk by chunk, {runs} runs, median:");
    println!("{:<10} {:>12} {:>8}", "ruleset", "ms", "ratio");
    for ((name, _), t) in terrains.iter().zip(&medians) {
        println!("{name:<10} {:>12} {:>8.2}", ms(*t).trim(), t.as_secs_f64() / medians[0].as_secs_f64());
    }
}
