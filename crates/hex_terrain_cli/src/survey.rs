//! `hexterrain survey`: one map config over many seeds, and what came out: each statistic's
//! minimum, median and maximum, and the time a map took. How a map designer tunes a config, and
//! how a map type is shown to keep its promises.

use std::path::Path;
use std::time::Instant;

use hex_terrain::{
    Biome, MapConfig, MapSize, MapStats, MapTypeReport, MapTypeTarget, RiverModel, SurveyFigure, SurveyTarget,
    SurveyVerdict, Terrain, WaterLevel, survey_targets,
};

use crate::CliResult;

/// Most seeds a survey runs (a survey of more is a benchmark).
const MAX_SEEDS: u32 = 100_000;

/// The map types' presets (Civilization VI Standard, wrapping), by the name `survey` takes.
const TYPE_PRESETS: [(&str, &str); 6] = [
    ("pangaea", include_str!("../../../assets/maps/types/pangaea.map.ron")),
    ("continents", include_str!("../../../assets/maps/types/continents.map.ron")),
    ("small-continents", include_str!("../../../assets/maps/types/small_continents.map.ron")),
    ("archipelago", include_str!("../../../assets/maps/types/archipelago.map.ron")),
    ("fractal", include_str!("../../../assets/maps/types/fractal.map.ron")),
    ("inland-sea", include_str!("../../../assets/maps/types/inland_sea.map.ron")),
];

/// The map config at `path`, or the preset of the map type `path` names when no such file
/// exists.
pub fn map_or_type(path: &Path) -> CliResult<MapConfig> {
    let name = path.to_string_lossy().to_ascii_lowercase().replace('_', "-");
    match TYPE_PRESETS.iter().find(|(n, _)| *n == name) {
        Some((_, preset)) if !path.exists() => {
            MapConfig::from_ron(preset).map_err(|e| format!("the {name} preset: {e}"))
        }
        _ => crate::load(path),
    }
}

/// What `survey` varies besides the seed.
pub struct Options {
    /// How many seeds.
    pub seeds: u32,
    /// The map's size instead of the config's.
    pub size: Option<(u32, u32)>,
    /// A map type's water level instead of the config's.
    pub water: Option<WaterLevel>,
}

