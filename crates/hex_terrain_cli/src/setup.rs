//! `hexterrain setup`: a game set up on a map or a globe (its starts, resources and wonders,
//! the fairness report), and optionally a picture of it (a globe's equirectangular).

use std::path::Path;
use std::time::Instant;

use hex_terrain::{GlobeTerrain, MapConfig, MapSize, ResourceClass, Terrain};

use crate::{CliResult, load, render, whole_map};

/// Sets up a game for `players` (the map's setup, else the default one) and prints its report;
/// with `output`, renders the map with the starts, resources and wonders marked.
pub fn setup(path: &Path, players: Option<u32>, output: Option<&Path>, width: u32) -> CliResult<()> {
    let mut config = load(path)?;
    let mut setup = config.setup.take().unwrap_or_default();
    if let Some(n) = players {
        setup.players = n;
    }
    config.setup = Some(setup);
    if let MapSize::Globe { .. } = config.size {
        return globe_setup(path, config, output, width);
    }
    let start = Instant::now();
    let t = Terrain::new(config).map_err(|e| format!("{}: {e}", path.display()))?;
    let elapsed = start.elapsed();
    let setup = t.setup().ok_or("the map has no setup")?;
    println!("{} ({}): {} players", t.config().name, path.display(), setup.starts().len());
    print!("{}", setup.report());
    println!("map and setup compiled in {:.1} ms", elapsed.as_secs_f64() * 1e3);
    let Some(output) = output else { return Ok(()) };
    let mesh = whole_map(&t)?;
    let mut marks = Vec::new();
    let center = |tile| t.tile_center(tile).map(|c| [c[0], c[2]]);
    for r in setup.resources() {
        marks.extend(center(r.tile).map(|at| render::Mark { at, radius: 0.4, color: class_color(r.class) }));
    }
    for w in setup.wonders() {
        marks.extend(center(w.tile).map(|at| render::Mark { at, radius: 0.7, color: [250, 200, 40] }));
    }
    for &s in setup.starts() {
        marks.extend(center(s).map(|at| render::Mark { at, radius: 1.1, color: [250, 250, 250] }));
    }
    let img = render::render(&t, &mesh, &render::Options { width, outlines: false, marks })?;
    render::save(&img, output)
}

/// A resource's mark color by its class.
fn class_color(class: ResourceClass) -> [u8; 3] {
    match class {
        ResourceClass::Bonus => [90, 220, 90],
        ResourceClass::Strategic => [230, 70, 60],
        ResourceClass::Luxury => [190, 110, 240],
    }
}

/// The globe's setup: its report, and with `output` its equirectangular picture with the starts,
/// resources and wonders marked.
fn globe_setup(path: &Path, config: MapConfig, output: Option<&Path>, width: u32) -> CliResult<()> {
    let start = Instant::now();
    let globe = GlobeTerrain::new(config).map_err(|e| format!("{}: {e}", path.display()))?;
    let elapsed = start.elapsed();
    let setup = globe.setup().ok_or("the globe has no setup")?;
    println!("{} ({}): {} players on a globe", globe.config().name, path.display(), setup.starts().len());
    print!("{}", setup.report());
    println!(
        "globe and setup compiled in {:.1} ms (the table's tile column: longitude, latitude)",
        elapsed.as_secs_f64() * 1e3
    );
    let Some(output) = output else { return Ok(()) };
    let mut img = crate::globe::render(&globe, crate::globe::View::Equirectangular, width, false);
    let (w, h) = (img.width() as f32, img.height() as f32);
    // Pixels a hex radius at the equator (the radius is in hex radii).
    let hex = w / (2.0 * std::f32::consts::PI * globe.radius() as f32);
    let mut mark = |tile_id, radius: f32, color| {
        let info = globe.tile_info(tile_id).expect("a tile of the globe");
        let at = [((info.longitude + 180.0) / 360.0) as f32 * w, ((90.0 - info.latitude) / 180.0) as f32 * h];
        render::disc(&mut img, at, (radius * hex).max(2.0), color);
    };
    for r in setup.resources() {
        mark(r.tile, 0.4, class_color(r.class));
    }
    for w in setup.wonders() {
        mark(w.tile, 0.7, [250, 200, 40]);
    }
    for &s in setup.starts() {
        mark(s, 1.1, [250, 250, 250]);
    }
    render::save(&img, output)
}
