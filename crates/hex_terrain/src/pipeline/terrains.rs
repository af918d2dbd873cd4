//! The pipeline's terrain ruleset: what each tile is under it ([`Pipeline::tile_terrain`]), its
//! look in the meshes, and the check that a map's edits name only the ruleset's terrains and
//! features.

use std::sync::Arc;

use hexx::Hex;

use super::Pipeline;
use crate::config::{FeatureEdit, MapConfig};
use crate::error::ConfigError;
use crate::geometry::Geometry;
use crate::ruleset::{FeaturePatches, Landform, TerrainId, TerrainRuleset, TileTerrain, TileTerrains};
use crate::vocab::{Biome, TileKind};

/// A map's terrain ruleset, ready to answer per tile.
#[derive(Debug)]
pub(super) struct Terrains {
    ruleset: Arc<TerrainRuleset>,
    patches: FeaturePatches,
    /// Whether the config named it (else it is the biome table's, and meshes keep the biomes'
    /// colors).
    pub(super) own: bool,
}

impl Terrains {
    pub(super) fn new(config: &MapConfig, geometry: &Geometry, ruleset: Option<Arc<TerrainRuleset>>) -> Self {
        let own = ruleset.is_some();
        let ruleset = ruleset.unwrap_or_else(|| Arc::new(TerrainRuleset::biomes(config)));
        let wrap_width = geometry.wrap().map(|w| w.width / geometry.hex_size());
        let patches = FeaturePatches::new(&ruleset, config.seed, wrap_width);
        Self { ruleset, patches, own }
    }
}

impl Pipeline {
    /// The map's terrain ruleset: the config's, or the biome table's
    /// ([`TerrainRuleset::biomes`]).
    #[must_use]
    pub fn ruleset(&self) -> &TerrainRuleset {
        &self.terrains.ruleset
    }

    /// Whether the config names its own terrain ruleset (then meshes take its colors).
    #[must_use]
    pub fn has_own_ruleset(&self) -> bool {
        self.terrains.own
    }

    /// What a tile of the map is under its ruleset: its terrain and feature from its landform,
    /// climate, height within its kind's band, latitude, and whether sea, a lake or a river is
    /// beside it. On a map without its own ruleset, the terrain is the tile's biome
    /// ([`Pipeline::tile_biome`]: a biome set by hand first).
    #[must_use]
    pub(crate) fn tile_terrain(&self, tile: Hex) -> TileTerrain {
        let geometry = &self.geometry;
        let sample = self.tile_sample(tile);
        let lake = self.table().is_some_and(|t| t.lake(geometry, tile).is_some());
        if !self.terrains.own {
            return self.biome_terrain(self.biome_with(tile, || sample), self.climate.landform(&sample, lake));
        }
        // The sample already knows its sea neighbors (their kinds, sampled once); lakes are the
        // table's.
        let lake_beside = |h: Hex| {
            let h = geometry.wrap_tile(h);
            geometry.contains(h) && self.table().is_some_and(|t| t.lake(geometry, h).is_some())
        };
        let near_water = sample.next_to_sea || tile.all_neighbors().into_iter().any(lake_beside);
        let near_river =
            self.table().is_some_and(|t| t.river_flow(geometry, tile) > 0.0 || t.river_edge_mask(geometry, tile) != 0);
        let climate = (self.climate.is_enabled() && !lake && sample.kind != TileKind::Sea).then(|| {
            self.table()
                .and_then(|t| t.climate(geometry, tile))
                .unwrap_or_else(|| self.climate.climate_of(geometry, &self.heights, tile, &sample))
        });
        let facts = self.climate.facts(geometry, tile, &sample, lake, climate, (near_water, near_river));
        let ruleset = &self.terrains.ruleset;
        // Set by hand (ids the compile checked), else by the rules.
        let (painted, grown) = self.heights.edits().map_or((None, None), |e| e.terrain(geometry, tile));
        let terrain =
            painted.and_then(|id| ruleset.terrain_id(id.as_str())).unwrap_or_else(|| ruleset.terrain_for(&facts));
        let feature = match grown {
            Some(FeatureEdit::Grow(id)) => ruleset.feature_id(id.as_str()),
            Some(FeatureEdit::Clear) => None,
            None => {
                let [x, z] = geometry.lattice().unit(geometry.lattice().tile_center(tile));
                self.terrains.patches.feature_for(ruleset, terrain, &facts, (x, z))
            }
        };
        TileTerrain {
            terrain,
            landform: facts.landform,
            feature,
            traits: ruleset.traits(terrain, facts.landform, feature),
        }
    }

