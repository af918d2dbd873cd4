//! The climate's winds and rivers on tile edges on Civ6 Huge (106x66, wrapping, climate, rivers
//! and relief: the Huge preset), beside the same preset with the moisture fBm's climate and
//! rivers through tile centers, in one run: per seed,
//! compiling the map (where the climate, the rain and the rivers are computed), then the median
//! over the seeds and the ratio.
//!
//! `cargo bench -p hex_terrain_bench --bench climate` (40 seeds; `HEXTERRAIN_SEEDS=200` for
//! more)

use std::time::{Duration, Instant};

use hex_terrain::{MapConfig, RiverModel, Terrain, WindConfig, WindPattern};
use hex_terrain_bench::{median, ms};

fn main() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/maps/civ6/huge.map.ron");
    let preset = MapConfig::load(path).expect("the Huge preset");
    let seeds: u32 = std::env::var("HEXTERRAIN_SEEDS").ok().and_then(|s| s.parse().ok()).unwrap_or(40);
    let with_winds = |pattern: WindPattern| {
        let mut config = preset.clone();
        config.climate.winds = Some(WindConfig { pattern, ..WindConfig::default() });
        config
    };
    let mut on_edges = with_winds(WindPattern::default());
    on_edges.rivers.model = RiverModel::Edges;
    let configs = [
        ("moisture fBm (before)", preset.clone()),
        ("winds, Earth's bands", with_winds(WindPattern::default())),
        ("winds, one bearing", with_winds(WindPattern::One(270.0))),
        ("winds, rivers on edges", on_edges),
    ];
    let mut times: Vec<Vec<Duration>> = vec![Vec::new(); configs.len()];
    std::hint::black_box(Terrain::new(preset.clone()).expect("a valid config"));
    // Seeds in the outer loop, so every config meets the machine in the same state.
    for i in 0..seeds {
        for ((_, config), row) in configs.iter().zip(&mut times) {
            let config = MapConfig { seed: preset.seed.wrapping_add(i), ..config.clone() };
            let start = Instant::now();
            std::hint::black_box(Terrain::new(config).expect("a valid config"));
            row.push(start.elapsed());
        }
    }
    println!("Civ6 Huge (106x66, wrapping, climate, rivers, relief), compiling the map, {seeds} seeds, median:");
    let baseline = median(times[0].clone());
    for ((name, _), row) in configs.iter().zip(times) {
        let m = median(row);
        println!("{name:<24} {:>10} {:>6.2}x", ms(m), m.as_secs_f64() / baseline.as_secs_f64());
    }
}
