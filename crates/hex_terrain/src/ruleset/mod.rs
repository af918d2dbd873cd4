//! A game's own terrain ([`TerrainRuleset`]): base terrains and features, each with an id the
//! game names, where it occurs (landform, temperature, moisture, elevation, latitude, next to
//! water or a river, with a priority where rules overlap), what it costs to enter, whether it
//! stands tall for sight, what it yields and how it looks. A RON file (`*.terrain.ron`), as
//! Unciv's mods define `Terrains.json` and Freeciv its `terrain.ruleset`.
//!
//! | module | what it holds |
//! |---|---|
//! | `mod.rs` | the file's types |
//! | `check.rs` | validation: every error names the entry, the field, the value and the allowed range |
//! | `select.rs` | the compiled ruleset: a tile's terrain and feature from its [`TileFacts`] |
//! | `biomes.rs` | the default ruleset: the 13 biomes of a climate's biome table, as rules |
//!
//! A tile's terrain is the terrain of the highest-priority rule that covers its facts (two
//! rules of different terrains that could both cover a tile never share a priority: the
//! ruleset is refused), or, when none covers it, its landform's
//! [`fallback`](TerrainRuleset::fallback); a map without a climate has only fallbacks. A
//! feature sits on a tile whose terrain it lists in [`FeatureDef::on`], where one of its rules
//! covers the tile and its patches ([`FeatureDef::density`], [`FeatureDef::patch`]) reach;
//! features are tried highest priority first.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::config::Yields;
use crate::error::LoadError;
use crate::vocab::PropKind;

mod biomes;
mod check;
mod select;
#[cfg(test)]
mod tests;

pub(crate) use biomes::biome_texture;
pub use check::{MAX_FEATURES, MAX_PATCH, MAX_RULES, MAX_TERRAINS};
pub(crate) use select::TileTerrains;
pub use select::{FeatureId, FeaturePatches, PATCH_SPREAD, TerrainId, TileFacts, TileTerrain};

/// Where a tile lies, from its height and its water: the first thing a terrain rule asks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum Landform {
    /// Sea away from land.
    OpenSea,
    /// Sea next to land.
    Shore,
    /// A lake tile.
    Lake,
    /// Land below the climate's hills line ([`ClimateConfig::hills`](crate::ClimateConfig::hills)).
    Flat,
    /// Land above the hills line (only on a map with a climate).
    Hills,
    /// A mountain tile.
    Mountain,
}

impl Landform {
    /// Every landform, lowest first.
    pub const ALL: [Self; 6] = [Self::OpenSea, Self::Shore, Self::Lake, Self::Flat, Self::Hills, Self::Mountain];

    /// Whether it is water (open sea, shore, lake).
    #[must_use]
    pub fn is_water(self) -> bool {
        matches!(self, Self::OpenSea | Self::Shore | Self::Lake)
    }
}

/// A game's terrains and features: what the climate stage gives each tile.
///
/// ```
/// use hex_terrain::{Landform, TerrainRuleset, TileFacts};
///
/// let ruleset = TerrainRuleset::from_ron(include_str!("../../../bevy_hex_terrain/assets/rulesets/civ5.terrain.ron")).unwrap();
/// let hot_wet_flat = TileFacts { temperature: 0.9, moisture: 0.9, ..TileFacts::new(Landform::Flat) };
/// assert_eq!(ruleset.terrain(ruleset.terrain_for(&hot_wet_flat)).id, "grassland");
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(deny_unknown_fields)]
pub struct TerrainRuleset {
    /// A human readable name, shown by tools.
    #[serde(default)]
    pub name: String,
    /// The terrain of a tile no rule covers, by its landform (every landform needs one); on a
    /// map without a climate, every tile's terrain.
    pub fallback: BTreeMap<Landform, String>,
    /// The base terrains, at most [`MAX_TERRAINS`]; a [`TerrainId`] is an index into them.
    pub terrains: Vec<TerrainDef>,
    /// The features, at most [`MAX_FEATURES`]; a [`FeatureId`] is an index into them.
    #[serde(default)]
    pub features: Vec<FeatureDef>,
}

