//! `hexterrain stats` on a map with its own terrain ruleset (or `--ruleset FILE`): the tiles of
//! each terrain (on hills among them) and feature, as `MapStats` counts them.

use hex_terrain::{MapStats, Terrain};

/// Prints each terrain's tiles (and how many lie on hills) and each feature's.
pub fn print(t: &Terrain, stats: &MapStats) {
    let ruleset = t.ruleset();
    println!("terrains ({}):", ruleset.name);
    for &(id, n, on_hills) in &stats.terrains {
        let hills = if on_hills > 0 { format!(" ({on_hills} on hills)") } else { String::new() };
        println!("  {:<20} {n}{hills}", ruleset.terrain(id).id);
    }
    if !stats.features.is_empty() {
        println!("features:");
        for &(id, n) in &stats.features {
            println!("  {:<20} {n}", ruleset.feature(id).id);
        }
    }
}
