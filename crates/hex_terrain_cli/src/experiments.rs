//! The thesis' chapter 7 rerun: tables 5-9 with the thesis' own numbers beside ours, and the
//! before/after pictures of Map0-Map15.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use hex_terrain::{ManipulationConfig, MapConfig, MapSize, PullMode, Shape, Sharpness, Terrain};
use indicatif::{ProgressBar, ProgressStyle};

use crate::{CliResult, render};

/// What to run.
pub struct Options {
    /// Output folder.
    pub out: PathBuf,
    /// Folder of map00.ron ... map15.ron.
    pub maps: PathBuf,
    /// Inner rings for tables 7-9.
    pub rings: u32,
    /// Timing runs (median).
    pub runs: usize,
    /// Largest map timed.
    pub max_hexes: u64,
    /// Picture width.
    pub width: u32,
}

/// Thesis table 5: name, basic ms, manipulation ms, overhead %.
const TABLE_5: [(&str, f32, f32, f32); 20] = [
    ("Map0", 161.0, 19.0, 11.8),
    ("Map1'", 162.0, 19.0, 11.7),
    ("Map1", 170.0, 21.0, 12.4),
    ("Map2'", 156.0, 21.0, 13.5),
    ("Map2", 162.0, 21.0, 13.0),
    ("Map3'", 159.0, 20.0, 12.6),
    ("Map3", 162.0, 20.0, 12.3),
    ("Map4'", 192.0, 30.0, 15.6),
    ("Map4", 200.0, 26.0, 13.0),
    ("Map5", 163.0, 19.0, 11.7),
    ("Map6", 166.0, 22.0, 13.3),
    ("Map7", 172.0, 26.0, 15.1),
    ("Map8", 141.0, 23.0, 16.3),
    ("Map9", 183.0, 25.0, 13.7),
    ("Map10", 167.0, 23.0, 13.8),
    ("Map11", 165.0, 16.0, 9.7),
    ("Map12", 160.0, 21.0, 13.1),
    ("Map13", 2200.0, 622.0, 28.3),
    ("Map14", 167.0, 22.0, 13.2),
    ("Map15", 162.0, 21.0, 13.0),
];

/// Thesis table 6: raw max, raw average, manipulated max, manipulated average, v1, s.
const TABLE_6: [(f32, f32, f32, f32, u32, f32); 20] = [
    (0.55, 0.12, 22.5, 4.92, 2770, 0.58),
    (0.52, 0.1, 19.8, 4.33, 2394, 0.45),
    (0.64, 0.09, 25.2, 4.5, 2900, 0.53),
    (0.54, 0.18, 24.4, 4.64, 2659, 0.64),
    (0.43, 0.09, 21.4, 4.92, 1800, 0.42),
    (0.59, 0.1, 23.5, 4.38, 2357, 0.49),
    (5.25, 0.25, 71.5, 6.55, 2034, 0.74),
    (0.47, 0.1, 19.8, 4.32, 2282, 0.35),
    (0.29, 0.05, 15.5, 3.71, 4168, 0.44),
    (0.52, 0.1, 20.5, 4.6, 2858, 0.54),
    (0.23, 0.05, 13.9, 3.87, 1431, 0.24),
    (6.44, 1.57, 82.9, 12.4, 7516, 4.37),
    (0.31, 0.08, 18.7, 4.52, 2528, 0.46),
    (2.26, 0.5, 30.3, 4.65, 3904, 1.06),
    (3.52, 0.8, 37.2, 5.94, 4709, 1.63),
    (0.5, 0.11, 20.4, 4.3, 3613, 0.63),
    (0.55, 0.1, 22.9, 4.75, 3110, 0.60),
    (0.54, 0.09, 20.9, 4.13, 50565, 0.41),
    (0.55, 0.11, 22.5, 4.92, 2770, 0.57),
    (0.55, 0.11, 22.5, 4.92, 2770, 0.57),
];