/// Runs the survey of `config` over `options.seeds` seeds (the config's seed, then the next
/// ones), at `options.size` and `options.water` when given.
pub fn run(path: &Path, mut config: MapConfig, options: &Options) -> CliResult<()> {
    let seeds = options.seeds;
    if !(1..=MAX_SEEDS).contains(&seeds) {
        return Err(format!("--seeds {seeds} is out of range: 1..={MAX_SEEDS} are allowed"));
    }
    if let Some((x, z)) = options.size {
        config.size = MapSize::Bounded { x, z };
    }
    if let Some(water) = options.water {
        let Some(map_type) = config.map_type.as_mut() else {
            return Err(format!("{}: --water needs a map with a map type (its `map_type`)", path.display()));
        };
        map_type.water = water;
    }
    if config.size.bounds().is_none() {
        return Err(format!("{}: an unbounded world has no whole to survey; give --size COLUMNSxROWS", path.display()));
    }
    let (x, z) = config.size.bounds().expect("bounded");
    let first = config.seed;
    let mut rows: Vec<Row> = Vec::with_capacity(seeds as usize);
    let mut refused = Vec::new();
    // The map's own terrain ruleset, if it has one: its terrains and features are surveyed too.
    let mut ruleset: Option<hex_terrain::TerrainRuleset> = None;
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
        if terrain.has_own_ruleset() && ruleset.is_none() {
            ruleset = Some(terrain.ruleset().clone());
        }
        let stats = MapStats::measure(&terrain).expect("a bounded map");
        let measured = began.elapsed() - compiled;
        rows.push(Row {
            seed,
            stats,
            map_type: terrain.map_type().cloned(),
            compile_ms: compiled.as_secs_f64() * 1e3,
            measure_ms: measured.as_secs_f64() * 1e3,
        });
    }
    println!(
        "{} ({}), {x}x{z}{}: {} seeds from {first}, {:.1} s",
        config.name,
        path.display(),
        if config.wrap { ", wrapping" } else { "" },
        seeds,
        start.elapsed().as_secs_f64()
    );
    println!("{:<40} {:>10} {:>10} {:>10}", "statistic", "min", "median", "max");
    let percent = |f: fn(&MapStats) -> f64| move |r: &Row| 100.0 * f(&r.stats);
    let count = |f: fn(&MapStats) -> u32| move |r: &Row| f64::from(f(&r.stats));
    let (map_columns, map_rows) = (f64::from(x), f64::from(z));
    let figure = move |r: &Row, f: SurveyFigure| f.of(&r.stats, (x, z));
    let extent = move |r: &Row, f: fn(&hex_terrain::Landmass) -> u32, whole: f64| {
        r.stats.continents().map(|c| 100.0 * f64::from(f(c)) / whole).fold(f64::NAN, f64::min)
    };
    use SurveyFigure::{ContinentsInLine, LargestLandmassWidth, ThirdLandmassTiles, TinyLandmassShare};
    let lines: [(&str, Statistic); 34] = [
        ("water share (%)", Box::new(percent(MapStats::water_share))),
        ("land tiles", Box::new(count(|s| s.land_tiles))),
        ("continents", Box::new(count(|s| s.continents().count() as u32))),
        ("islands", Box::new(count(|s| s.islands().count() as u32))),
        ("largest landmass (% of land)", Box::new(percent(MapStats::largest_landmass_share))),
        ("coast (tile edges)", Box::new(count(|s| s.coast_edges))),
        ("mountains (% of land)", Box::new(percent(MapStats::mountain_share))),
        ("mountains in ranges (%)", Box::new(percent(MapStats::range_share))),
        ("mountain neighbors a mountain", Box::new(|r: &Row| r.stats.mountain_neighbors())),
        ("longest range (tiles end to end)", Box::new(count(|s| s.longest_range))),
        ("river systems", Box::new(count(|s| s.rivers.systems))),
        ("tiles on a river", Box::new(count(|s| s.rivers.tiles))),
        ("river edges (rivers on edges)", Box::new(count(|s| s.rivers.edges))),
        ("longest river (tiles; on edges, edges)", Box::new(count(|s| s.rivers.longest))),
        ("lakes", Box::new(count(|s| s.lakes))),
        ("straightest ridge (mountains in a row)", Box::new(count(|s| s.straight_ridge))),
        ("mountains in blobs (%)", Box::new(percent(MapStats::blob_share))),
        ("polar rows' land (% of land)", Box::new(percent(MapStats::polar_land_share))),
        ("snow, tundra, snow peaks (% of land)", Box::new(percent(MapStats::cold_share))),
        ("deserts (% of land)", Box::new(|r: &Row| 100.0 * r.stats.biome_share(Biome::Desert))),
        ("lake tiles (% of land)", Box::new(percent(MapStats::lake_share))),
        ("lakes per 1,000 land tiles", Box::new(|r: &Row| r.stats.lakes_per_thousand())),
        ("land on a river (%)", Box::new(percent(MapStats::river_share))),
        ("river length, median of the map", Box::new(count(|s| s.rivers.median))),
        ("sources near hills or mountains (%)", Box::new(percent(MapStats::sources_near_relief_share))),
        ("continents' least height (% of rows)", Box::new(move |r: &Row| extent(r, |c| c.rows, map_rows))),
        ("continents' least width (% of columns)", Box::new(move |r: &Row| extent(r, |c| c.columns, map_columns))),
        ("largest landmass' width (% of columns)", Box::new(move |r: &Row| 100.0 * figure(r, LargestLandmassWidth))),
        ("continents in line (% of pairs)", Box::new(move |r: &Row| 100.0 * figure(r, ContinentsInLine))),
        ("third largest landmass (tiles)", Box::new(move |r: &Row| figure(r, ThirdLandmassTiles))),
        ("landmasses of 1-3 tiles (%)", Box::new(move |r: &Row| 100.0 * figure(r, TinyLandmassShare))),
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
                println!("{name:<40} {min:>10.1} {median:>10.1} {max:>10.1}{shown}");
            }
            _ => println!("{name:<40} {:>10}", "none"),
        }
    }
    if let Some(ruleset) = &ruleset {
        print_terrains(ruleset, &rows);
    }
    let reports: Vec<&MapTypeReport> = rows.iter().filter_map(|r| r.map_type.as_ref()).collect();
    if let Some(first) = reports.first() {
        print_map_type(first.kind.name(), &reports);
        let on_edges = config.rivers.model == RiverModel::Edges;
        let targets = survey_targets(first.kind, on_edges, config.climate.winds.is_some());
        print_targets(&targets, &rows, (x, z));
    }
    for line in &refused {
        println!("refused: {line}");
    }
    Ok(())
}

