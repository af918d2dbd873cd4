//! Map types players pick before anything else (Pangaea, Continents, Archipelago...), each
//! with the targets it promises: the config half. The stage that builds them is
//! [`crate::heights::landmass`].

use serde::{Deserialize, Serialize};

/// The map's type (the map config's `map_type`): which arrangement of land and sea the fBm is
/// shaped into, how much water, and how much of the land is mountains. Bounded maps only
/// (wrapping or not); an unbounded world keeps the thesis' shapes. Every type meets its
/// [targets](MapType) or says which it missed in the map's
/// [`MapTypeReport`](crate::MapTypeReport).
///
/// ```
/// use hex_terrain::{MapConfig, MapType, WaterLevel};
///
/// let config = MapConfig::from_ron("(size: Bounded(x: 84, z: 54), wrap: true, map_type: Some((kind: Continents, water: High)))").unwrap();
/// let map_type = config.map_type.unwrap();
/// assert_eq!((map_type.kind, map_type.water), (MapType::Continents, WaterLevel::High));
/// assert_eq!(map_type.sea_share(), 0.71); // Civilization V's Continents, high water
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct MapTypeConfig {
    /// The arrangement of land and sea.
    pub kind: MapType,
    /// How much of the map is sea: the type's share for this level ([`MapType::sea_share`]).
    pub water: WaterLevel,
    /// Mountains' share of the land tiles, in `[0, MAX_MOUNTAIN_SHARE]`: the highest land
    /// becomes mountains until it holds this share.
    pub mountains: f32,
    /// Mountains in ranges along the lines where tectonic plates meet (as Civilization V's
    /// map scripts raise them), rather than on the highest land wherever it lies: the
    /// mountains' share is the same, their shape is chains (see
    /// [`MapStats::mountain_neighbors`](crate::MapStats::mountain_neighbors)), bent, broken by
    /// passes, with at most [`MAX_STRAIGHT_RIDGE`](crate::MAX_STRAIGHT_RIDGE) mountains in a row
    /// and [`MAX_BLOB_SHARE`](crate::MAX_BLOB_SHARE) of them in blobs (two more targets). Off by
    /// default; on in the type presets.
    pub ranges: bool,
}

/// Largest mountain share of a map type's land.
pub const MAX_MOUNTAIN_SHARE: f32 = 0.5;

impl Default for MapTypeConfig {
    fn default() -> Self {
        Self { kind: MapType::Continents, water: WaterLevel::Normal, mountains: 0.08, ranges: false }
    }
}

impl MapTypeConfig {
    /// The sea's share of the map's tiles this config asks for.
    #[must_use]
    pub fn sea_share(&self) -> f64 {
        self.kind.sea_share(self.water)
    }
}

/// How much water a map has, as Civilization's "sea level" setting.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum WaterLevel {
    /// Less sea than usual.
    Low,
    /// The type's usual sea.
    #[default]
    Normal,
    /// More sea than usual.
    High,
}

impl WaterLevel {
    /// Every level, lowest first.
    pub const ALL: [Self; 3] = [Self::Low, Self::Normal, Self::High];
}

/// The arrangement of land and sea of a map type, and the targets it promises. The sea shares
/// (of the map's tiles, low / normal / high water) are Civilization V's, from its map scripts'
/// `water_percent` (`Pangaea.lua`, `Continents.lua`, `Small_Continents.lua`,
/// `Archipelago.lua`, `Fractal.lua` through `MapGenerator.lua`'s `FractalWorld`); Inland Sea's
/// are ours (Civilization V's `Inland_Sea.lua` places its sea in a box of the map's middle
/// rather than by a share). The landmass targets are ours, after what players of those games
/// expect of each type; a continent is a landmass of at least
/// [`CONTINENT_MIN_SHARE`](crate::CONTINENT_MIN_SHARE) of the land and
/// [`CONTINENT_MIN_TILES`](crate::CONTINENT_MIN_TILES) tiles, as [`MapStats`](crate::MapStats)
/// counts them, and the strait between continents is [`MapStats`](crate::MapStats)'
/// narrowest strait (the fewest tiles between two).
///
/// | type | sea % (low / normal / high) | landmass targets |
/// |---|---|---|
/// | Pangaea | 63 / 68 / 73 | the largest landmass holds at least 80 % of the land |
/// | Continents | 63 / 67 / 71 | 2 or 3 continents, the two largest each at least 25 % of the land, at least 2 tiles of sea between continents, each spanning at least 55 % of the rows |
/// | Small Continents | 69 / 75 / 80 | 4 to 8 continents, the largest at most 40 % of the land, at least 2 tiles of sea between continents |
/// | Archipelago | 72 / 78 / 83 | at least 10 landmasses, the largest at most 15 % of the land |
/// | Fractal | 65 / 72 / 78 | the sea share only: the thesis' fBm as it falls |
/// | Inland Sea | 15 / 20 / 25 | the largest sea holds at least 80 % of the sea and touches no edge of the map; the largest landmass (the ring around it) holds at least 90 % of the land |
///
/// Every type also keeps its sea share within [`SEA_SHARE_TOLERANCE`] of the level's and the
/// mountains within one tile of the config's share of the land. Every type but Inland Sea keeps
/// its first and last rows sea, as Civilization V does. Beyond these, what a player judges a map
/// by over many seeds (ranges, poles, lakes, rivers, shapes, deserts) is
/// [`survey_targets`](crate::survey_targets), which the type presets meet.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum MapType {
    /// One great continent and a few islands.
    Pangaea,
    /// Two or three large continents, apart across the sea.
    #[default]
    Continents,
    /// Four to eight smaller continents.
    SmallContinents,
    /// Many islands, none large.
    Archipelago,
    /// The fBm as it falls, with the type's share of sea: land and sea anywhere.
    Fractal,
    /// A sea in the middle of the map, ringed by land.
    InlandSea,
}

/// How far a map type's sea share may lie from its level's (a share of the map's tiles): the
/// generator tries the level's share first, then shares this far either side of it when the
/// landmass targets ask for more or less sea.
pub const SEA_SHARE_TOLERANCE: f64 = 0.02;

impl MapType {
    /// Every type.
    pub const ALL: [Self; 6] =
        [Self::Pangaea, Self::Continents, Self::SmallContinents, Self::Archipelago, Self::Fractal, Self::InlandSea];

    /// The sea's share of the map's tiles at a water level (see the table on [`MapType`]).
    #[must_use]
    pub fn sea_share(self, water: WaterLevel) -> f64 {
        let [low, normal, high] = match self {
            Self::Pangaea => [0.63, 0.68, 0.73],
            Self::Continents => [0.63, 0.67, 0.71],
            Self::SmallContinents => [0.69, 0.75, 0.80],
            Self::Archipelago => [0.72, 0.78, 0.83],
            Self::Fractal => [0.65, 0.72, 0.78],
            Self::InlandSea => [0.15, 0.20, 0.25],
        };
        match water {
            WaterLevel::Low => low,
            WaterLevel::Normal => normal,
            WaterLevel::High => high,
        }
    }

    /// The type's name as players read it ("Small Continents").
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Pangaea => "Pangaea",
            Self::Continents => "Continents",
            Self::SmallContinents => "Small Continents",
            Self::Archipelago => "Archipelago",
            Self::Fractal => "Fractal",
            Self::InlandSea => "Inland Sea",
        }
    }
}