    /// What a tile of `biome` on `landform` is under the default ruleset (a map without its
    /// own): the biome's terrain and its traits.
    pub(crate) fn biome_terrain(&self, biome: Biome, landform: Landform) -> TileTerrain {
        let terrain = TerrainId(biome as u8);
        TileTerrain { terrain, landform, feature: None, traits: self.terrains.ruleset.traits(terrain, landform, None) }
    }

    /// A tile's color and texture layer in the meshes under the map's own ruleset: its
    /// feature's look, else its terrain's.
    pub(crate) fn look_of(&self, t: &TileTerrain) -> ([u8; 3], u8) {
        let ruleset = &self.terrains.ruleset;
        let look = t.feature.map_or(&ruleset.terrain(t.terrain).look, |f| &ruleset.feature(f).look);
        (look.color, look.texture)
    }

    /// A tile's color in the meshes: its biome's, or, under the map's own ruleset, its
    /// feature's (else its terrain's).
    #[must_use]
    pub(crate) fn tile_color(&self, tile: Hex) -> [u8; 3] {
        self.tile_look(tile).0
    }

    /// A tile's color and texture layer in the meshes: its biome's (the default ruleset's
    /// terrain of that biome), or, under the map's own ruleset, its feature's (else its
    /// terrain's).
    #[must_use]
    pub(crate) fn tile_look(&self, tile: Hex) -> ([u8; 3], u8) {
        if !self.terrains.own {
            let biome = self.tile_biome(tile);
            return (biome.color(), self.biome_texture(biome));
        }
        self.look_of(&self.tile_terrain(tile))
    }

    /// The texture layer of a biome: its terrain's in the default ruleset (sea, grass or rock).
    #[must_use]
    pub(crate) fn biome_texture(&self, biome: Biome) -> u8 {
        crate::ruleset::biome_texture(biome)
    }
}

impl TileTerrains for Pipeline {
    fn tile_terrain(&self, tile: Hex) -> TileTerrain {
        Pipeline::tile_terrain(self, tile)
    }
}

/// Every terrain and feature an edit sets is one of the ruleset's: a save whose ruleset lost an
/// id it needs is refused, naming the edit and the ids the ruleset has.
pub(super) fn check_edit_ids(config: &MapConfig, ruleset: &TerrainRuleset) -> Result<(), ConfigError> {
    for (i, edit) in config.edits.iter().enumerate() {
        if let Some(id) = edit.terrain.filter(|id| ruleset.terrain_id(id.as_str()).is_none()) {
            let ids: Vec<&str> = ruleset.terrains.iter().map(|t| t.id.as_str()).collect();
            return Err(ConfigError::new(
                &format!("edits[{i}].terrain"),
                format!("{id:?}"),
                format!("a terrain of the ruleset {:?}: {}", ruleset.name, ids.join(", ")),
            ));
        }
        if let Some(FeatureEdit::Grow(id)) = edit.feature.filter(|f| match f {
            FeatureEdit::Grow(id) => ruleset.feature_id(id.as_str()).is_none(),
            FeatureEdit::Clear => false,
        }) {
            let ids: Vec<&str> = ruleset.features.iter().map(|f| f.id.as_str()).collect();
            return Err(ConfigError::new(
                &format!("edits[{i}].feature"),
                format!("{id:?}"),
                format!("a feature of the ruleset {:?}: {}", ruleset.name, ids.join(", ")),
            ));
        }
    }
    Ok(())
}