/// A base terrain (grassland, tundra, volcanic waste...).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(deny_unknown_fields)]
pub struct TerrainDef {
    /// What the game calls it: lower-case letters, digits and `_`, unique among the terrains.
    pub id: String,
    /// Its name, as a player reads it.
    pub name: String,
    /// Where it occurs; none: only where it is a fallback (or painted).
    #[serde(default)]
    pub occurs: Vec<Occurs>,
    /// What entering it costs, whether it stands tall, what it yields.
    #[serde(default)]
    pub traits: Traits,
    /// Its traits on hills (Civilization's "grassland hills": 2 to enter, tall, production);
    /// `None`: the same as on flat land.
    #[serde(default)]
    pub hills: Option<Traits>,
    /// How it looks.
    #[serde(default)]
    pub look: Look,
}

/// A feature on top of a terrain (forest, jungle, marsh, floodplains, oasis, ice, reef...).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(deny_unknown_fields)]
pub struct FeatureDef {
    /// What the game calls it: lower-case letters, digits and `_`, unique among the features.
    pub id: String,
    /// Its name, as a player reads it.
    pub name: String,
    /// The terrains it may sit on (their ids).
    pub on: Vec<String>,
    /// Where it occurs on them (at least one rule).
    pub occurs: Vec<Occurs>,
    /// About the share of the tiles it may occupy that it covers, in `(0, 1]`: its patches'
    /// noise lies under the matching threshold (1: every one).
    #[serde(default = "one")]
    pub density: f32,
    /// The size of its patches in tiles, in `[1, MAX_PATCH]`: the scale of the noise whose low
    /// places it fills, so it forms patches rather than salt and pepper.
    #[serde(default = "three")]
    pub patch: f32,
    /// Its own traits.
    #[serde(default)]
    pub traits: Traits,
    /// Whether its traits replace the terrain's (Civilization's forest: 2 to enter and 1 food,
    /// 1 production whatever it grows on) or add to them (a costlier entry, extra yields, the
    /// tall of either).
    #[serde(default)]
    pub replace: bool,
    /// How it looks, over its terrain.
    #[serde(default)]
    pub look: Look,
}

fn one() -> f32 {
    1.0
}

fn three() -> f32 {
    3.0
}

/// Where a terrain or a feature occurs: every range half-open `[lo, hi)` with 1 itself inside a
/// range ending at 1, every condition met.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct Occurs {
    /// The landforms it occurs on (at least one).
    pub landform: Vec<Landform>,
    /// Temperature, 0 coldest, 1 hottest.
    pub temperature: (f32, f32),
    /// Moisture, 0 driest, 1 wettest.
    pub moisture: (f32, f32),
    /// Height within its landform's band (0 its bottom, 1 its top).
    pub elevation: (f32, f32),
    /// Latitude, 0 at the equator, 1 at a pole (on an unbounded map, 0.5 everywhere).
    pub latitude: (f32, f32),
    /// `Some(true)`: only next to sea or a lake; `Some(false)`: only away from them.
    pub near_water: Option<bool>,
    /// `Some(true)`: only on a river (through the tile or on an edge); `Some(false)`: only off.
    pub near_river: Option<bool>,
    /// Where rules of different terrains (or features) overlap, the higher wins; such rules
    /// with equal priorities are refused.
    pub priority: u8,
}

impl Default for Occurs {
    fn default() -> Self {
        Self {
            landform: Vec::new(),
            temperature: (0.0, 1.0),
            moisture: (0.0, 1.0),
            elevation: (0.0, 1.0),
            latitude: (0.0, 1.0),
            near_water: None,
            near_river: None,
            priority: 0,
        }
    }
}

/// What a terrain (or a feature) means to the rules of a game.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct Traits {
    /// The cost of entering it, `0..=MAX_MOVE_COST`, 0: impassable.
    pub movement: u32,
    /// Whether it stands tall: it blocks the view of viewers on lower tiles and lifts a viewer
    /// on it ([`SightConfig`](crate::SightConfig)'s rule).
    pub tall: bool,
    /// What a city working it gets, each in `[0, MAX_YIELD]`.
    pub yields: Yields,
}

