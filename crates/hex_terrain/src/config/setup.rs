//! Game setup settings: how many players, what a tile yields, where a start may stand, the
//! resources and natural wonders, and how fair the starts must be. Off by default (the map's
//! `setup` is `None`), so a map without it generates exactly what it did.

mod validate;

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::chunk::TileRect;
use crate::vocab::{Biome, TileKind};

/// Most players a setup places.
pub const MAX_PLAYERS: u32 = 32;
/// Most rings counted around a start.
pub const MAX_SETUP_RINGS: u32 = 5;
/// Largest minimum distance between starts, spacing of resources or wonders, in tiles.
pub const MAX_SETUP_DISTANCE: u32 = 64;
/// Most resources of one kind each player is guaranteed near its start.
pub const MAX_PER_PLAYER: u32 = 8;
/// Most resource and wonder rules.
pub const MAX_SETUP_RULES: usize = 64;
/// Largest yield (or movement cost) of one tile.
pub const MAX_YIELD: f32 = 100.0;
/// Most tiles the setup surveys (the whole bounded map, or the `area` of an unbounded one).
pub const MAX_SETUP_TILES: u64 = 1 << 18;

/// The setup of a game on the map: players' starts, resources and natural wonders, placed as a
/// pure function of the config and the seed, with a fairness report.
///
/// ```
/// use hex_terrain::{MapConfig, Terrain};
///
/// let config = MapConfig::from_ron(
///     "(size: Bounded(x: 48, z: 30), climate: (enabled: true), setup: Some((players: 4, min_distance: 8)))",
/// )
/// .unwrap();
/// let terrain = Terrain::new(config).unwrap();
/// let setup = terrain.setup().unwrap();
/// assert_eq!(setup.starts().len(), 4);
/// for (i, &a) in setup.starts().iter().enumerate() {
///     for &b in &setup.starts()[i + 1..] {
///         assert!(terrain.distance(a, b).unwrap() >= 8);
///     }
/// }
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct SetupConfig {
    /// Number of players, `1..=32`.
    pub players: u32,
    /// Rings of tiles around a start that count for its value and its guaranteed resources
    /// (a city's working radius), `1..=5`.
    pub rings: u32,
    /// Fewest tiles between two starts (hex distance, across the seam on a wrapping map).
    /// Starts are found whenever the map has that many tiles a start may stand on this far
    /// apart, by an exact search if the spread by regions falls short; a map where the search
    /// would take more than [`MAX_START_SEARCH_CHECKS`](crate::MAX_START_SEARCH_CHECKS) distance
    /// checks is refused with the largest distance found, saying the search stopped.
    pub min_distance: u32,
    /// Where a start may stand, besides on land that is neither mountain nor lake.
    pub start_on: StartOn,
    /// What each tile yields.
    pub yields: YieldTable,
    /// How yields and reachable land add up to a tile's and a start's value.
    pub value: ValueWeights,
    /// The largest spread of the starts' values allowed, `max / min - 1`, in `[0, 10]`
    /// (0.1: the best start is worth at most 10 % more than the worst).
    pub fairness: f32,
    /// Whether the weakest starts get bonus resources near them until the spread is within
    /// `fairness` (or there is no room left).
    pub normalize: bool,
    /// Resources, placed in this order.
    pub resources: Vec<ResourceRule>,
    /// Natural wonders.
    pub wonders: WonderConfig,
    /// The tiles the setup places on (offset coordinates, map-local): the whole map when
    /// `None`; required on an unbounded map.
    pub area: Option<TileRect>,
}

impl Default for SetupConfig {
    fn default() -> Self {
        Self {
            players: 2,
            rings: 3,
            min_distance: 6,
            start_on: StartOn::Land,
            yields: YieldTable::default(),
            value: ValueWeights::default(),
            fairness: 0.1,
            normalize: true,
            resources: ResourceRule::defaults(),
            wonders: WonderConfig::default(),
            area: None,
        }
    }
}

/// Where a start may stand: always on a land tile (not mountain, not lake); these ask more.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum StartOn {
    /// Any land tile.
    #[default]
    Land,
    /// A land tile next to the sea.
    Coast,
    /// A land tile a river runs through.
    River,
    /// A land tile next to the sea or with a river.
    CoastOrRiver,
}

/// What a tile gives a player working it.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct Yields {
    /// Food.
    pub food: f32,
    /// Production.
    pub production: f32,
    /// Gold.
    pub gold: f32,
}

impl Yields {
    /// Yields of `food`, `production` and `gold`.
    #[must_use]
    pub const fn new(food: f32, production: f32, gold: f32) -> Self {
        Self { food, production, gold }
    }

    /// The three values, food first.
    #[must_use]
    pub fn values(self) -> [f32; 3] {
        [self.food, self.production, self.gold]
    }
}

impl std::ops::Add for Yields {
    type Output = Self;

