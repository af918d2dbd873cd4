//! The vocabulary every stage speaks: what a tile is ([`TileKind`], [`Biome`]) and what stands
//! on it ([`PropKind`]). A leaf: it imports nothing
//! of the crate, so every stage can use it without depending on another stage.

use serde::{Deserialize, Serialize};

/// The type of a tile, decided by the height of its center.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[repr(u8)]
pub enum TileKind {
    /// Center below the sea threshold.
    Sea = 0,
    /// Center between the thresholds.
    Land = 1,
    /// Center at or above the mountain threshold.
    Mountain = 2,
}

impl TileKind {
    /// All kinds, lowest first.
    pub const ALL: [Self; 3] = [Self::Sea, Self::Land, Self::Mountain];

    /// Lower-case name.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Sea => "sea",
            Self::Land => "land",
            Self::Mountain => "mountain",
        }
    }
}

/// A tile's biome: the relief kind refined by climate and water.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[repr(u8)]
pub enum Biome {
    /// Deep sea, away from land.
    Ocean = 0,
    /// Shallow sea next to land.
    Coast,
    /// Water above sea level, filling a depression.
    Lake,
    /// Hot and dry land.
    Desert,
    /// Dry or temperate open land.
    Plains,
    /// Temperate, moist open land.
    Grassland,
    /// Temperate, wet land.
    Forest,
    /// Hot, wet land.
    Rainforest,
    /// Cold land.
    Tundra,
    /// The coldest land.
    Snow,
    /// High land (the upper part of the land range).
    Hills,
    /// Bare mountains.
    Rock,
    /// Cold mountains.
    SnowPeak,
}

impl Biome {
    /// Every biome, in discriminant order.
    pub const ALL: [Self; 13] = [
        Self::Ocean,
        Self::Coast,
        Self::Lake,
        Self::Desert,
        Self::Plains,
        Self::Grassland,
        Self::Forest,
        Self::Rainforest,
        Self::Tundra,
        Self::Snow,
        Self::Hills,
        Self::Rock,
        Self::SnowPeak,
    ];

    /// Lower-case name.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Ocean => "ocean",
            Self::Coast => "coast",
            Self::Lake => "lake",
            Self::Desert => "desert",
            Self::Plains => "plains",
            Self::Grassland => "grassland",
            Self::Forest => "forest",
            Self::Rainforest => "rainforest",
            Self::Tundra => "tundra",
            Self::Snow => "snow",
            Self::Hills => "hills",
            Self::Rock => "rock",
            Self::SnowPeak => "snow peak",
        }
    }

    /// Its color in the meshes' vertex colors and the CLI's renders (sRGB).
    #[must_use]
    pub fn color(self) -> [u8; 3] {
        match self {
            Self::Ocean => [30, 66, 128],
            Self::Coast => [62, 136, 182],
            Self::Lake => [52, 118, 176],
            Self::Desert => [224, 202, 142],
            Self::Plains => [184, 182, 98],
            Self::Grassland => [104, 164, 66],
            Self::Forest => [42, 110, 50],
            Self::Rainforest => [22, 88, 42],
            Self::Tundra => [150, 148, 122],
            Self::Snow => [238, 242, 246],
            Self::Hills => [138, 142, 82],
            Self::Rock => [122, 112, 104],
            Self::SnowPeak => [228, 234, 242],
        }
    }

    /// Its terrain's id in the default terrain ruleset
    /// ([`TerrainRuleset::biomes`](crate::TerrainRuleset::biomes)): its name, `_` for a space
    /// (`"snow_peak"`).
    #[must_use]
    pub fn id(self) -> &'static str {
        match self {
            Self::SnowPeak => "snow_peak",
            other => other.name(),
        }
    }

    /// The biome whose id ([`Biome::id`]) is `id`: what a terrain of that id is named in the
    /// default ruleset, whatever ruleset it comes from.
    #[must_use]
    pub fn from_id(id: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|b| b.id() == id)
    }

    /// Whether it is water (ocean, coast, lake).
    #[must_use]
    pub fn is_water(self) -> bool {
        matches!(self, Self::Ocean | Self::Coast | Self::Lake)
    }

    /// Whether the biome is bare rock or a snow peak (the mountain biomes).
    #[must_use]
    pub fn is_rocky(self) -> bool {
        matches!(self, Self::Rock | Self::SnowPeak)
    }

    /// The biome a tile of `kind` has when the map has no climate.
    #[must_use]
    pub fn of_kind(kind: TileKind) -> Self {
        match kind {
            TileKind::Sea => Self::Ocean,
            TileKind::Land => Self::Grassland,
            TileKind::Mountain => Self::Rock,
        }
    }
}

/// What a prop is: which family of meshes draws it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum PropKind {
    /// A round-crowned tree.
    Broadleaf,
    /// A conifer.
    Pine,
    /// A boulder.
    Rock,
    /// A clump of reeds.
    Reed,
    /// A game setup's resource marker: its variant is the resource's class (0 bonus, 1
    /// strategic, 2 luxury).
    Resource,
    /// A game setup's natural wonder marker.
    Wonder,
}

impl PropKind {
    /// Every kind, in order.
    pub const ALL: [Self; 6] = [Self::Broadleaf, Self::Pine, Self::Rock, Self::Reed, Self::Resource, Self::Wonder];
}

/// How many mesh variants each prop kind has; a prop's [`variant`](crate::props::Prop::variant) is below it.
pub const PROP_VARIANTS: u8 = 3;

/// Most bytes in the id of a terrain or a feature of a ruleset.
pub const MAX_ID_LEN: usize = 31;

/// The id of a terrain or a feature of a terrain ruleset, as an edit names it (`"grassland"`):
/// at most [`MAX_ID_LEN`] bytes held inline, so edits stay `Copy`; written as a string.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct RuleId {
    len: u8,
    bytes: [u8; MAX_ID_LEN],
}

impl RuleId {
    /// The id `id`, or `None` when it is longer than [`MAX_ID_LEN`] bytes.
    #[must_use]
    pub fn new(id: &str) -> Option<Self> {
        let len = id.len();
        (len <= MAX_ID_LEN).then(|| {
            let mut bytes = [0; MAX_ID_LEN];
            bytes[..len].copy_from_slice(id.as_bytes());
            Self { len: len as u8, bytes }
        })
    }

    /// The id as a string.
    #[must_use]
    pub fn as_str(&self) -> &str {
        std::str::from_utf8(&self.bytes[..usize::from(self.len)]).expect("made from a str")
    }
}

impl std::fmt::Debug for RuleId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:?}", self.as_str())
    }
}

impl std::fmt::Display for RuleId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl Serialize for RuleId {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.as_str())
    }
}

impl<'de> Deserialize<'de> for RuleId {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let id = String::deserialize(deserializer)?;
        Self::new(&id)
            .ok_or_else(|| serde::de::Error::custom(format!("the id {id:?} is longer than {MAX_ID_LEN} bytes")))
    }
}