impl Default for Traits {
    fn default() -> Self {
        Self { movement: 1, tall: false, yields: Yields::new(0.0, 0.0, 0.0) }
    }
}

/// How a terrain or a feature looks.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct Look {
    /// Its base color (sRGB), in the meshes' vertex colors and the CLI's renders.
    pub color: [u8; 3],
    /// The layer of the material's texture array it is drawn with.
    pub texture: u8,
    /// Its color on the minimap (sRGB); `None`: its base color.
    pub minimap: Option<[u8; 3]>,
    /// What grows or lies on it.
    pub props: Option<PropGrowth>,
}

impl Default for Look {
    fn default() -> Self {
        Self { color: [128, 128, 128], texture: 0, minimap: None, props: None }
    }
}

/// The props on a tile of a terrain or a feature: how many of which kind, how large.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(deny_unknown_fields)]
pub struct PropGrowth {
    /// The kind (a tree, a rock, reeds).
    pub kind: PropKind,
    /// How many on a tile, `1..=MAX_PROPS_ON_TILE`.
    pub count: u8,
    /// Their size, in hex radii, in `(0, 1]`.
    pub size: f32,
    /// The share of the tiles that have them, in `(0, 1]`.
    pub chance: f32,
}

impl TerrainRuleset {
    /// Parses and validates a ruleset from RON text.
    ///
    /// # Errors
    /// [`LoadError::Ron`] with the line and column of malformed text, [`LoadError::Invalid`]
    /// naming the entry and the field of a value out of range ([`TerrainRuleset::validate`]).
    pub fn from_ron(text: &str) -> Result<Self, LoadError> {
        let ruleset: Self = ron::de::from_str(text)?;
        ruleset.validate()?;
        Ok(ruleset)
    }

    /// Reads, parses and validates a ruleset file.
    ///
    /// # Errors
    /// As [`TerrainRuleset::from_ron`], plus [`LoadError::Io`] when the file cannot be read.
    pub fn load(path: impl AsRef<std::path::Path>) -> Result<Self, LoadError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path)
            .map_err(|source| LoadError::Io { path: path.display().to_string(), source })?;
        Self::from_ron(&text)
    }

    /// Serialises to pretty RON.
    #[must_use]
    pub fn to_ron(&self) -> String {
        ron::ser::to_string_pretty(self, ron::ser::PrettyConfig::default()).expect("a ruleset serialises")
    }

    /// A terrain by its index.
    ///
    /// # Panics
    /// When `id` is not a terrain of this ruleset.
    #[must_use]
    pub fn terrain(&self, id: TerrainId) -> &TerrainDef {
        &self.terrains[usize::from(id.0)]
    }

    /// A feature by its index.
    ///
    /// # Panics
    /// When `id` is not a feature of this ruleset.
    #[must_use]
    pub fn feature(&self, id: FeatureId) -> &FeatureDef {
        &self.features[usize::from(id.0)]
    }

    /// The biome a terrain is named after ([`Biome::from_id`](crate::Biome::from_id) of its
    /// id): every terrain of the default ruleset ([`TerrainRuleset::biomes`]), `None` for a
    /// terrain of another ruleset whose id names no biome.
    #[must_use]
    pub fn biome(&self, id: TerrainId) -> Option<crate::vocab::Biome> {
        self.terrains.get(usize::from(id.0)).and_then(|t| crate::vocab::Biome::from_id(&t.id))
    }

    /// The terrain with this id (what the game calls it).
    #[must_use]
    pub fn terrain_id(&self, id: &str) -> Option<TerrainId> {
        self.terrains.iter().position(|t| t.id == id).map(|i| TerrainId(i as u8))
    }

    /// The feature with this id (what the game calls it).
    #[must_use]
    pub fn feature_id(&self, id: &str) -> Option<FeatureId> {
        self.features.iter().position(|f| f.id == id).map(|i| FeatureId(i as u8))
    }
}

/// Most props of one kind a ruleset puts on a tile.
pub const MAX_PROPS_ON_TILE: u8 = 12;
