//! `hexterrain-bench`: the thesis' run-time tables (7, 8, 9) measured here, with the basic PTG
//! baseline, the full pipeline (and the same keeping per-vertex diagnostics), the bare noise floor (ours and `noise`'s Perlin) and hexx's
//! column mesh builder run side by side in one process.
//!
//! ```text
//! cargo run --release -p hex_terrain_bench -- [--rings N] [--runs K] [--tables 7,8,9] [--max-hexes H] [--fresh-pages]
//! ```
//!
//! Every workload allocates its buffers afresh in every run. By default the process runs with
//! glibc's malloc told to keep freed memory ([`KEEP_MEMORY`]), as a game that generates
//! terrain over and over reaches in steady state; `--fresh-pages` leaves glibc's defaults, under
//! which large buffers go back to the system after each run and the next run pays a page fault
//! for every 4 KiB it writes (about 3 µs each on this machine's VM).

use std::hint::black_box;
use std::time::Instant;

use hex_terrain::Terrain;
use hex_terrain_bench::{
    TABLE_7, TABLE_8, TABLE_9, generate, generate_with_diagnostics, hexx_columns, noise_floor, noise_floor_reference,
    terrains, water_terrains,
};

/// glibc malloc settings (read from the environment at start-up) that keep freed memory in the
/// process: no trimming of the heap, and every block below 32 MiB served from it.
const KEEP_MEMORY: [(&str, &str); 2] =
    [("MALLOC_TRIM_THRESHOLD_", "17179869184"), ("MALLOC_MMAP_THRESHOLD_", "33554432")];

struct Args {
    rings: u32,
    runs: usize,
    tables: Vec<u32>,
    max_hexes: u64,
    fresh_pages: bool,
}

fn parse() -> Result<Args, String> {
    let mut args = Args { rings: 3, runs: 5, tables: vec![7, 8, 9], max_hexes: u64::MAX, fresh_pages: false };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let mut value = || it.next().ok_or_else(|| format!("{flag} needs a value"));
        match flag.as_str() {
            "--rings" => args.rings = value()?.parse().map_err(|e| format!("--rings: {e}"))?,
            "--runs" => args.runs = value()?.parse::<usize>().map_err(|e| format!("--runs: {e}"))?.max(1),
            "--max-hexes" => args.max_hexes = value()?.parse().map_err(|e| format!("--max-hexes: {e}"))?,
            "--fresh-pages" => args.fresh_pages = true,
            "--tables" => {
                args.tables = value()?
                    .split(',')
                    .map(|t| t.trim().parse().map_err(|e| format!("--tables: {e}")))
                    .collect::<Result<_, _>>()?;
            }
            "-h" | "--help" => {
                println!(
                    "hexterrain-bench [--rings N (inner rings, default 3: 48 vertices/hex, the thesis has ~32)] \
                     [--runs K (median of K, default 5)] [--tables 7,8,9] [--max-hexes H] \
                     [--fresh-pages (glibc's default malloc: freed memory goes back to the system)]"
                );
                std::process::exit(0);
            }
            other => return Err(format!("unknown argument {other}; see --help")),
        }
    }
    Ok(args)
}

/// Median wall times of each workload over `runs` interleaved rounds (each round runs every
/// workload once, in order), in milliseconds, so drift on a shared machine hits them alike.
fn time_interleaved(runs: usize, work: &mut [&mut dyn FnMut()]) -> Vec<f64> {
    let mut samples = vec![Vec::with_capacity(runs); work.len()];
    for _ in 0..runs {
        for (w, s) in work.iter_mut().zip(&mut samples) {
            let start = Instant::now();
            w();
            s.push(start.elapsed().as_secs_f64() * 1e3);
        }
    }
    samples
        .into_iter()
        .map(|mut s| {
            s.sort_by(f64::total_cmp);
            s[s.len() / 2]
        })
        .collect()
}