    fn add(self, o: Self) -> Self {
        Self::new(self.food + o.food, self.production + o.production, self.gold + o.gold)
    }
}

impl std::ops::AddAssign for Yields {
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

/// The yields of a tile: its biome's, plus its tile type's, plus a bonus for a river through it
/// and for land next to the sea.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct YieldTable {
    /// Per biome; biomes not listed keep their default ([`YieldTable::default_biome`]).
    pub biomes: BTreeMap<Biome, Yields>,
    /// Added per tile type (none by default; on a map without a climate every tile's biome
    /// follows its type, so the biome entries already tell the types apart).
    pub kinds: BTreeMap<TileKind, Yields>,
    /// Added on a tile a river runs through.
    pub river: Yields,
    /// Added on a land tile next to the sea.
    pub coast: Yields,
}

impl Default for YieldTable {
    fn default() -> Self {
        Self {
            biomes: BTreeMap::new(),
            kinds: BTreeMap::new(),
            river: Yields::new(1.0, 0.0, 1.0),
            coast: Yields::new(0.0, 0.0, 1.0),
        }
    }
}

impl YieldTable {
    /// What a biome yields when the table does not list it (after Civilization's base
    /// terrains: grassland feeds, hills and forest produce, the sea feeds a little).
    #[must_use]
    pub fn default_biome(biome: Biome) -> Yields {
        match biome {
            Biome::Ocean => Yields::new(1.0, 0.0, 0.0),
            Biome::Coast => Yields::new(1.0, 0.0, 1.0),
            Biome::Lake => Yields::new(2.0, 0.0, 1.0),
            Biome::Desert | Biome::Snow | Biome::SnowPeak => Yields::new(0.0, 0.0, 0.0),
            Biome::Plains => Yields::new(1.0, 1.0, 0.0),
            Biome::Grassland => Yields::new(2.0, 0.0, 0.0),
            Biome::Forest => Yields::new(1.0, 2.0, 0.0),
            Biome::Rainforest => Yields::new(2.0, 1.0, 0.0),
            Biome::Tundra => Yields::new(1.0, 0.0, 0.0),
            Biome::Hills => Yields::new(0.0, 2.0, 0.0),
            Biome::Rock => Yields::new(0.0, 1.0, 0.0),
        }
    }

    /// A biome's yields: the table's entry, or the default.
    #[must_use]
    pub fn biome(&self, biome: Biome) -> Yields {
        self.biomes.get(&biome).copied().unwrap_or_else(|| Self::default_biome(biome))
    }
}

/// How a tile's yields add up to its value, and how much each tile of land a start reaches
/// before any rival adds to the start's value.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct ValueWeights {
    /// Worth of one food.
    pub food: f32,
    /// Worth of one production.
    pub production: f32,
    /// Worth of one gold.
    pub gold: f32,
    /// Worth of each passable tile the start reaches before any rival (by path cost).
    pub reach: f32,
}

impl Default for ValueWeights {
    fn default() -> Self {
        Self { food: 1.0, production: 1.0, gold: 0.5, reach: 0.02 }
    }
}

impl ValueWeights {
    /// The value of some yields.
    #[must_use]
    pub fn of(&self, y: Yields) -> f32 {
        y.food * self.food + y.production * self.production + y.gold * self.gold
    }
}

/// A kind of tile something may lie on.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum Place {
    /// Tiles of this biome: under the default ruleset the terrain named after it (as
    /// `Terrain(biome.id())`); on a map with its own ruleset, the climate's biome beneath the
    /// tile's terrain.
    Biome(Biome),
    /// Tiles of this type.
    Kind(TileKind),
    /// Tiles of this terrain of the map's ruleset (its id: `"grassland"`; under the default
    /// ruleset the biomes' names, `"snow_peak"`), whatever their feature.
    Terrain(String),
    /// Tiles with this feature of the map's ruleset (its id: `"forest"`).
    Feature(String),
}

/// Bonus, strategic or luxury, as in Civilization.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[repr(u8)]
pub enum ResourceClass {
    /// More food or production on its tile.
    #[default]
    Bonus = 0,
    /// Needed for units and buildings.
    Strategic = 1,
    /// Traded, keeps people happy.
    Luxury = 2,
}

impl ResourceClass {
    /// Every class, in order.
    pub const ALL: [Self; 3] = [Self::Bonus, Self::Strategic, Self::Luxury];

    /// Lower-case name.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Bonus => "bonus",
            Self::Strategic => "strategic",
            Self::Luxury => "luxury",
        }
    }
}

/// One resource: where it may lie, how common it is, how far apart, and how many each player
/// finds near its start.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct ResourceRule {
    /// Its name, unique in the table.
    pub name: String,
    /// Bonus, strategic or luxury.
    pub class: ResourceClass,
    /// The tiles it may lie on (any of them).
    pub on: Vec<Place>,
    /// Share of the tiles it may lie on that hold it, in `[0, 1]`.
    pub density: f32,
    /// Fewest tiles between two of it, `1..=64` (1: neighbors allowed).
    pub spacing: u32,
    /// How many each player finds within its start's rings, `0..=8`.
    pub per_player: u32,
    /// Added to its tile's yields.
    pub yields: Yields,
}

