//! `hexterrain stats` on a flat map: its tiles by type and biome (terrains and features under its
//! own ruleset), water, game setup, `MapStats`, map type report, edits, mesh, generation time and
//! sharpness; a globe's go to `globe_stats`.

use std::path::Path;
use std::time::Instant;

use hex_terrain::{Biome, MapStats, RiverModel, Sharpness, TileKind};

use crate::{CliResult, globe_stats, load, terrain, terrains, whole_map};

/// Prints a map's statistics (under `ruleset` when given).
pub fn stats(path: &Path, ruleset: Option<&Path>) -> CliResult<()> {
    let mut config = load(path)?;
    if config.size.globe().is_some() {
        if ruleset.is_some() {
            return Err("--ruleset: terrain rulesets are not on globes yet".into());
        }
        return globe_stats::stats(path, config);
    }
    if let Some(ruleset) = ruleset {
        config.ruleset = Some(ruleset.display().to_string());
    }
    let t = terrain(config.clone(), false)?;
    let start = Instant::now();
    let mesh = whole_map(&t)?;
    let elapsed = start.elapsed();
    let raw = whole_map(&terrain(config.clone(), true)?)?;
    let s = Sharpness::measure(&raw, &mesh, config.terrain.max_elevation);
    println!("{} ({})", config.name, path.display());
    println!("tiles:");
    for kind in TileKind::ALL {
        let count = mesh.tiles.iter().filter(|t| t.kind == kind).count();
        println!("  {:<9} {count}", kind.name());
    }
    println!("  total     {}", mesh.tiles.len());
    // A map of biomes (its own ruleset's terrains come from `MapStats` below).
    if (t.config().climate.enabled || t.hydrology().is_some()) && !t.has_own_ruleset() {
        println!("biomes:");
        for biome in Biome::ALL {
            let count = mesh.tiles.iter().filter(|i| t.ruleset().biome(i.terrain.terrain) == Some(biome)).count();
            if count > 0 {
                println!("  {:<11} {count}", biome.name());
            }
        }
    }
    let measured = MapStats::measure(&t);
    if let Some(stats) = measured.as_ref().filter(|_| t.has_own_ruleset()) {
        terrains::print(&t, stats);
    }
    let edge_rivers = measured.as_ref().filter(|_| t.config().rivers.model == RiverModel::Edges);
    if let (Some(h), Some(stats)) = (t.hydrology(), edge_rivers) {
        let r = stats.rivers;
        println!(
            "water: rivers on {} tile edges ({} systems, {} tiles on a river, the longest {} edges); {} lakes ({} tiles)",
            r.edges,
            r.systems,
            r.tiles,
            r.longest,
            h.lake_count(),
            mesh.tiles.iter().filter(|t| t.lake.is_some()).count()
        );
    } else if let Some(h) = t.hydrology() {
        let rivers = t.rivers();
        let sources = rivers.iter().filter(|r| r.upstream.is_empty()).count();
        let mouths = rivers.iter().filter(|r| r.downstream.is_none_or(|d| t.river(d).is_none())).count();
        println!(
            "water: {} river tiles, {sources} sources, {mouths} mouths; {} lakes ({} tiles)",
            rivers.len(),
            h.lake_count(),
            mesh.tiles.iter().filter(|t| t.lake.is_some()).count()
        );
    }
    match t.setup() {
        Some(setup) => {
            let r = setup.report();
            println!(
                "setup: {} players, spread {:.1} % (bound {:.1} %), {} resources, {} wonders",
                setup.starts().len(),
                r.spread * 100.0,
                r.bound * 100.0,
                r.resources,
                r.wonders
            );
        }
        None => println!("setup: none (`hexterrain setup {}` places a game with the default setup)", path.display()),
    }
    // `stats` takes bounded maps only (`whole_map` above), which always have statistics.
    if let Some(stats) = &measured {
        println!("{stats}");
    }
    if let Some(report) = t.map_type() {
        println!("map type {report}");
    }
    match config.edits.len() {
        0 => println!("edits: none (the generated map)"),
        n => println!("edits: {n} tiles edited (the map file's `edits` section, applied over the seed)"),
    }
    println!("mesh: {} vertices, {} triangles", mesh.buffers.vertex_count(), mesh.buffers.triangle_count());
    println!("generation: {:.2} ms", elapsed.as_secs_f64() * 1e3);
    println!("sharpness (% of max elevation):");
    println!("  raw map          max {:>7.3}  average {:>7.3}", s.raw_max, s.raw_average);
    println!(
        "  manipulated      max {:>7.3}  average {:>7.3}  ({} manipulated vertices)",
        s.manipulated_max, s.manipulated_average, s.manipulated_vertices
    );
    println!("  mesh (eq. 7.3)   {:.3}   measured directly {:.3}", s.weighted_mesh, s.mesh_average);
    Ok(())
}
