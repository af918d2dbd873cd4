//! `hexterrain survey`: one map config over many seeds, and what came out: each statistic's
//! minimum, median and maximum, and the time a map took. How a map designer tunes a config, and
//! how a map type is shown to keep its promises.

use std::path::Path;
use std::time::Instant;

use hex_terrain::{MapConfig, MapSize, MapStats, Terrain};

use crate::CliResult;

/// Most seeds a survey runs (a survey of more is a benchmark).
const MAX_SEEDS: u32 = 100_000;

/// Runs the survey of `config` over `seeds` seeds (the config's seed, then the next ones), at
/// `size` when given.
pub fn run(path: &Path, mut config: MapConfig, seeds: u32, size: Option<(u32, u32)>) -> CliResult<()> {
    if !(1..=MAX_SEEDS).contains(&seeds) {
        return Err(format!("--seeds {seeds} is out of range: 1..={MAX_SEEDS} are allowed"));
    }
    if let Some((x, z)) = size {
        config.size = MapSize::Bounded { x, z };
    }
    if config.size.bounds().is_none() {
        return Err(format!("{}: an unbounded world has no whole to survey; give --size COLUMNSxROWS", path.display()));
    }
    let first = config.seed;
    let mut rows: Vec<Row> = Vec::with_capacity(seeds as usize);
    let mut refused = Vec::new();
    let start = Instant::now();
    for i in 0..seeds {
        let seed = first.wrapping_add(i);
        let began = Instant::now();
        let terrain = match Terrain::new(MapConfig { seed, ..config.clone() }) {
            Ok(t) => t,
            Err(e) => {
                refused.push(format!("seed {seed}: {e}"));
                continue;
            }
        };
        let compiled = began.elapsed();
        let stats = MapStats::measure(&terrain).expect("a bounded map");
        let measured = began.elapsed() - compiled;
        rows.push(Row { stats, compile_ms: compiled.as_secs_f64() * 1e3, measure_ms: measured.as_secs_f64() * 1e3 });
    }
    let (x, z) = config.size.bounds().expect("bounded");
    println!(
        "{} ({}), {x}x{z}{}: {} seeds from {first}, {:.1} s",
        config.name,
        path.display(),
        if config.wrap { ", wrapping" } else { "" },
        seeds,
        start.elapsed().as_secs_f64()
    );
    println!("{:<34} {:>10} {:>10} {:>10}", "statistic", "min", "median", "max");
    let percent = |f: fn(&MapStats) -> f64| move |r: &Row| 100.0 * f(&r.stats);
    let count = |f: fn(&MapStats) -> u32| move |r: &Row| f64::from(f(&r.stats));
    let lines: [(&str, Statistic); 14] = [
        ("water share (%)", Box::new(percent(MapStats::water_share))),
        ("land tiles", Box::new(count(|s| s.land_tiles))),
        ("continents", Box::new(count(|s| s.continents().count() as u32))),
        ("islands", Box::new(count(|s| s.islands().count() as u32))),
        ("largest landmass (% of land)", Box::new(percent(MapStats::largest_landmass_share))),
        ("coast (tile edges)", Box::new(count(|s| s.coast_edges))),
        ("mountains (% of land)", Box::new(percent(MapStats::mountain_share))),
        ("mountains in ranges (%)", Box::new(percent(MapStats::range_share))),
        ("river systems", Box::new(count(|s| s.rivers.systems))),
        ("longest river (tiles)", Box::new(count(|s| s.rivers.longest))),
        ("lakes", Box::new(count(|s| s.lakes))),
        ("narrowest strait (tiles)", Box::new(|r: &Row| r.stats.narrowest_strait.map_or(f64::NAN, f64::from))),
        ("compile the map (ms)", Box::new(|r: &Row| r.compile_ms)),
        ("measure its statistics (ms)", Box::new(|r: &Row| r.measure_ms)),
    ];
    for (name, value) in &lines {
        let mut values: Vec<f64> = rows.iter().map(value).filter(|v| !v.is_nan()).collect();
        values.sort_by(f64::total_cmp);
        match (values.first(), values.last()) {
            (Some(min), Some(max)) => {
                let median = values[values.len() / 2];
                let shown = if name.starts_with("narrowest") {
                    format!(" ({} of {} maps have two continents)", values.len(), rows.len())
                } else {
                    String::new()
                };
                println!("{name:<34} {min:>10.1} {median:>10.1} {max:>10.1}{shown}");
            }
            _ => println!("{name:<34} {:>10}", "none"),
        }
    }
    for line in &refused {
        println!("refused: {line}");
    }
    Ok(())
}

/// How a statistic is read from a seed's map.
type Statistic = Box<dyn Fn(&Row) -> f64>;

/// One seed's map.
struct Row {
    stats: MapStats,
    /// `Terrain::new`.
    compile_ms: f64,
    /// `MapStats::measure`.
    measure_ms: f64,
}
