//! A tile's biome on a map without its own terrain ruleset, read the one way a tile is asked:
//! its `TileInfo::terrain`, named by the ruleset (`TerrainRuleset::biome`).
#![allow(dead_code, reason = "each test takes what it needs")]

use hex_terrain::hexx::Hex;
use hex_terrain::{Biome, Terrain, TileInfo};

/// The biome of a tile's info.
pub fn of(t: &Terrain, info: &TileInfo) -> Biome {
    t.ruleset().biome(info.terrain.terrain).expect("a terrain of the default ruleset")
}

/// The biome of a tile; `None` past the world.
pub fn at(t: &Terrain, tile: Hex) -> Option<Biome> {
    t.tile_info(tile).map(|info| of(t, &info))
}