/// The map type's lines: how many maps met every target, the tries they took, and each
/// target's spread and misses.
fn print_map_type(name: &str, reports: &[&MapTypeReport]) {
    let met = reports.iter().filter(|r| r.met()).count();
    let mut tries: Vec<u32> = reports.iter().map(|r| r.tries).collect();
    tries.sort_unstable();
    let within = |lo: u32, hi: u32| tries.iter().filter(|&&t| (lo..=hi).contains(&t)).count();
    println!(
        "map type {name}: {met} of {} maps met every target; tries min {} median {} max {} \
         (1: {}, 2-5: {}, 6-20: {}, more: {})",
        reports.len(),
        tries[0],
        tries[tries.len() / 2],
        tries[tries.len() - 1],
        within(1, 1),
        within(2, 5),
        within(6, 20),
        within(21, u32::MAX),
    );
    println!("{:<40} {:>10} {:>10} {:>10} {:>8}", "target", "min", "median", "max", "missed");
    let targets: Vec<MapTypeTarget> = reports[0].checks.iter().map(|c| c.target).collect();
    for target in targets {
        let checks: Vec<_> = reports.iter().filter_map(|r| r.check(target)).collect();
        let scale = if target.is_share() { 100.0 } else { 1.0 };
        let mut values: Vec<f64> = checks.iter().map(|c| c.measured * scale).collect();
        values.sort_by(f64::total_cmp);
        let missed = checks.iter().filter(|c| !c.met()).count();
        let unit = if scale == 100.0 { " (%)" } else { "" };
        let shown = |v: f64| if v.is_infinite() { "none".to_owned() } else { format!("{v:.1}") };
        println!(
            "{:<40} {:>10} {:>10} {:>10} {missed:>8}",
            format!("{}{unit}", target.name()),
            shown(values[0]),
            shown(values[values.len() / 2]),
            shown(values[values.len() - 1]),
        );
    }
}

/// The survey's targets ([`survey_targets`]): each figure's median and 95th percentile on the
/// bad side beside their bounds, the worst seed, and the seeds that miss.
fn print_targets(targets: &[SurveyTarget], rows: &[Row], size: (u32, u32)) {
    let verdicts: Vec<SurveyVerdict> = targets.iter().map(|t| t.judge(&values(t, rows, size))).collect();
    let met = verdicts.iter().filter(|v| v.met).count();
    println!("survey targets: {met} of {} met", targets.len());
    println!(
        "{:<42} {:>9} {:>9} {:>12} {:>22}  verdict",
        "figure", "median", "95th", "worst (seed)", "bound (median; 95th)"
    );
    for (target, verdict) in targets.iter().zip(verdicts) {
        let scale = if target.figure.is_share() { 100.0 } else { 1.0 };
        let unit = if scale == 100.0 { " (%)" } else { "" };
        let shown = |v: f64| if v.is_infinite() { "-".to_owned() } else { format!("{:.1}", v * scale) };
        let side = if target.at_most { "<=" } else { ">=" };
        let every = target.every.map_or(String::new(), |e| format!("; all {side} {}", shown(e)));
        let bound = format!("{side} {}; {side} {}{every}", shown(target.median), shown(target.tail));
        let missed = match verdict.missed.len() {
            0 => String::new(),
            n => {
                let first: Vec<String> = verdict.missed.iter().take(8).map(u32::to_string).collect();
                format!(" ({n} seeds past the bound: {}{})", first.join(", "), if n > 8 { ", ..." } else { "" })
            }
        };
        println!(
            "{:<42} {:>9} {:>9} {:>12} {bound:>22}  {}{missed}",
            format!("{}{unit}", target.figure.name()),
            shown(verdict.median),
            shown(verdict.tail),
            format!("{} ({})", shown(verdict.worst.1), verdict.worst.0),
            if verdict.met { "met" } else { "MISSED" },
        );
    }
}

/// Each seed's figure of a target.
fn values(target: &SurveyTarget, rows: &[Row], size: (u32, u32)) -> Vec<(u32, f64)> {
    rows.iter().map(|r| (r.seed, target.figure.of(&r.stats, size))).collect()
}

/// How a statistic is read from a seed's map.
type Statistic = Box<dyn Fn(&Row) -> f64>;

/// One seed's map.
/// Each terrain's and feature's share of the map's tiles under its own ruleset: minimum, median
/// and maximum over the seeds.
fn print_terrains(ruleset: &hex_terrain::TerrainRuleset, rows: &[Row]) {
    let spread = |name: String, share: &dyn Fn(&Row) -> f64| {
        let mut values: Vec<f64> = rows.iter().map(|r| 100.0 * share(r)).collect();
        values.sort_by(f64::total_cmp);
        if let (Some(min), Some(max)) = (values.first(), values.last()) {
            println!("{name:<40} {min:>10.1} {:>10.1} {max:>10.1}", values[values.len() / 2]);
        }
    };
    for (i, def) in ruleset.terrains.iter().enumerate() {
        spread(format!("terrain {} (% of tiles)", def.id), &|r: &Row| {
            let n = r.stats.terrains.iter().find(|e| usize::from(e.0.0) == i).map_or(0, |e| e.1);
            f64::from(n) / f64::from(r.stats.tiles.max(1))
        });
    }
    for (i, def) in ruleset.features.iter().enumerate() {
        spread(format!("feature {} (% of tiles)", def.id), &|r: &Row| {
            f64::from(r.stats.features.get(i).map_or(0, |e| e.1)) / f64::from(r.stats.tiles.max(1))
        });
    }
}

struct Row {
    seed: u32,
    stats: MapStats,
    /// What came of the map's type, if it has one.
    map_type: Option<MapTypeReport>,
    /// `Terrain::new`.
    compile_ms: f64,
    /// `MapStats::measure`.
    measure_ms: f64,
}