/// Median wall time of `runs` calls, in milliseconds.
fn time<T>(runs: usize, mut f: impl FnMut() -> T) -> f64 {
    let mut samples: Vec<f64> = (0..runs)
        .map(|_| {
            let start = Instant::now();
            black_box(f());
            start.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    samples.sort_by(f64::total_cmp);
    samples[samples.len() / 2]
}

fn row(label: &str, x: u32, z: u32, args: &Args) {
    let (full, basic) = terrains(x, z, args.rings);
    let hexes = u64::from(x) * u64::from(z);
    // Fewer runs for the largest maps, which take seconds each.
    let runs = if hexes > 100_000 { args.runs.min(3) } else { args.runs };
    let mesh = full.generate_map().expect("bounded");
    let (v, t) = (mesh.buffers.vertex_count(), mesh.buffers.triangle_count());
    drop(mesh);
    let reference = noise::Perlin::new(full.config().seed);
    let times = time_interleaved(
        runs,
        &mut [
            &mut || {
                black_box(generate(&basic));
            },
            &mut || {
                black_box(generate(&full));
            },
            &mut || {
                black_box(noise_floor(&full));
            },
            &mut || {
                black_box(noise_floor_reference(&full, &reference));
            },
            &mut || {
                black_box(generate_with_diagnostics(&full));
            },
        ],
    );
    let (basic_ms, full_ms, floor_ms, floor_ref_ms, diag_ms) = (times[0], times[1], times[2], times[3], times[4]);
    let mut peer_vertices = 0;
    let peer_ms = time(runs, || peer_vertices = hexx_columns(&full));
    println!(
        "| {label} | {x}x{z} | {hexes} | {v} | {t} | {:.1} | {basic_ms:.2} | {full_ms:.2} | {:.2} | {:.0} | {:+.1} | {diag_ms:.2} | {:+.1} | {floor_ms:.2} | {:.2} | {floor_ref_ms:.2} | {:.2} | {peer_ms:.2} | {peer_vertices} |",
        v as f64 / hexes as f64,
        full_ms * 1e3 / hexes as f64,
        full_ms * 1e6 / v as f64,
        (full_ms - basic_ms) / basic_ms * 100.0,
        (diag_ms - full_ms) / full_ms * 100.0,
        full_ms / floor_ms,
        floor_ref_ms / floor_ms,
    );
}

/// One row of the climate/rivers table: whole-map generation without and with biomes, rivers
/// and lakes (same run, interleaved), and compiling each config (`Terrain::new`: the water
/// network, biomes and their noise field are built there, once per map). Returns the river and
/// lake network's time: compiling with rivers less compiling with the climate alone.
fn water_row(label: &str, x: u32, z: u32, args: &Args) -> f64 {
    let (plain_config, water_config) = water_terrains(x, z, args.rings);
    let mut climate_config = water_config.clone();
    climate_config.rivers.enabled = false;
    let plain = Terrain::new(plain_config.clone()).expect("valid");
    let water = Terrain::new(water_config.clone()).expect("valid");
    // Generation and compiling are timed apart, so neither's allocations sit between the other's
    // runs.
    let mut times = time_interleaved(
        args.runs,
        &mut [
            &mut || {
                black_box(generate(&plain));
            },
            &mut || {
                black_box(generate(&water));
            },
        ],
    );
    times.extend(time_interleaved(
        args.runs,
        &mut [
            &mut || {
                black_box(Terrain::new(plain_config.clone()).expect("valid"));
            },
            &mut || {
                black_box(Terrain::new(water_config.clone()).expect("valid"));
            },
            &mut || {
                black_box(Terrain::new(climate_config.clone()).expect("valid"));
            },
        ],
    ));
    let rivers = water.rivers().len();
    let lakes = water.hydrology().map_or(0, |h| h.lake_count());
    println!(
        "| {label} | {x}x{z} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {rivers} | {lakes} |",
        times[0],
        times[1],
        times[1] / times[0],
        times[2],
        times[4],
        times[3],
        times[3] - times[4],
    );
    times[3] - times[4]
}

/// One row of the wrapping table: the same map planar and wrapping east to west (periodic noise
/// read at canonical points), sampling the noise at every mesh point and generating the whole
/// map, interleaved in one run. Returns the noise-sampling ratio, wrapping / planar.
fn wrap_row(label: &str, x: u32, z: u32, args: &Args) -> f64 {
    let (planar, _) = terrains(x, z, args.rings);
    let wrapped = Terrain::new(hex_terrain::MapConfig { wrap: true, ..planar.config().clone() }).expect("valid");
    let times = time_interleaved(
        args.runs,
        &mut [
            &mut || {
                black_box(noise_floor(&planar));
            },
            &mut || {
                black_box(noise_floor(&wrapped));
            },
            &mut || {
                black_box(generate(&planar));
            },
            &mut || {
                black_box(generate(&wrapped));
            },
        ],
    );
    println!(
        "| {label} | {x}x{z} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} |",
        times[0],
        times[1],
        times[1] / times[0],
        times[2],
        times[3],
        times[3] / times[2]
    );
    times[1] / times[0]
}

/// Players of a Civilization VI game at each size (Duel to Huge).
const CIV6_PLAYERS: [u32; 6] = [2, 4, 6, 8, 10, 12];

/// One row of the start-of-game table: the whole world a game gets on a Civ6 size (its preset:
/// climate, rivers, lakes, relief, wrapping), interleaved in one run: compiling it, its game
/// setup for the size's players, meshing it whole, and all of it again with the Continents map
/// type (mountain ranges on), and with the weather (Earth's prevailing winds) and rivers on the
/// tiles' edges.
fn start_row(name: &str, players: u32, args: &Args) {
    let path = format!("{}/../../assets/maps/civ6/{}.map.ron", env!("CARGO_MANIFEST_DIR"), name.to_lowercase());
    let plain = hex_terrain::MapConfig::load(&path).expect("the Civ6 preset");
    let setup = Some(hex_terrain::SetupConfig { players, ..hex_terrain::SetupConfig::default() });
    let with_setup = hex_terrain::MapConfig { setup: setup.clone(), ..plain.clone() };
    let map_type = hex_terrain::MapTypeConfig { ranges: true, ..hex_terrain::MapTypeConfig::default() };
    let typed = hex_terrain::MapConfig { map_type: Some(map_type), ..with_setup.clone() };
    let mut weather = with_setup.clone();
    weather.climate.winds = Some(hex_terrain::WindConfig::default());
    weather.rivers.model = hex_terrain::RiverModel::Edges;
    let world = Terrain::new(with_setup.clone()).expect("the preset takes its players");
    let times = time_interleaved(
        args.runs,
        &mut [
            &mut || {
                black_box(Terrain::new(plain.clone()).expect("valid"));
            },
            &mut || {
                black_box(Terrain::new(with_setup.clone()).expect("valid"));
            },
            &mut || {
                black_box(generate(&world));
            },
            &mut || {
                black_box(generate(&Terrain::new(with_setup.clone()).expect("valid")));
            },
            &mut || {
                black_box(generate(&Terrain::new(typed.clone()).expect("valid")));
            },
            &mut || {
                black_box(generate(&Terrain::new(weather.clone()).expect("valid")));
            },
        ],
    );
    let (x, z) = plain.size.bounds().expect("bounded");
    println!(
        "| Civ6 {name} | {x}x{z} | {players} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} |",
        times[0],
        times[1] - times[0],
        times[2],
        times[3],
        times[4],
        times[5]
    );
}

/// Runs this program again with [`KEEP_MEMORY`] in its environment, unless it is there already
/// (or `--fresh-pages` was given); returns whether it did, with the child's exit code.
fn rerun_keeping_memory(args: &Args) -> Option<i32> {
    if args.fresh_pages || std::env::var_os(KEEP_MEMORY[0].0).is_some() {
        return None;
    }
    let exe = std::env::current_exe().ok()?;
    let status = std::process::Command::new(exe).args(std::env::args_os().skip(1)).envs(KEEP_MEMORY).status().ok()?;
    Some(status.code().unwrap_or(1))
}

fn main() {
    let args = match parse() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    };
    if let Some(code) = rerun_keeping_memory(&args) {
        std::process::exit(code);
    }
    let memory = if args.fresh_pages {
        "glibc malloc defaults (freed memory returns to the system)".to_string()
    } else {
        format!("glibc malloc keeps freed memory ({})", KEEP_MEMORY.map(|(k, v)| format!("{k}={v}")).join(" "))
    };
    println!(
        "hex_terrain generation, Map0 parameters, {} inner ring(s), {} threads, median of {} runs, {memory}",
        args.rings,
        rayon::current_num_threads(),
        args.runs
    );
    println!();
    println!(
        "| map | size | hexes | vertices | triangles | v/hex | basic ms | full ms | full us/hex | full ns/vertex | overhead % | full + diagnostics ms | diagnostics cost % | noise floor ms | full/floor | noise-crate floor ms | floor speed-up | hexx columns ms | hexx vertices |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for table in &args.tables {
        let sizes: Vec<(String, u32, u32)> = match table {
            7 => TABLE_7.iter().map(|&(x, z)| ("table 7".to_string(), x, z)).collect(),
            8 => TABLE_8.iter().map(|&(x, z)| ("table 8".to_string(), x, z)).collect(),
            9 => TABLE_9.iter().map(|&(n, x, z)| (format!("Civ6 {n}"), x, z)).collect(),
            other => {
                eprintln!("error: no table {other}; tables are 7, 8 and 9");
                std::process::exit(2);
            }
        };
        for (label, x, z) in sizes {
            if u64::from(x) * u64::from(z) <= args.max_hexes {
                row(&label, x, z, &args);
            }
        }
    }
    if args.tables.contains(&9) {
        println!();
        println!("Climate (biomes), rivers and lakes on the Civ6 sizes, Map0 parameters, same run:");
        println!();
        println!(
            "| map | size | plain ms | with water ms | ratio | compile plain ms | compile + climate ms | compile + climate + rivers ms | river/lake network ms | river tiles | lakes |"
        );
        println!("|---|---|---|---|---|---|---|---|---|---|---|");
        let mut network = 0.0;
        for (name, x, z) in TABLE_9 {
            network = water_row(&format!("Civ6 {name}"), x, z, &args);
        }
        println!();
        println!("river and lake network, Civ6 Huge: {network:.2} ms (compiling with rivers less without)");
        println!();
        println!(
            "East-west wrapping on the Civ6 sizes, Map0 parameters, same run (planar, then the same map wrapping):"
        );
        println!();
        println!(
            "| map | size | noise planar ms | noise wrapping ms | noise ratio | generate planar ms | generate wrapping ms | generate ratio |"
        );
        println!("|---|---|---|---|---|---|---|---|");
        let worst =
            TABLE_9.iter().map(|&(name, x, z)| wrap_row(&format!("Civ6 {name}"), x, z, &args)).fold(0.0, f64::max);
        println!();
        println!("wrapping noise sampling costs at most {worst:.2}x the planar sampling (limit 1.5x)");
        println!();
        println!(
            "The whole world a game gets at start, each Civ6 preset (climate, rivers, lakes, relief, wrapping), same run; then with the Continents map type, and with the winds and rivers on edges:"
        );
        println!();
        println!(
            "| map | size | players | compile ms | setup ms | meshes ms | whole world ms | whole world, Continents map type ms | whole world, winds and edge rivers ms |"
        );
        println!("|---|---|---|---|---|---|---|---|---|");
        for ((name, _, _), players) in TABLE_9.into_iter().zip(CIV6_PLAYERS) {
            start_row(name, players, &args);
        }
    }
}