/// Thesis tables 7-9: label, x, z, vertices, basic ms, manipulation ms, overhead %.
type TimingRow = (&'static str, u32, u32, u32, f32, f32, f32);

const TABLE_7: [TimingRow; 11] = [
    ("", 2, 2, 153, 57.0, 2.0, 3.51),
    ("", 6, 6, 1225, 59.0, 3.0, 5.08),
    ("", 10, 6, 2025, 63.0, 3.0, 4.76),
    ("", 16, 8, 4257, 70.0, 4.0, 5.71),
    ("", 20, 10, 6601, 77.0, 5.0, 6.49),
    ("", 24, 12, 9457, 88.0, 6.0, 6.82),
    ("", 30, 16, 15665, 105.0, 9.0, 8.57),
    ("", 36, 20, 23409, 130.0, 14.0, 10.77),
    ("", 40, 20, 26001, 139.0, 13.0, 9.35),
    ("", 48, 24, 37345, 173.0, 19.0, 10.98),
    ("", 60, 30, 58201, 228.0, 35.0, 15.35),
];

const TABLE_8: [TimingRow; 8] = [
    ("", 80, 40, 103_201, 370.0, 100.0, 25.79),
    ("", 100, 50, 161_001, 560.0, 140.0, 25.72),
    ("", 200, 100, 642_001, 2010.0, 570.0, 28.51),
    ("", 400, 200, 2_564_001, 7940.0, 2340.0, 29.46),
    ("", 500, 250, 4_005_001, 12240.0, 3560.0, 29.09),
    ("", 600, 300, 5_766_001, 20800.0, 6300.0, 30.30),
    ("", 800, 400, 10_248_001, 33410.0, 10100.0, 30.25),
    ("", 1000, 500, 16_010_001, 50190.0, 15060.0, 30.02),
];

const TABLE_9: [TimingRow; 6] = [
    ("Duel", 44, 26, 37065, 159.0, 32.1, 20.19),
    ("Tiny", 60, 38, 73593, 299.4, 63.5, 21.21),
    ("Small", 74, 46, 109_705, 390.6, 102.4, 26.22),
    ("Standard", 84, 54, 146_041, 515.8, 123.4, 23.92),
    ("Large", 96, 60, 185_329, 633.3, 175.4, 27.70),
    ("Huge", 106, 66, 224_985, 749.9, 202.0, 26.94),
];

fn median_ms(runs: usize, mut f: impl FnMut()) -> f64 {
    let mut v: Vec<f64> = (0..runs)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn raw(config: &MapConfig) -> MapConfig {
    MapConfig { manipulation: ManipulationConfig::raw(), ..config.clone() }
}

fn build(config: MapConfig) -> CliResult<Terrain> {
    Terrain::new(config).map_err(|e| e.to_string())
}

/// Basic (raw) and full generation time of a bounded map, median ms.
fn timings(config: &MapConfig, runs: usize) -> CliResult<(f64, f64, usize, usize)> {
    let full = build(config.clone())?;
    let basic = build(raw(config))?;
    let mesh = full.generate_map().ok_or("experiments need bounded maps")?;
    let (v, t) = (mesh.buffers.vertex_count(), mesh.buffers.triangle_count());
    drop(mesh);
    let basic_ms = median_ms(runs, || drop(std::hint::black_box(basic.generate_map())));
    let full_ms = median_ms(runs, || drop(std::hint::black_box(full.generate_map())));
    Ok((basic_ms, full_ms, v, t))
}

/// Writes every table and picture, and `README.md` in the output folder.
///
/// # Errors
/// A missing map config or an unwritable output folder.
pub fn run(o: &Options) -> CliResult<()> {
    let images = o.out.join("images");
    std::fs::create_dir_all(&images).map_err(|e| format!("{}: {e}", images.display()))?;
    let maps: Vec<MapConfig> =
        (0..16).map(|i| crate::load(&o.maps.join(format!("map{i:02}.map.ron")))).collect::<CliResult<_>>()?;
    // Table 5/6 rows: Map0, then Map1'-Map4' (shape off) before each shaped map, then the rest.
    let mut rows: Vec<(String, MapConfig)> = Vec::new();
    for (i, m) in maps.iter().enumerate() {
        if (1..=4).contains(&i) {
            rows.push((format!("Map{i}'"), MapConfig { shape: Shape::None, ..m.clone() }));
        }
        rows.push((format!("Map{i}"), m.clone()));
    }
    let timing_sizes: Vec<(&str, &TimingRow)> = TABLE_7
        .iter()
        .map(|r| ("7", r))
        .chain(TABLE_8.iter().map(|r| ("8", r)))
        .chain(TABLE_9.iter().map(|r| ("9", r)))
        .filter(|(_, r)| u64::from(r.1) * u64::from(r.2) <= o.max_hexes)
        .collect();
    let steps = (rows.len() * 2 + maps.len() + timing_sizes.len()) as u64;
    let bar = ProgressBar::new(steps).with_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} {msg} [{elapsed}]").unwrap_or(ProgressStyle::default_bar()),
    );
    let mut md = String::new();
    let _ = writeln!(
        md,
        "# The thesis' chapter 7, rerun\n\nGenerated by `hexterrain experiments` on this machine ({} threads); the \
         thesis ran Unity on an Intel i7 laptop. Times are medians of {} runs. \"Manipulation\" is full generation \
         minus basic generation (same noise, same lattice, manipulation off), as the thesis derives it; timing noise \
         can make it slightly negative.\n",
        rayon::current_num_threads(),
        o.runs
    );

    // Table 5.
    let _ = writeln!(
        md,
        "## Table 5: run time of Map0-Map15 ({} inner ring, as the map files)\n\n| map | x | z | hexes | vertices | basic ms | manipulation ms | overhead % | thesis vertices | thesis basic ms | thesis manipulation ms | thesis overhead % |\n|---|---|---|---|---|---|---|---|---|---|---|---|",
        maps[0].terrain.inner_rings
    );
    for ((name, config), thesis) in rows.iter().zip(TABLE_5) {
        bar.set_message(format!("table 5 {name}"));
        let (basic, full, v, _) = timings(config, o.runs)?;
        let (x, z) = config.size.bounds().unwrap_or((0, 0));
        let thesis_v = (8 * x + 1) * (4 * z + 1);
        let _ = writeln!(
            md,
            "| {name} | {x} | {z} | {} | {v} | {basic:.2} | {:.2} | {:.1} | {thesis_v} | {} | {} | {} |",
            x * z,
            full - basic,
            (full - basic) / basic * 100.0,
            thesis.1,
            thesis.2,
            thesis.3
        );
        bar.inc(1);
    }

    // Table 6.
    let _ = writeln!(
        md,
        "\n## Table 6: sharpness (% of max elevation), {} inner rings ({:.0} vertices a hex; the thesis has ~32)\n\nCurvature (eq. 4.1) at each vertex is the largest `|2a2 - a1 - a3|` over the three lattice lines through it. Manipulated vertices are those hex unity or edge/corner correction moved. `s` is eq. 7.3; \"mesh avg\" is the manipulated mesh's average over every vertex, measured directly. Two pulls for inner vertices: **clamp** (default: the least move that puts every inner vertex in its tile type's range) and **thesis** (Algorithm 3 as written: halfway to the threshold); \"outside\" counts inner vertices the thesis pull leaves outside their range (invariant 4).\n\n| map | raw max | raw avg | clamp max | clamp avg | clamp v1 | clamp s | clamp mesh avg | thesis-pull max | thesis-pull avg | thesis-pull s | outside | thesis raw max | thesis raw avg | thesis max | thesis avg | thesis v1 | thesis s |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
        o.rings,
        3.0 * f64::from(o.rings + 1).powi(2)
    );
    for ((name, config), t) in rows.iter().zip(TABLE_6) {
        bar.set_message(format!("table 6 {name}"));
        let mut config = config.clone();
        config.terrain.inner_rings = o.rings;
        let config = &config;
        let max_e = config.terrain.max_elevation;
        let raw_mesh = map_with_diagnostics(&build(raw(config))?).ok_or("bounded")?;
        let clamp_mesh = map_with_diagnostics(&build(config.clone())?).ok_or("bounded")?;
        let mut thesis_config = config.clone();
        thesis_config.manipulation.pull = PullMode::Thesis;
        let thesis_terrain = build(thesis_config)?;
        let thesis_mesh = map_with_diagnostics(&thesis_terrain).ok_or("bounded")?;
        let c = Sharpness::measure(&raw_mesh, &clamp_mesh, max_e);
        let th = Sharpness::measure(&raw_mesh, &thesis_mesh, max_e);
        let outside = outside_range(&thesis_terrain, &thesis_mesh);
        let _ = writeln!(
            md,
            "| {name} | {:.2} | {:.2} | {:.1} | {:.2} | {} | {:.2} | {:.2} | {:.1} | {:.2} | {:.2} | {outside} | {} | {} | {} | {} | {} | {} |",
            c.raw_max,
            c.raw_average,
            c.manipulated_max,
            c.manipulated_average,
            c.manipulated_vertices,
            c.weighted_mesh,
            c.mesh_average,
            th.manipulated_max,
            th.manipulated_average,
            th.weighted_mesh,
            t.0,
            t.1,
            t.2,
            t.3,
            t.4,
            t.5
        );
        bar.inc(1);
    }

    // Sharpness against ring count (the thesis' conclusion: more inner hexagons, less sharpness).
    let _ = writeln!(
        md,
        "\n## Sharpness of Map0 against the number of inner rings\n\n| inner rings | vertices a hex | raw max | raw avg | manipulated max | manipulated avg | v1 | s (eq. 7.3) | mesh avg |\n|---|---|---|---|---|---|---|---|---|"
    );
    for rings in 1..=4 {
        let mut config = maps[0].clone();
        config.terrain.inner_rings = rings;
        let raw_mesh = map_with_diagnostics(&build(raw(&config))?).ok_or("bounded")?;
        let mesh = map_with_diagnostics(&build(config.clone())?).ok_or("bounded")?;
        let s = Sharpness::measure(&raw_mesh, &mesh, config.terrain.max_elevation);
        let _ = writeln!(
            md,
            "| {rings} | {} | {:.2} | {:.3} | {:.1} | {:.2} | {} | {:.3} | {:.3} |",
            3 * (rings + 1).pow(2),
            s.raw_max,
            s.raw_average,
            s.manipulated_max,
            s.manipulated_average,
            s.manipulated_vertices,
            s.weighted_mesh,
            s.mesh_average
        );
    }

    // Tables 7-9.
    for (table, title, unit) in
        [("7", "small maps", "ms"), ("8", "larger maps", "ms"), ("9", "Civilization 6 map sizes", "ms")]
    {
        let _ = writeln!(
            md,
            "\n## Table {table}: run time, {title} ({} inner rings)\n\n| map | x | z | hexes | vertices | v/hex | triangles | basic {unit} | manipulation {unit} | total {unit} | overhead % | thesis vertices | thesis basic {unit} | thesis manipulation {unit} | thesis overhead % | speed-up |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
            o.rings
        );
        for (_, r) in timing_sizes.iter().filter(|(t, _)| *t == table) {
            bar.set_message(format!("table {table} {}x{}", r.1, r.2));
            let mut config = MapConfig { size: MapSize::Bounded { x: r.1, z: r.2 }, ..MapConfig::default() };
            config.terrain.inner_rings = o.rings;
            let (basic, full, v, t) = timings(&config, if r.1 * r.2 > 100_000 { o.runs.min(3) } else { o.runs })?;
            let hexes = r.1 * r.2;
            let _ = writeln!(
                md,
                "| {} | {} | {} | {hexes} | {v} | {:.1} | {t} | {basic:.2} | {:.2} | {full:.2} | {:.1} | {} | {} | {} | {} | {:.0}x |",
                if r.0.is_empty() { format!("{}x{}", r.1, r.2) } else { r.0.to_string() },
                r.1,
                r.2,
                v as f64 / f64::from(hexes),
                full - basic,
                (full - basic) / basic * 100.0,
                r.3,
                r.4,
                r.5,
                r.6,
                f64::from(r.4 + r.5) / full
            );
            bar.inc(1);
        }
    }

    // Pictures.
    let _ = writeln!(
        md,
        "\n## Before and after (raw noise map, manipulated tiled map)\n\n| map | raw | manipulated |\n|---|---|---|"
    );
    for (i, m) in maps.iter().enumerate() {
        bar.set_message(format!("pictures Map{i}"));
        for (suffix, config) in [("raw", raw(m)), ("tiled", m.clone())] {
            let t = build(config)?;
            let mesh = map_with_diagnostics(&t).ok_or("bounded")?;
            let img =
                render::render(&t, &mesh, &render::Options { width: o.width, outlines: false, marks: Vec::new() })?;
            render::save(&img, &images.join(format!("map{i:02}_{suffix}.png")))?;
        }
        let _ = writeln!(md, "| {} | ![](images/map{i:02}_raw.png) | ![](images/map{i:02}_tiled.png) |", m.name);
        bar.inc(1);
    }
    bar.finish_with_message("done");
    let path = o.out.join("README.md");
    std::fs::write(&path, md).map_err(|e| format!("{}: {e}", path.display()))?;
    println!("wrote {}", path.display());
    Ok(())
}

