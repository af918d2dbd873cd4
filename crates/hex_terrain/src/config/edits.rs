//! The edits of a map: what a designer changed on the generated map, saved as a delta over the
//! seed in the map file's `edits` section (a list a person can read and diff, one entry an edited
//! tile), and checked like every other field.

use serde::{Deserialize, Serialize};

use super::check::{check, finite_in};
use super::{MAX_WORLD_TILE, MapSize, RiverConfig};
use crate::error::ConfigError;
use crate::vocab::{Biome, RuleId, TileKind};

/// Most edited tiles a map holds (a Civilization VI Huge map has 10,640 tiles; a designer's
/// scenario edits a fraction of them).
pub const MAX_EDITS: usize = 1 << 18;

/// What a designer set on one tile. Every field but `at` is optional: a tile keeps what the
/// generator gave it for the fields not set.
///
/// ```
/// use hex_terrain::{MapConfig, TileKind};
///
/// let config = MapConfig::from_ron(
///     "(size: Bounded(x: 20, z: 10), edits: [(at: (4, 5), kind: Some(Mountain)), (at: (5, 5), height: Some(0.4))])",
/// )
/// .unwrap();
/// assert_eq!(config.edits[0].kind, Some(TileKind::Mountain));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(deny_unknown_fields)]
pub struct TileEdit {
    /// The tile, in offset coordinates `(column, row)` like the map's size (on a wrapping map,
    /// the map's own column, `0..width`); on a globe `(id, 0)`, the tile's
    /// [`GlobeTile`](crate::GlobeTile) id ([`GlobeTile::at`](crate::GlobeTile::at)).
    pub at: (i32, i32),
    /// The height of the tile's center before the type rules, a fraction of the maximum
    /// elevation in `[0, 1]` (the generator's raw height: below `terrain.sea_threshold` is sea,
    /// from `terrain.mountain_threshold` on mountain). The whole tile moves with its center,
    /// keeping its relief; its border vertices move halfway (a third at corners), so the
    /// neighbors keep theirs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f32>,
    /// The tile's type: its center height is brought into the type's range (the nearest height
    /// of it to `height`, or to the generated one) and every inner vertex of the tile with it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kind: Option<TileKind>,
    /// The tile's biome, set by hand: it stays whatever the tile's elevation, climate or water,
    /// on maps with and without climate (an unedited tile's biome follows its edited elevation;
    /// the rule: [`Terrain::tile_info`](crate::Terrain::tile_info)).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub biome: Option<Biome>,
    /// A river set by hand on a map with rivers: a new source here, or no river here nor
    /// upstream of here.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub river: Option<RiverEdit>,
    /// How many props (trees, rocks, reeds) the tile grows, instead of what its biome grows.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub props: Option<PropDensity>,
    /// On a map with its own terrain ruleset: the tile's terrain, set by hand (its id), whatever
    /// its climate; its landform stays its elevation's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub terrain: Option<RuleId>,
    /// On a map with its own terrain ruleset: the tile's feature, set by hand, or none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub feature: Option<FeatureEdit>,
}

/// A feature set by hand on a tile ([`TileEdit::feature`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum FeatureEdit {
    /// This feature of the map's ruleset (its id), whatever the tile's terrain.
    Grow(RuleId),
    /// No feature.
    Clear,
}

/// A river set by hand on a tile ([`TileEdit::river`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum RiverEdit {
    /// A river rises on the tile and runs down the drainage, as generated rivers do, to the sea,
    /// a lake or the map's edge (merging with the rivers it meets). On a sea tile it does nothing.
    /// With rivers on tile edges it rises at the tile's lowest corner that drains (none beside
    /// water or the map's edge: then it does nothing), wherever that lies from the sea.
    Source,
    /// No water runs through the tile: neither the tile nor any tile draining through it carries
    /// a river, and the rivers downstream carry less (they may end where their flow falls below
    /// the threshold, or rise again where tributaries join). With rivers on tile edges: no
    /// water runs through the tile's corners, so no river runs along or ends on its edges.
    Dry,
}

/// How many props a tile grows ([`TileEdit::props`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum PropDensity {
    /// No props.
    None,
    /// A few: two or three trees on land (pines on high ground), a rock on a mountain.
    Sparse,
    /// A wood: seven to nine trees on land, four to six rocks on a mountain.
    Dense,
}

