//! Our fBm kernels against the Rust noise libraries, then the whole-map figures per kernel.
//!
//! First table: 1,000,000 points (a 1000x1000 grid, 0.05 noise units apart) of 10-octave 2D
//! Perlin fBm with Map0's persistence 0.3 and lacunarity 2, on one thread and on all cores, the
//! contenders interleaved round by round, the median of the rounds. Every contender is built as
//! its crate documents and fed the grid row by row (1,000 points a call). Our kernels are the
//! same bits (a test holds them to it); `noise::Perlin` is the reference our tests compare with.
//!
//! Second table: Civ6 Huge (106x66, Map0) generated whole and its noise floor (the bare fBm at
//! every point generation samples) on each of our kernels, interleaved, with the ratio to the
//! portable kernel.
//!
//! `cargo bench -p hex_terrain_bench --bench noise -- [--rounds N]`

use std::hint::black_box;
use std::time::{Duration, Instant};

use hex_terrain::{Fbm, Kernel};
use hex_terrain::{NoiseConfig, Terrain};
use hex_terrain_bench::{generate, median, noise_floor, terrains};
use libnoise::Generator;
use noise::{MultiFractal, NoiseFn};
use rayon::prelude::*;

const SIDE: usize = 1000;
const STEP: f64 = 0.05;
const ORIGIN: [f64; 2] = [12.3, -7.7];
const SEED: u32 = 1000;
const OCTAVES: u32 = 10;
const PERSISTENCE: f64 = 0.3;
const LACUNARITY: f64 = 2.0;

/// A contender: its name, its precision, and one row of the grid (row `r`), summed.
struct Contender {
    name: String,
    precision: &'static str,
    row: Box<dyn Fn(usize) -> f64 + Sync>,
}

fn grid_x(i: usize) -> f64 {
    ORIGIN[0] + i as f64 * STEP
}

fn grid_z(r: usize) -> f64 {
    ORIGIN[1] + r as f64 * STEP
}

fn ours(kernel: Kernel) -> Option<Contender> {
    // Scale 4 makes one hex radius one noise unit, so the grid is in the peers' units.
    let config = NoiseConfig { octaves: OCTAVES, persistence: PERSISTENCE, lacunarity: LACUNARITY, scale: 4.0 };
    let fbm = Fbm::new(SEED, &config).with_kernel(kernel)?;
    let detected = if kernel == Kernel::detect() { ", detected" } else { "" };
    Some(Contender {
        name: format!("hex_terrain `Fbm::sample_many` ({}{detected})", kernel.name()),
        precision: "f64",
        row: Box::new(move |r| {
            let points: Vec<[f64; 2]> = (0..SIDE).map(|i| [grid_x(i), grid_z(r)]).collect();
            let mut out = vec![0.0; SIDE];
            fbm.sample_many(&points, &mut out);
            out.iter().sum()
        }),
    })
}

fn peers() -> Vec<Contender> {
    let noise_fbm = noise::Fbm::<noise::Perlin>::new(SEED)
        .set_octaves(OCTAVES as usize)
        .set_persistence(PERSISTENCE)
        .set_lacunarity(LACUNARITY)
        .set_frequency(1.0);
    let mut lite = fastnoise_lite::FastNoiseLite::with_seed(SEED as i32);
    lite.set_noise_type(Some(fastnoise_lite::NoiseType::Perlin));
    lite.set_fractal_type(Some(fastnoise_lite::FractalType::FBm));
    lite.set_fractal_octaves(Some(OCTAVES as i32));
    lite.set_fractal_gain(Some(PERSISTENCE as f32));
    lite.set_fractal_lacunarity(Some(LACUNARITY as f32));
    lite.set_frequency(Some(1.0));
    let libnoise_fbm = libnoise::Source::<2>::perlin(u64::from(SEED)).fbm(OCTAVES, 1.0, LACUNARITY, PERSISTENCE);
    vec![
        Contender {
            name: "noise 0.9 `Fbm<Perlin>`".into(),
            precision: "f64",
            row: Box::new(move |r| (0..SIDE).map(|i| noise_fbm.get([grid_x(i), grid_z(r)])).sum()),
        },
        Contender {
            name: "fastnoise-lite 1.1 Perlin FBm".into(),
            precision: "f32",
            row: Box::new(move |r| {
                (0..SIDE).map(|i| f64::from(lite.get_noise_2d(grid_x(i) as f32, grid_z(r) as f32))).sum()
            }),
        },
        Contender {
            name: "libnoise 1.2 `perlin().fbm()`".into(),
            precision: "f64",
            row: Box::new(move |r| (0..SIDE).map(|i| libnoise_fbm.sample([grid_x(i), grid_z(r)])).sum()),
        },
        Contender {
            name: "simdnoise 3.1 gradient fbm (runtime SIMD)".into(),
            precision: "f32",
            row: Box::new(|r| {
                // Grid units times the frequency: x = (offset + i) * STEP.
                let (noise, _, _) = simdnoise::NoiseBuilder::fbm_2d_offset(
                    (ORIGIN[0] / STEP) as f32,
                    SIDE,
                    (grid_z(r) / STEP) as f32,
                    1,
                )
                .with_freq(STEP as f32)
                .with_octaves(OCTAVES as u8)
                .with_gain(PERSISTENCE as f32)
                .with_lacunarity(LACUNARITY as f32)
                .with_seed(SEED as i32)
                .generate();
                noise.iter().map(|&v| f64::from(v)).sum()
            }),
        },
    ]
}

