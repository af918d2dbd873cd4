//! What a game reads of one tile ([`TileInfo`]): its place, type and elevation, what it is
//! under the map's terrain ruleset, and its water. The one answer to "what is this tile"
//! ([`Terrain::tile_info`](crate::Terrain::tile_info)); chunk meshes carry the same for their
//! tiles.

use hexx::Hex;
use serde::{Deserialize, Serialize};

use crate::ruleset::TileTerrain;
use crate::vocab::TileKind;

/// What a game needs to know about one tile.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct TileInfo {
    /// Axial coordinate, map-local (the map's first tile is `Hex::ZERO`).
    pub hex: Hex,
    /// Type by center height.
    pub kind: TileKind,
    /// World height of the tile's center on the manipulated surface.
    pub elevation: f32,
    /// Whether the tile belongs to the map (always true for an unbounded world).
    pub in_map: bool,
    /// What it is under the map's terrain ruleset
    /// ([`Terrain::ruleset`](crate::Terrain::ruleset)): its terrain, landform, feature and
    /// their traits. On a map without its own ruleset the terrain is the tile's biome (the
    /// default ruleset's terrain `i` is [`Biome::ALL`](crate::Biome::ALL)`[i]`; read it with
    /// [`TerrainRuleset::biome`](crate::TerrainRuleset::biome)), a biome set by hand included.
    pub terrain: TileTerrain,
    /// Water a river on the tile carries, 0 without a river.
    pub river_flow: f32,
    /// The lake the tile belongs to, if it is a lake tile.
    pub lake: Option<u32>,
}
