//! The default ruleset: the 13 biomes ([`Biome`]) as terrains, in their order (terrain `i` is
//! `Biome::ALL[i]`, its id [`Biome::id`]), placed by a map's biome table. It gives every tile
//! the biome the climate stage gives it
//! ([`ClimateModel::biome_from`](crate::ClimateModel::biome_from)), and the movement costs,
//! sight and yields the map's config gives each biome.

use std::collections::BTreeMap;

use super::{Landform, Look, Occurs, TerrainDef, TerrainRuleset, Traits};
use crate::config::{BiomeRule, MapConfig, YieldTable};
use crate::vocab::{Biome, TileKind};

/// The priority of the table's rules, and of the hills over them.
const TABLE: u8 = 1;

/// The priority of snow and tundra, which stay on hills (the hills line does not lift them).
const COLD: u8 = 2;

impl TerrainRuleset {
    /// The default ruleset of a map: the 13 biomes placed by its biome table
    /// ([`ClimateConfig::biomes`](crate::ClimateConfig::biomes)): each table rule a rule of its
    /// biome on flat land (or mountains), snow and tundra on hills too and above the hills,
    /// which take every other hills tile; ocean on open sea, coast on the shore, lake on lakes;
    /// without a climate (and where the table covers nothing) ocean, lake, grassland and rock.
    /// Each terrain's traits are its biome's by the config: the cost of entering it
    /// ([`MovementConfig::biome_cost`](crate::MovementConfig::biome_cost)), whether it stands
    /// tall ([`SightConfig::tall`](crate::SightConfig::tall)) and its yields
    /// ([`YieldTable::biome`](crate::YieldTable::biome)).
    #[must_use]
    pub fn biomes(config: &MapConfig) -> Self {
        let (climate, movement, sight) = (&config.climate, &config.movement, &config.sight);
        let mut occurs: BTreeMap<Biome, Vec<Occurs>> = BTreeMap::new();
        let rule = |landform: Vec<Landform>, priority: u8| Occurs { landform, priority, ..Occurs::default() };
        occurs.entry(Biome::Ocean).or_default().push(rule(vec![Landform::OpenSea], TABLE));
        occurs.entry(Biome::Coast).or_default().push(rule(vec![Landform::Shore], TABLE));
        occurs.entry(Biome::Lake).or_default().push(rule(vec![Landform::Lake], TABLE));
        occurs.entry(Biome::Hills).or_default().push(rule(vec![Landform::Hills], TABLE));
        for BiomeRule { biome, relief, temperature, moisture } in &climate.biomes {
            let (landform, priority) = match (relief, biome) {
                (TileKind::Mountain, _) => (vec![Landform::Mountain], TABLE),
                (_, Biome::Snow | Biome::Tundra) => (vec![Landform::Flat, Landform::Hills], COLD),
                _ => (vec![Landform::Flat], TABLE),
            };
            let r = Occurs { temperature: *temperature, moisture: *moisture, ..rule(landform, priority) };
            occurs.entry(*biome).or_default().push(r);
        }
        let terrains = Biome::ALL
            .into_iter()
            .map(|b| TerrainDef {
                id: b.id().to_owned(),
                name: capitalised(b.name()),
                occurs: occurs.remove(&b).unwrap_or_default(),
                traits: Traits {
                    movement: movement.biome_cost(b),
                    tall: sight.tall.contains(&b),
                    yields: config.setup.as_ref().map_or_else(|| YieldTable::default_biome(b), |s| s.yields.biome(b)),
                },
                hills: None,
                look: Look { color: b.color(), texture: biome_texture(b), minimap: None, props: None },
            })
            .collect();
        let id = |b: Biome| b.id().to_owned();
        let fallback = BTreeMap::from([
            (Landform::OpenSea, id(Biome::Ocean)),
            (Landform::Shore, id(Biome::Ocean)),
            (Landform::Lake, id(Biome::Lake)),
            (Landform::Flat, id(Biome::Grassland)),
            (Landform::Hills, id(Biome::Hills)),
            (Landform::Mountain, id(Biome::Rock)),
        ]);
        Self { name: "Biomes".to_owned(), fallback, terrains, features: Vec::new() }
    }
}

/// "snow peak" to "Snow peak".
fn capitalised(name: &str) -> String {
    let mut chars = name.chars();
    chars.next().map_or_else(String::new, |c| c.to_uppercase().chain(chars).collect())
}

/// The material's texture layer of a biome in the default ruleset: sea (0), grass (1), rock (2).
pub(crate) fn biome_texture(b: Biome) -> u8 {
    match b {
        Biome::Ocean | Biome::Coast | Biome::Lake => 0,
        Biome::Rock | Biome::SnowPeak => 2,
        _ => 1,
    }
}
