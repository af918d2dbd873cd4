//! Generates a map from a RON config and prints its summary: tile counts per type, mesh size,
//! sharpness raw vs manipulated, generation time.
//!
//! ```text
//! cargo run --release -p hex_terrain --example summary -- assets/maps/thesis/map00.ron
//! ```

use std::time::Instant;

use hex_terrain::{ManipulationConfig, MapConfig, Sharpness, Terrain, TileKind};

fn main() {
    let path = std::env::args().nth(1).unwrap_or_else(|| "assets/maps/thesis/map00.ron".into());
    let config = match MapConfig::load(&path) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("error: {path}: {e}");
            std::process::exit(1);
        }
    };
    let terrain = match Terrain::new(config.clone()) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("error: {path}: {e}");
            std::process::exit(1);
        }
    };
    let start = Instant::now();
    let Some(map) = terrain.generate_map() else {
        eprintln!("error: {path}: an unbounded world has no whole-map summary; generate chunks instead");
        std::process::exit(1);
    };
    let elapsed = start.elapsed();
    let raw_config = MapConfig { manipulation: ManipulationConfig::raw(), ..config.clone() };
    let raw = Terrain::new(raw_config).map(|t| t.generate_map()).ok().flatten();
    println!("{} ({path})", config.name);
    for kind in TileKind::ALL {
        let count = map.tiles.iter().filter(|t| t.kind == kind).count();
        println!("  {:<9} {count:>7} tiles", kind.name());
    }
    println!(
        "  mesh      {} vertices, {} triangles, generated in {:.2} ms",
        map.buffers.vertex_count(),
        map.buffers.triangle_count(),
        elapsed.as_secs_f64() * 1e3
    );
    if let Some(raw) = raw {
        let s = Sharpness::measure(&raw, &map, config.terrain.max_elevation);
        println!(
            "  sharpness raw max {:.2}% avg {:.3}%; manipulated ({} vertices) max {:.2}% avg {:.2}%; mesh (eq. 7.3) {:.3}%",
            s.raw_max, s.raw_average, s.manipulated_vertices, s.manipulated_max, s.manipulated_average, s.weighted_mesh
        );
    }
}
