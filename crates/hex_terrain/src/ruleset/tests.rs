//! The default ruleset gives every tile the climate stage's biome; the shipped rulesets load.

use proptest::prelude::*;

use super::*;
use crate::climate::{Climate, ClimateModel, TileSample};
use crate::config::{ClimateConfig, MapConfig, MapSize};
use crate::geometry::Geometry;
use crate::kind::Thresholds;
use crate::vocab::{Biome, TileKind};

fn model(config: &MapConfig) -> (ClimateModel, Geometry) {
    let geometry = Geometry::new(config);
    (ClimateModel::new(config, &geometry, Thresholds::new(&config.terrain, &config.manipulation)), geometry)
}

proptest! {
    /// Over random samples of random maps (the default table and the type presets' tables;
    /// climate on or off; hills on or off), the default ruleset's terrain is the climate
    /// stage's biome.
    #[test]
    fn the_biome_table_as_a_ruleset_gives_every_tile_its_biome(
        table in 0usize..3,
        enabled in any::<bool>(),
        hills in prop_oneof![Just(1.0f32), 0.0f32..1.0],
        raw in 0.0f32..1.0,
        neighbors in prop::collection::vec(prop::option::of(0u8..3), 6),
        lake in any::<bool>(),
        temperature in 0.0f32..=1.0,
        moisture in 0.0f32..=1.0,
    ) {
        let mut config = MapConfig { size: MapSize::Bounded { x: 12, z: 10 }, ..MapConfig::default() };
        config.climate = ClimateConfig { enabled, hills, ..ClimateConfig::default() };
        if table > 0 {
            let name = ["", "pangaea", "small_continents"][table];
            let text = std::fs::read_to_string(format!(
                "{}/../bevy_hex_terrain/assets/maps/types/{name}.map.ron", env!("CARGO_MANIFEST_DIR")
            )).unwrap();
            config.climate.biomes = MapConfig::from_ron(&text).unwrap().climate.biomes;
        }
        let (model, geometry) = model(&config);
        let thresholds = Thresholds::new(&config.terrain, &config.manipulation);
        let kinds = neighbors.iter().map(|n| n.map(|k| TileKind::ALL[usize::from(k)]));
        let s = TileSample::new(raw, thresholds.classify(raw), kinds);
        let lake = lake && s.kind != TileKind::Sea;
        let climate = (enabled && !lake && s.kind != TileKind::Sea).then_some(Climate { temperature, moisture });
        let biome = model.biome_from(&s, lake, climate);
        let ruleset = TerrainRuleset::biomes(&config);
        prop_assert!(ruleset.validate().is_ok(), "{:?}", ruleset.validate());
        let tile = geometry.tile_from_offset([3, 4]);
        let facts = model.facts(&geometry, tile, &s, lake, climate, (s.next_to_sea, false));
        let terrain = ruleset.terrain_for(&facts);
        prop_assert_eq!(Biome::ALL[usize::from(terrain.0)], biome, "{:?}", facts);
        prop_assert_eq!(ruleset.terrain(terrain).id.as_str(), biome.id());
        prop_assert_eq!(ruleset.biome(terrain), Some(biome));
    }
}

/// The shipped default ruleset file is the biome table's ruleset, written out.
#[test]
fn the_default_ruleset_file_is_the_biome_table() {
    let text = include_str!("../../../bevy_hex_terrain/assets/rulesets/default.terrain.ron");
    let file = TerrainRuleset::from_ron(text).unwrap();
    assert_eq!(
        file,
        TerrainRuleset::biomes(&MapConfig::default()),
        "if intended, write:\n{}",
        TerrainRuleset::biomes(&MapConfig::default()).to_ron()
    );
}

/// The three shipped rulesets load and validate.
#[test]
fn the_shipped_rulesets_load() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../bevy_hex_terrain/assets/rulesets");
    for name in ["default", "civ5", "fantasy"] {
        let ruleset = TerrainRuleset::load(dir.join(format!("{name}.terrain.ron")));
        assert!(ruleset.is_ok(), "{name}: {ruleset:?}");
    }
}

proptest! {
    /// A map's default ruleset gives each biome's terrain the traits the map's config gives the
    /// biome, whatever costs, tall biomes and yields the config sets.
    #[test]
    fn the_default_rulesets_traits_are_the_configs(
        costs in prop::collection::btree_map(0usize..13, 0u32..5, 0..6),
        tall in prop::collection::btree_set(0usize..13, 0..6),
        yields in prop::collection::btree_map(0usize..13, (0.0f32..4.0, 0.0f32..4.0, 0.0f32..4.0), 0..6),
        setup in any::<bool>(),
    ) {
        let mut config = MapConfig::default();
        config.movement.costs = costs.into_iter().map(|(b, c)| (Biome::ALL[b], c)).collect();
        config.sight.tall = tall.into_iter().map(|b| Biome::ALL[b]).collect();
        if setup {
            let mut s = crate::config::SetupConfig::default();
            s.yields.biomes =
                yields.into_iter().map(|(b, (f, p, g))| (Biome::ALL[b], crate::config::Yields::new(f, p, g))).collect();
            config.setup = Some(s);
        }
        let ruleset = TerrainRuleset::biomes(&config);
        for (i, biome) in Biome::ALL.into_iter().enumerate() {
            let t = &ruleset.terrains[i];
            prop_assert_eq!(ruleset.biome(TerrainId(i as u8)), Some(biome));
            prop_assert_eq!(t.traits.movement, config.movement.biome_cost(biome));
            prop_assert_eq!(t.traits.tall, config.sight.tall.contains(&biome));
            let table = config.setup.as_ref().map_or_else(crate::config::YieldTable::default, |s| s.yields.clone());
            prop_assert_eq!(t.traits.yields, table.biome(biome));
        }
    }
}