impl TileEdit {
    /// An edit of the tile at offset coordinates `at` that sets nothing yet.
    #[must_use]
    pub fn at(at: (i32, i32)) -> Self {
        Self { at, height: None, kind: None, biome: None, river: None, props: None, terrain: None, feature: None }
    }

    /// Whether it sets nothing (an edit that erasing left empty).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.height.is_none()
            && self.kind.is_none()
            && self.biome.is_none()
            && self.river.is_none()
            && self.props.is_none()
            && self.terrain.is_none()
            && self.feature.is_none()
    }
}

/// Checks the edits of a map of `size`: every tile on the map (within the world's edge on an
/// unbounded one, `(id, 0)` of one of its tiles on a globe), once; every height finite in `[0, 1]`; a type the map can have; at most
/// [`MAX_EDITS`]; a river only on a map with rivers; a biome only on a map of biomes, a terrain
/// and a feature only on a map with its own terrain ruleset.
pub(super) fn validate(
    edits: &[TileEdit],
    size: MapSize,
    sea_threshold: f32,
    rivers: &RiverConfig,
    own_ruleset: bool,
) -> Result<(), ConfigError> {
    check(edits.len() <= MAX_EDITS, "edits", format!("{} edited tiles", edits.len()), format!("at most {MAX_EDITS}"))?;
    let mut seen = std::collections::HashSet::with_capacity(edits.len());
    for (i, edit) in edits.iter().enumerate() {
        let (col, row) = edit.at;
        let field = format!("edits[{i}].at");
        match (size, size.bounds()) {
            (MapSize::Globe { frequency }, _) => {
                let tiles = 10 * i64::from(frequency).pow(2) + 2;
                check(
                    row == 0 && (0..tiles).contains(&i64::from(col)),
                    &field,
                    format!("({col}, {row})"),
                    format!("a tile of the globe: (id, 0) with an id in 0..{tiles}"),
                )?;
            }
            (_, Some((x, z))) => check(
                (0..x as i64).contains(&i64::from(col)) && (0..z as i64).contains(&i64::from(row)),
                &field,
                format!("({col}, {row})"),
                format!("a tile of the map: columns 0..{x}, rows 0..{z}"),
            )?,
            (_, None) => check(
                (-MAX_WORLD_TILE..MAX_WORLD_TILE).contains(&col) && (-MAX_WORLD_TILE..MAX_WORLD_TILE).contains(&row),
                &field,
                format!("({col}, {row})"),
                format!("a tile of the world: columns and rows in -{MAX_WORLD_TILE}..{MAX_WORLD_TILE}"),
            )?,
        }
        check(seen.insert(edit.at), &field, format!("({col}, {row})"), "a tile no other edit names")?;
        if let Some(h) = edit.height {
            check(finite_in(f64::from(h), 0.0, 1.0), &format!("edits[{i}].height"), h, "[0, 1]")?;
        }
        check(
            !(edit.kind == Some(TileKind::Sea) && sea_threshold <= 0.0),
            &format!("edits[{i}].kind"),
            "Sea",
            "Land or Mountain: terrain.sea_threshold is 0, so no tile is sea",
        )?;
        // One way to paint what a tile is: its biome on a map of biomes, its terrain and
        // feature on a map with its own ruleset (whose ids the pipeline checks).
        if let Some(biome) = edit.biome {
            check(
                !own_ruleset,
                &format!("edits[{i}].biome"),
                format!("{biome:?}"),
                "none on a map with its own terrain ruleset: paint `terrain` and `feature`",
            )?;
        }
        if let Some(terrain) = edit.terrain {
            check(
                own_ruleset,
                &format!("edits[{i}].terrain"),
                format!("{terrain:?}"),
                "none on a map without its own terrain ruleset (`ruleset`): paint `biome`",
            )?;
        }
        if let Some(feature) = edit.feature {
            check(
                own_ruleset,
                &format!("edits[{i}].feature"),
                format!("{feature:?}"),
                "none on a map without its own terrain ruleset (`ruleset`)",
            )?;
        }
        if let Some(river) = edit.river {
            check(
                rivers.enabled && size.bounds().is_some(),
                &format!("edits[{i}].river"),
                format!("{river:?}"),
                "none: rivers are off (rivers.enabled is false, or the map is unbounded)",
            )?;
        }
    }
    Ok(())
}
