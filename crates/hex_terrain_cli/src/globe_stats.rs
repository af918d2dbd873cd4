//! `hexterrain stats` and `hexterrain survey` on a globe config: its tiles, biomes, landmasses
//! and map type report ([`GlobeStats`]), and the same over many seeds (minimum, median and
//! maximum of each figure, and how many seeds met the map type's targets).

use std::path::Path;
use std::time::Instant;

use hex_terrain::{Biome, GlobeStats, GlobeTerrain, MapConfig, TileKind};

use crate::CliResult;

/// Most seeds a globe survey runs.
const MAX_SEEDS: u32 = 10_000;

/// Prints a globe's statistics.
pub fn stats(path: &Path, config: MapConfig) -> CliResult<()> {
    let start = Instant::now();
    let globe = GlobeTerrain::new(config).map_err(|e| format!("{}: {e}", path.display()))?;
    let compiled = start.elapsed();
    let grid = globe.grid();
    println!(
        "{} ({}): a globe of frequency {}, {} tiles (12 pentagons), radius {:.1}, compiled in {:.1} ms",
        globe.config().name,
        path.display(),
        grid.frequency(),
        grid.tile_count(),
        globe.radius(),
        compiled.as_secs_f64() * 1e3
    );
    println!("tiles:");
    for kind in TileKind::ALL {
        let count = grid.tiles().filter(|&t| globe.tile_kind(t) == Some(kind)).count();
        println!("  {:<9} {count}", kind.name());
    }
    let stats = GlobeStats::measure(&globe);
    if globe.config().climate.enabled {
        println!("biomes:");
        for (biome, count) in &stats.biomes {
            println!("  {:<11} {count}", biome.name());
        }
    }
    println!("{stats}");
    if let Some(report) = globe.map_type_report() {
        println!("map type {report}");
    }
    Ok(())
}

/// One globe of a survey.
struct Row {
    stats: GlobeStats,
    met: Option<bool>,
    ms: f64,
}

/// Surveys a globe config over `seeds` seeds from its own.
pub fn survey(path: &Path, config: MapConfig, seeds: u32) -> CliResult<()> {
    if !(1..=MAX_SEEDS).contains(&seeds) {
        return Err(format!("--seeds {seeds} is out of range for a globe: 1..={MAX_SEEDS} are allowed"));
    }
    let first = config.seed;
    let start = Instant::now();
    let mut rows = Vec::with_capacity(seeds as usize);
    for i in 0..seeds {
        let began = Instant::now();
        let config = MapConfig { seed: first.wrapping_add(i), ..config.clone() };
        let globe = GlobeTerrain::new(config).map_err(|e| format!("{}: {e}", path.display()))?;
        let stats = GlobeStats::measure(&globe);
        let met = globe.map_type_report().map(|r| r.met());
        rows.push(Row { stats, met, ms: began.elapsed().as_secs_f64() * 1e3 });
    }
    let frequency = config.size.globe().unwrap_or(0);
    println!(
        "{} ({}), a globe of frequency {frequency}: {seeds} seeds from {first}, {:.1} s",
        config.name,
        path.display(),
        start.elapsed().as_secs_f64()
    );
    println!("{:<40} {:>10} {:>10} {:>10}", "statistic", "min", "median", "max");
    let percent = |f: fn(&GlobeStats) -> f64| move |r: &Row| 100.0 * f(&r.stats);
    type Figure = Box<dyn Fn(&Row) -> f64>;
    let lines: [(&str, Figure); 12] = [
        ("water share (%)", Box::new(percent(GlobeStats::water_share))),
        ("land tiles", Box::new(|r: &Row| f64::from(r.stats.land_tiles))),
        ("continents", Box::new(|r: &Row| r.stats.continents().count() as f64)),
        ("islands", Box::new(|r: &Row| r.stats.islands().count() as f64)),
        ("largest landmass (% of land)", Box::new(percent(GlobeStats::largest_landmass_share))),
        ("narrowest strait (tiles)", Box::new(|r: &Row| r.stats.narrowest_strait.map_or(f64::NAN, f64::from))),
        ("coast (tile edges)", Box::new(|r: &Row| f64::from(r.stats.coast_edges))),
        ("mountains (% of land)", Box::new(percent(GlobeStats::mountain_share))),
        ("mountain neighbors a mountain", Box::new(|r: &Row| r.stats.mountain_neighbors())),
        ("polar land (% of land)", Box::new(percent(GlobeStats::polar_land_share))),
        ("snow, tundra, snow peaks (% of land)", Box::new(percent(GlobeStats::cold_share))),
        ("deserts (% of land)", Box::new(|r: &Row| desert(&r.stats))),
    ];
    for (name, figure) in &lines {
        let mut values: Vec<f64> = rows.iter().map(figure).filter(|v| !v.is_nan()).collect();
        if values.is_empty() {
            println!("{name:<40} {:>10} {:>10} {:>10}", "-", "-", "-");
            continue;
        }
        values.sort_by(f64::total_cmp);
        let (min, median, max) = (values[0], values[values.len() / 2], values[values.len() - 1]);
        println!("{name:<40} {min:>10.1} {median:>10.1} {max:>10.1}");
    }
    let mut ms: Vec<f64> = rows.iter().map(|r| r.ms).collect();
    ms.sort_by(f64::total_cmp);
    println!(
        "{:<40} {:>10.1} {:>10.1} {:>10.1}",
        "ms a globe (compile and measure)",
        ms[0],
        ms[ms.len() / 2],
        ms[ms.len() - 1]
    );
    if let Some(kind) = config.map_type.as_ref().map(|t| t.kind) {
        let met = rows.iter().filter(|r| r.met == Some(true)).count();
        println!("map type {}: its targets met on {met} of {seeds} seeds", kind.name());
    }
    Ok(())
}

/// Deserts' share of the land, in percent.
fn desert(stats: &GlobeStats) -> f64 {
    let tiles = stats.biomes.iter().find(|(b, _)| *b == Biome::Desert).map_or(0, |&(_, n)| n);
    100.0 * f64::from(tiles) / f64::from(stats.land_tiles.max(1))
}