/// Inner vertices (ring 1..n) of in-map tiles outside their tile type's range.
fn outside_range(terrain: &Terrain, mesh: &hex_terrain::ChunkMesh) -> usize {
    let n = terrain.lattice().subdivisions();
    let max_e = terrain.config().terrain.max_elevation.max(f32::MIN_POSITIVE);
    let eps = 1e-5;
    let Some(d) = &mesh.diagnostics else { return 0 };
    d.lattice
        .iter()
        .enumerate()
        .filter(|&(i, &p)| {
            let ring = u32::from(d.rings[i]);
            if ring == 0 || ring >= n {
                return false;
            }
            let tile = terrain.lattice().tiles_at(p).tiles()[0];
            let Some(kind) = terrain.tile_kind(tile) else { return true };
            let (lo, hi) = terrain.thresholds().range(kind);
            let h = mesh.buffers.positions[i][1] / max_e;
            h < lo - eps || h > hi + eps
        })
        .count()
}

/// The whole map with per-vertex diagnostics (what the sharpness and range figures read).
fn map_with_diagnostics(terrain: &Terrain) -> Option<hex_terrain::ChunkMesh> {
    terrain.bounds().map(|rect| terrain.generate(rect, hex_terrain::GenerateOptions::DIAGNOSTICS))
}
