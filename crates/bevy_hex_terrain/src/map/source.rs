//! Where a map comes from: a config given in code or a RON asset path.

use bevy::prelude::*;
use hex_terrain::MapConfig;

/// Where the map comes from. Reflected as an opaque value (its config is boxed): inspectors show
/// it by `Debug`.
#[derive(Debug, Clone, Reflect)]
#[reflect(opaque, Debug, Clone)]
pub enum MapSource {
    /// A config given in code.
    Config(Box<MapConfig>),
    /// A RON asset path (e.g. `maps/island.map.ron`), hot-reloaded when the asset server
    /// watches files.
    Asset(String),
}

impl Default for MapSource {
    /// An unbounded continent: the thesis' Map0 noise, two inner rings, a maximum elevation of
    /// four hex radii (Map0's ten makes unit-sized hexes look like needles), peaks and hills
    /// ([`ReliefConfig::MOUNTAINS`](hex_terrain::ReliefConfig::MOUNTAINS)).
    fn default() -> Self {
        let mut config =
            MapConfig { name: "Continent".into(), size: hex_terrain::MapSize::Unbounded, ..MapConfig::default() };
        config.terrain.max_elevation = 4.0;
        config.terrain.inner_rings = 2;
        config.noise.scale = 60.0;
        config.relief = hex_terrain::ReliefConfig::MOUNTAINS;
        Self::Config(Box::new(config))
    }
}

impl From<&str> for MapSource {
    fn from(path: &str) -> Self {
        Self::Asset(path.to_owned())
    }
}

impl From<String> for MapSource {
    fn from(path: String) -> Self {
        Self::Asset(path)
    }
}

impl From<MapConfig> for MapSource {
    fn from(config: MapConfig) -> Self {
        Self::Config(Box::new(config))
    }
}
