//! A Standard globe (frequency 21: 4,412 tiles) beside the flat Civ6 Standard map (84x54:
//! 4,536 tiles) in one run, both with the same noise, thresholds and inner rings and nothing
//! else (no climate, rivers, relief or shape), for 1, 2 and 3 inner rings: compiling and meshing
//! the whole map, the whole globe, and the globe chunk by chunk; the median over the runs and the
//! globe's ratio to the flat map. Then each map's noise floor: the fBm alone at every point its
//! mesh has (2D on the flat map, 3D at each direction on the globe), and the globe's floor as a
//! share of the flat map's whole generation: what the globe's noise alone takes of it.
//!
//! `cargo bench -p hex_terrain_bench --bench globe` (20 runs; `HEXTERRAIN_RUNS` for more)

use std::time::{Duration, Instant};

use hex_terrain::{GlobeTerrain, MapConfig, MapSize, Terrain};
use hex_terrain_bench::{generate, median, ms, noise_floor};

fn main() {
    let runs: usize = std::env::var("HEXTERRAIN_RUNS").ok().and_then(|s| s.parse().ok()).unwrap_or(20);
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/maps/globe/standard.map.ron");
    let globe = MapConfig::load(path).expect("the Standard globe");
    println!("Standard globe (f = 21, 4,412 tiles) beside flat Standard (84x54, 4,536 tiles), {runs} runs, median:");
    println!(
        "{:<6} {:>10} {:>14} {:>14} {:>9} {:>9} {:>12} {:>14} {:>14} {:>11}",
        "rings",
        "flat ms",
        "globe ms",
        "chunked ms",
        "ratio",
        "chunked",
        "globe verts",
        "flat noise ms",
        "globe noise ms",
        "noise/flat"
    );
    for rings in 1..=3 {
        let mut globe = globe.clone();
        globe.terrain.inner_rings = rings;
        let flat = MapConfig { size: MapSize::Bounded { x: 84, z: 54 }, ..globe.clone() };
        let (mut f, mut g, mut c) = (Vec::new(), Vec::new(), Vec::new());
        let (mut fnoise, mut gnoise) = (Vec::new(), Vec::new());
        let mut vertices = 0;
        for _ in 0..runs {
            let start = Instant::now();
            let terrain = Terrain::new(flat.clone()).expect("a valid config");
            std::hint::black_box(generate(&terrain));
            f.push(start.elapsed());
            let start = Instant::now();
            let terrain = GlobeTerrain::new(globe.clone()).expect("a valid globe");
            let mesh = std::hint::black_box(terrain.generate_whole());
            g.push(start.elapsed());
            vertices = mesh.buffers.positions.len();
            let start = Instant::now();
            let terrain = GlobeTerrain::new(globe.clone()).expect("a valid globe");
            for chunk in terrain.chunks() {
                std::hint::black_box(terrain.generate(chunk));
            }
            c.push(start.elapsed());
            let (flat_terrain, globe_terrain) = (
                Terrain::new(flat.clone()).expect("a valid config"),
                GlobeTerrain::new(globe.clone()).expect("a valid globe"),
            );
            let start = Instant::now();
            std::hint::black_box(noise_floor(&flat_terrain));
            fnoise.push(start.elapsed());
            let start = Instant::now();
            std::hint::black_box(globe_terrain.noise_floor());
            gnoise.push(start.elapsed());
        }
        let (fnoise, gnoise) = (median(fnoise), median(gnoise));
        let (f, g, c): (Duration, Duration, Duration) = (median(f), median(g), median(c));
        println!(
            "{rings:<6} {:>10} {:>14} {:>14} {:>9.2} {:>9.2} {vertices:>12} {:>14} {:>14} {:>11.2}",
            ms(f).trim(),
            ms(g).trim(),
            ms(c).trim(),
            g.as_secs_f64() / f.as_secs_f64(),
            c.as_secs_f64() / f.as_secs_f64(),
            ms(fnoise).trim(),
            ms(gnoise).trim(),
            gnoise.as_secs_f64() / f.as_secs_f64()
        );
    }
}
