//! What units see: how far, and what blocks their view, after Civilization's.

use std::collections::BTreeSet;

use serde::{Deserialize, Serialize};

use crate::vocab::Biome;

/// Largest sight bonus of a tall tile or a mountain.
pub const MAX_SIGHT_BONUS: u32 = 8;

/// The sight rule (the map config's `sight`). Tiles have a height for sight: 2 for a mountain,
/// 1 for a tile of a `tall` biome (hills and forests by default), 0 for the rest (open land and
/// water). A viewer sees a tile within its radius unless a tile strictly between them on hexx's
/// line (drawn from the viewer) is higher than the viewer's own tile, or is a mountain (mountains block every view); a
/// viewer on a tall tile sees `tall_bonus` farther, on a mountain `mountain_bonus` farther. Not
/// symmetric: a unit on a hill sees over a forest that hides the hill from a unit on flat land.
///
/// ```
/// use hex_terrain::MapConfig;
///
/// let config = MapConfig::from_ron("(sight: (tall: [Hills], tall_bonus: 1, mountain_bonus: 3))").unwrap();
/// assert_eq!(config.sight.mountain_bonus, 3);
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct SightConfig {
    /// Biomes that stand tall: they block the view of viewers on lower tiles and lift a viewer
    /// on them.
    pub tall: BTreeSet<Biome>,
    /// Extra sight radius of a viewer on a tall tile, `0..=MAX_SIGHT_BONUS`.
    pub tall_bonus: u32,
    /// Extra sight radius of a viewer on a mountain, `0..=MAX_SIGHT_BONUS`.
    pub mountain_bonus: u32,
}

impl Default for SightConfig {
    fn default() -> Self {
        Self {
            tall: BTreeSet::from([Biome::Hills, Biome::Forest, Biome::Rainforest]),
            tall_bonus: 1,
            mountain_bonus: 2,
        }
    }
}

impl SightConfig {
    /// Whether it is the default rule (map files leave it out then).
    #[must_use]
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }
}