impl Default for ResourceRule {
    fn default() -> Self {
        Self {
            name: String::new(),
            class: ResourceClass::Bonus,
            on: Vec::new(),
            density: 0.05,
            spacing: 2,
            per_player: 0,
            yields: Yields::default(),
        }
    }
}

impl ResourceRule {
    fn new(
        name: &str,
        class: ResourceClass,
        on: &[Place],
        density: f32,
        spacing: u32,
        per_player: u32,
        y: Yields,
    ) -> Self {
        Self { name: name.into(), class, on: on.to_vec(), density, spacing, per_player, yields: y }
    }

    /// The default table: four bonus resources, two strategic, three luxuries; every player
    /// finds wheat, horses and iron near its start.
    #[must_use]
    pub fn defaults() -> Vec<Self> {
        use Biome as B;
        use Place::{Biome as On, Kind};
        use ResourceClass::{Bonus, Luxury, Strategic};
        vec![
            Self::new("wheat", Bonus, &[On(B::Plains), On(B::Grassland)], 0.06, 3, 1, Yields::new(1.0, 0.0, 0.0)),
            Self::new("cattle", Bonus, &[On(B::Grassland), On(B::Plains)], 0.04, 3, 0, Yields::new(1.0, 0.0, 0.0)),
            Self::new("deer", Bonus, &[On(B::Forest), On(B::Tundra)], 0.06, 3, 0, Yields::new(1.0, 0.0, 0.0)),
            Self::new("fish", Bonus, &[On(B::Coast), On(B::Lake)], 0.06, 3, 0, Yields::new(2.0, 0.0, 0.0)),
            Self::new(
                "horses",
                Strategic,
                &[On(B::Plains), On(B::Grassland), On(B::Tundra)],
                0.02,
                3,
                1,
                Yields::new(0.0, 1.0, 0.0),
            ),
            Self::new(
                "iron",
                Strategic,
                &[On(B::Hills), On(B::Tundra), On(B::Desert), Kind(TileKind::Mountain)],
                0.03,
                3,
                1,
                Yields::new(0.0, 1.0, 0.0),
            ),
            Self::new("gold", Luxury, &[On(B::Hills), On(B::Desert)], 0.015, 5, 0, Yields::new(0.0, 0.0, 2.0)),
            Self::new("spices", Luxury, &[On(B::Rainforest), On(B::Forest)], 0.015, 5, 0, Yields::new(0.0, 0.0, 2.0)),
            Self::new("whales", Luxury, &[On(B::Ocean), On(B::Coast)], 0.005, 6, 0, Yields::new(1.0, 0.0, 1.0)),
        ]
    }
}

/// Natural wonders: how many, where each may stand, how far apart and from starts.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct WonderConfig {
    /// How many to place (each wonder of `list` at most once), `0..=64`.
    pub count: u32,
    /// Fewest tiles between two wonders.
    pub spacing: u32,
    /// Fewest tiles between a wonder and any start.
    pub from_starts: u32,
    /// The wonders; the rarest (fewest tiles it may stand on) are placed first.
    pub list: Vec<WonderRule>,
}

impl Default for WonderConfig {
    fn default() -> Self {
        Self { count: 3, spacing: 8, from_starts: 4, list: WonderRule::defaults() }
    }
}

/// One natural wonder.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct WonderRule {
    /// Its name, unique among the wonders.
    pub name: String,
    /// The tiles it may stand on (any of them).
    pub on: Vec<Place>,
    /// Its tile's yields, added to the tile's own.
    pub yields: Yields,
}

impl WonderRule {
    /// The default wonders: a great peak, a barrier reef, a sacred lake, an old forest, a crater.
    #[must_use]
    pub fn defaults() -> Vec<Self> {
        use Biome as B;
        use Place::{Biome as On, Kind};
        let w = |name: &str, on: &[Place], y: Yields| Self { name: name.into(), on: on.to_vec(), yields: y };
        vec![
            w("great peak", &[On(B::SnowPeak), Kind(TileKind::Mountain)], Yields::new(0.0, 2.0, 3.0)),
            w("barrier reef", &[On(B::Coast)], Yields::new(3.0, 0.0, 2.0)),
            w("sacred lake", &[On(B::Lake)], Yields::new(2.0, 0.0, 4.0)),
            w("old forest", &[On(B::Rainforest), On(B::Forest)], Yields::new(2.0, 2.0, 1.0)),
            w("crater", &[On(B::Desert), On(B::Tundra), On(B::Snow)], Yields::new(0.0, 3.0, 2.0)),
        ]
    }
}