fn timed(f: impl FnOnce() -> f64) -> Duration {
    let start = Instant::now();
    black_box(f());
    start.elapsed()
}

fn main() {
    let mut args = std::env::args().skip(1);
    let mut rounds = 7;
    while let Some(a) = args.next() {
        if a == "--rounds" {
            rounds = args.next().and_then(|v| v.parse().ok()).filter(|&n| n > 0).unwrap_or(rounds);
        }
    }
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("a one-thread pool");
    let contenders: Vec<Contender> = Kernel::ALL.into_iter().filter_map(ours).chain(peers()).collect();
    let (mut single, mut all) = (vec![Vec::new(); contenders.len()], vec![Vec::new(); contenders.len()]);
    for _ in 0..rounds {
        for (k, c) in contenders.iter().enumerate() {
            single[k].push(one.install(|| timed(|| (0..SIDE).map(|r| (c.row)(r)).sum())));
            all[k].push(timed(|| (0..SIDE).into_par_iter().map(|r| (c.row)(r)).sum()));
        }
    }
    let points = (SIDE * SIDE) as f64;
    let rate = |d: Duration| points / d.as_secs_f64() / 1e6;
    let detected =
        Kernel::ALL.into_iter().filter(|k| k.is_supported()).position(|k| k == Kernel::detect()).unwrap_or(0);
    let (base_single, base_all) = (rate(median(single[detected].clone())), rate(median(all[detected].clone())));
    println!(
        "10-octave 2D Perlin fBm (persistence {PERSISTENCE}, lacunarity {LACUNARITY}), {} points, median of {rounds} interleaved rounds; all cores = {} threads",
        SIDE * SIDE,
        rayon::current_num_threads()
    );
    println!();
    println!("| library | precision | M points/s, one thread | vs ours | M points/s, all cores | vs ours |");
    println!("|---|---|---|---|---|---|");
    for (k, c) in contenders.iter().enumerate() {
        let (s, a) = (rate(median(single[k].clone())), rate(median(all[k].clone())));
        println!("| {} | {} | {s:.1} | {:.2} | {a:.1} | {:.2} |", c.name, c.precision, s / base_single, a / base_all);
    }
    whole_map(rounds, &one);
}

/// Civ6 Huge generated whole, and its noise floor, on every kernel this CPU runs.
fn whole_map(rounds: usize, one: &rayon::ThreadPool) {
    let (full, _) = terrains(106, 66, 3);
    let kernels: Vec<(Kernel, Terrain)> =
        Kernel::ALL.into_iter().filter_map(|k| full.with_kernel(k).map(|t| (k, t))).collect();
    let floor = noise_floor(&kernels[0].1).to_bits();
    assert!(kernels.iter().all(|(_, t)| noise_floor(t).to_bits() == floor), "every kernel samples the same bits");
    let mut times = vec![[Vec::new(), Vec::new(), Vec::new(), Vec::new()]; kernels.len()];
    for _ in 0..rounds {
        for (k, (_, t)) in kernels.iter().enumerate() {
            times[k][0].push(timed(|| generate(t) as f64));
            times[k][1].push(timed(|| noise_floor(t)));
            times[k][2].push(one.install(|| timed(|| generate(t) as f64)));
            times[k][3].push(one.install(|| timed(|| noise_floor(t))));
        }
    }
    let ms = |v: &Vec<Duration>| median(v.clone()).as_secs_f64() * 1e3;
    println!();
    println!(
        "Civ6 Huge (106x66, Map0, 3 inner rings), median of {rounds} interleaved rounds; ratio = portable / this kernel"
    );
    println!();
    println!(
        "| kernel | full ms, all cores | ratio | floor ms, all cores | ratio | full ms, one thread | ratio | floor ms, one thread | ratio |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    let base: Vec<f64> = times[0].iter().map(ms).collect();
    for ((kernel, _), t) in kernels.iter().zip(&times) {
        let m: Vec<f64> = t.iter().map(ms).collect();
        println!(
            "| {} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} |",
            kernel.name(),
            m[0],
            base[0] / m[0],
            m[1],
            base[1] / m[1],
            m[2],
            base[2] / m[2],
            m[3],
            base[3] / m[3]
        );
    }
}
