//! How units move over the map: the cost of entering each tile. One model for the game's rules
//! and for the game setup's fairness (its reach and path costs), after Civilization's.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::vocab::Biome;

/// Highest cost of entering a tile.
pub const MAX_MOVE_COST: u32 = 100;

/// The movement model: the cost of entering a tile (its biome's, plus fording a river), which
/// tiles cannot be entered, and whether units may take to the sea.
///
/// ```
/// use hex_terrain::{Biome, MapConfig};
///
/// let config = MapConfig::from_ron("(movement: (costs: {Hills: 3}, river: 2, embark: Some(4)))").unwrap();
/// let m = &config.movement;
/// assert_eq!(m.enter(Biome::Hills, false), Some(3)); // set in the file
/// assert_eq!(m.enter(Biome::Forest, true), Some(4)); // the default 2, plus 2 across the river
/// assert_eq!(m.enter(Biome::Ocean, false), Some(4)); // embarked
/// assert_eq!(m.enter(Biome::SnowPeak, false), None); // impassable
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct MovementConfig {
    /// Cost of entering a tile of each biome, `0..=MAX_MOVE_COST` (0: impassable). Biomes not
    /// listed keep their default: 1 on open land (plains, grassland, desert, tundra, snow), 2 on
    /// hills, forest and rainforest, impassable on water (ocean, coast, lake), rock and snow peaks.
    pub costs: BTreeMap<Biome, u32>,
    /// Extra cost of entering a tile that carries a river (fording it), `0..=MAX_MOVE_COST`.
    pub river: u32,
    /// Units may embark: entering a sea tile (ocean or coast) costs this, `1..=MAX_MOVE_COST`;
    /// `None`: the sea is its biomes' cost (impassable by default).
    pub embark: Option<u32>,
}

impl Default for MovementConfig {
    fn default() -> Self {
        Self { costs: BTreeMap::new(), river: 1, embark: None }
    }
}

impl MovementConfig {
    /// The cost of entering a tile of `biome` (0: impassable): the `costs` entry, or the default.
    #[must_use]
    pub fn biome_cost(&self, biome: Biome) -> u32 {
        self.costs.get(&biome).copied().unwrap_or(match biome {
            Biome::Ocean | Biome::Coast | Biome::Lake | Biome::Rock | Biome::SnowPeak => 0,
            Biome::Hills | Biome::Forest | Biome::Rainforest => 2,
            _ => 1,
        })
    }

    /// The cost of entering a tile of `biome`, with a river on it or not; `None` when it cannot
    /// be entered. The sea (ocean and coast) costs `embark` when units may embark.
    #[must_use]
    pub fn enter(&self, biome: Biome, river: bool) -> Option<u32> {
        self.enter_with(self.biome_cost(biome), matches!(biome, Biome::Ocean | Biome::Coast), river)
    }

    /// The cost of entering a tile whose own cost is `cost` (0: impassable; a terrain ruleset's
    /// traits), on the sea or not, with a river on it or not: the sea costs `embark` when units
    /// may embark, a river `river` more; `None` when it cannot be entered.
    #[must_use]
    pub fn enter_with(&self, cost: u32, sea: bool, river: bool) -> Option<u32> {
        let base = match self.embark {
            Some(embark) if sea => embark,
            _ => cost,
        };
        (base > 0).then(|| base + if river { self.river } else { 0 })
    }

    /// Whether it is the default model (map files leave it out then).
    #[must_use]
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }
}
