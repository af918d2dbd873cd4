//! `hexterrain setup`: a game set up on a map (its starts, resources and wonders, the fairness
//! report), and optionally a picture of it.

use std::path::Path;
use std::time::Instant;

use hex_terrain::Terrain;

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
        let color = match r.class {
            hex_terrain::ResourceClass::Bonus => [90, 220, 90],
            hex_terrain::ResourceClass::Strategic => [230, 70, 60],
            hex_terrain::ResourceClass::Luxury => [190, 110, 240],
        };
        marks.extend(center(r.tile).map(|at| render::Mark { at, radius: 0.4, color }));
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
