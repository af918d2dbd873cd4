//! Map types on Civ6 Huge (106x66, wrapping, climate, rivers and relief: the Huge preset),
//! beside the same preset without a type, in one run: per seed, compiling the map (its type's
//! tries included) and meshing it whole, then the median over the seeds, each type's ratio to
//! the preset's, how many maps met every target and how many tries they took. Each type also
//! as its preset plays (`assets/maps/types/`: winds, rivers on tile edges rising in the hills,
//! at the Huge size), with its compile time's ratio to the type's on the Huge preset.
//!
//! `cargo bench -p hex_terrain_bench --bench map_types` (40 seeds; `HEXTERRAIN_SEEDS=200` for
//! more)

use std::time::{Duration, Instant};

use hex_terrain::{MapConfig, MapType, MapTypeConfig, Terrain};
use hex_terrain_bench::{generate, median, ms};

/// A config's timings over the seeds: compiling, compiling and meshing, and its type's outcome
/// (met every target, tries).
type Row = (Vec<Duration>, Vec<Duration>, Vec<(bool, u32)>);

/// One seed's map: compiled, then meshed whole.
fn time(config: &MapConfig) -> (Duration, Duration, Option<(bool, u32)>) {
    let start = Instant::now();
    let terrain = Terrain::new(config.clone()).expect("a valid config");
    let compiled = start.elapsed();
    std::hint::black_box(generate(&terrain));
    let outcome = terrain.map_type().map(|r| (r.met(), r.tries));
    (compiled, start.elapsed(), outcome)
}

fn main() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/maps/civ6/huge.map.ron");
    let preset = MapConfig::load(path).expect("the Huge preset");
    let seeds: u32 = std::env::var("HEXTERRAIN_SEEDS").ok().and_then(|s| s.parse().ok()).unwrap_or(40);
    let mut configs = vec![("Huge preset (no type)".to_owned(), preset.clone())];
    let files = ["pangaea", "continents", "small_continents", "archipelago", "fractal", "inland_sea"];
    for (kind, file) in MapType::ALL.into_iter().zip(files) {
        let map_type = MapTypeConfig { kind, ranges: true, ..MapTypeConfig::default() };
        configs.push((kind.name().to_owned(), MapConfig { map_type: Some(map_type), ..preset.clone() }));
        let path = format!("{}/../../assets/maps/types/{file}.map.ron", env!("CARGO_MANIFEST_DIR"));
        let typed = MapConfig::load(&path).expect("the type's preset");
        let played = MapConfig { size: preset.size, seed: preset.seed, ..typed };
        configs.push((format!("{} as its preset", kind.name()), played));
    }
    // Seeds in the outer loop, so every config meets the machine in the same state.
    let mut rows: Vec<Row> = vec![Row::default(); configs.len()];
    std::hint::black_box(generate(&Terrain::new(preset.clone()).expect("a valid config")));
    for i in 0..seeds {
        for ((_, config), row) in configs.iter().zip(&mut rows) {
            let (compiled, total, outcome) = time(&MapConfig { seed: preset.seed.wrapping_add(i), ..config.clone() });
            row.0.push(compiled);
            row.1.push(total);
            row.2.extend(outcome);
        }
    }
    println!("Civ6 Huge (106x66, wrapping, climate, rivers, relief), {seeds} seeds, median per map:");
    println!(
        "{:<32} {:>10} {:>10} {:>8} {:>9} {:>6} {:>24}",
        "map", "compile ms", "+ mesh ms", "ratio", "compile x", "met", "tries 1 / 2-5 / 6-20 / more"
    );
    let baseline = median(rows[0].1.clone());
    for (k, ((name, _), (compiled, total, outcomes))) in configs.iter().zip(&rows).enumerate() {
        // A type as its preset: its compile time over the type's on the Huge preset (the row
        // before it).
        let against = if name.ends_with("as its preset") {
            let mine = median(compiled.clone()).as_secs_f64();
            format!("{:.2}", mine / median(rows[k - 1].0.clone()).as_secs_f64())
        } else {
            "-".to_owned()
        };
        let whole = median(total.clone());
        let tries = |lo: u32, hi: u32| outcomes.iter().filter(|(_, t)| (lo..=hi).contains(t)).count();
        let (met, spread) = if outcomes.is_empty() {
            ("-".to_owned(), "-".to_owned())
        } else {
            (
                outcomes.iter().filter(|(m, _)| *m).count().to_string(),
                format!("{} / {} / {} / {}", tries(1, 1), tries(2, 5), tries(6, 20), tries(21, u32::MAX)),
            )
        };
        println!(
            "{name:<32} {:>10} {:>10} {:>8.2} {against:>9} {met:>6} {spread:>24}",
            ms(median(compiled.clone())).trim_end_matches(" ms").trim(),
            ms(whole).trim_end_matches(" ms").trim(),
            whole.as_secs_f64() / baseline.as_secs_f64()
        );
    }
}
