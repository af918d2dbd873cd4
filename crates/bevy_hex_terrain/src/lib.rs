//! A Bevy plugin generating 3D hexagonal tiled terrain for turn-based strategy games, after the
//! thesis "Applying Perlin noise on 3D hexagonal tiled maps".
//!
//! `app.add_plugins(HexTerrainPlugin::default())` adds [`HexTerrainPlugins`]: the [`HexMap`]
//! resource and its map assets ([`HexMapPlugin`]), chunk streaming around every
//! [`HexTerrainAgent`] ([`HexStreamingPlugin`]), with the `picking` feature a `bevy_picking`
//! backend whose pointer events carry the tile (`HexPickingPlugin`) and, with the `render`
//! feature, the terrain material (`HexTerrainMaterialPlugin`). Pick a map file with [`HexTerrainPlugin::from_asset`],
//! switch maps at run time with the [`LoadHexMap`] message. Heights, tile types and meshes come
//! from the Bevy-free [`hex_terrain`] crate, so [`HexMap`]'s queries hold for tiles whose chunk
//! is not loaded.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_hex_terrain::prelude::*;
//!
//! App::new()
//!     .add_plugins((DefaultPlugins, HexTerrainPlugin::from_asset("maps/island.map.ron")))
//!     .add_systems(Startup, |mut commands: Commands| {
//!         commands.spawn((Camera3d::default(), HexTerrainAgent::default(),
//!             Transform::from_xyz(0.0, 30.0, 30.0).looking_at(Vec3::ZERO, Vec3::Y)));
//!     })
//!     .run();
//! ```
//!
//! A headless app (a server, a test) streams meshes without the material:
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_hex_terrain::prelude::*;
//!
//! let mut app = App::new();
//! app.add_plugins((MinimalPlugins, AssetPlugin::default(), TransformPlugin));
//! # #[cfg(feature = "render")]
//! app.add_plugins(HexTerrainPlugins::default().build().disable::<HexTerrainMaterialPlugin>());
//! ```

pub mod asset;
#[cfg(feature = "big_space")]
pub mod far;
#[cfg(feature = "render")]
pub mod light;
pub mod map;
#[cfg(feature = "render")]
pub mod material;
pub mod mesh;
#[cfg(feature = "minimap")]
pub mod minimap;
#[cfg(feature = "picking")]
pub mod picking;
pub mod props;
pub mod streaming;
pub mod tiles;
pub mod water;

use bevy::app::PluginGroupBuilder;
use bevy::prelude::*;
pub use hex_terrain;
use hex_terrain::MapConfig;

pub use crate::asset::{HexMapAsset, HexMapLoader, HexMapLoaderError};
#[cfg(feature = "big_space")]
pub use crate::far::{HexBigSpacePlugin, HexTerrainGrid};
#[cfg(feature = "render")]
pub use crate::light::{HexLightPlugin, HexSun, HexTerrainCamera, TerrainLighting};
pub use crate::map::{HexMap, HexMapError, HexMapHandle, HexMapPlugin, LoadHexMap, TileHit, TileHitF64};
#[cfg(feature = "render")]
pub use crate::material::{HexTerrainMaterial, HexTerrainMaterialPlugin, RenderOrigin, TerrainAppearance};
#[cfg(feature = "minimap")]
pub use crate::minimap::{
    HexMinimap, HexMinimapCamera, HexMinimapPlugin, HexMinimapSystems, MinimapCorner, MinimapNavigate, MinimapPicture,
    MinimapSettings,
};
#[cfg(feature = "picking")]
pub use crate::picking::{HexPick, HexPickingCamera, HexPickingPlugin, HexPickingSettings, HexPickingStats};
pub use crate::props::{HexProp, HexPropStats, HexPropsPlugin};
pub use crate::streaming::{
    ChunkContent, ChunkDespawned, ChunkSpawned, ChunkStreamer, ChunkTask, ChunkThreads, HexChunk, HexStreamingPlugin,
    HexTerrainAgent, HexTerrainSettings, HexTerrainStats, HexWorldPosition, PropSettings, TerrainReady, WaterSettings,
};
pub use crate::tiles::{
    FogState, HexTileStatePlugin, HexTileStateSystems, Highlight, SaveError, TileStateError, TileStateSave,
    TileStateSettings, TileStateStats, TileStates,
};
pub use crate::water::{HexWater, HexWaterPlugin};

/// Everything a game usually needs.
pub mod prelude {
    #[cfg(feature = "big_space")]
    pub use crate::far::{HexBigSpacePlugin, HexTerrainGrid};
    #[cfg(feature = "render")]
    pub use crate::light::{HexLightPlugin, HexTerrainCamera, TerrainLighting};
    #[cfg(feature = "render")]
    pub use crate::material::{HexTerrainMaterialPlugin, TerrainAppearance};
    #[cfg(feature = "minimap")]
    pub use crate::minimap::{HexMinimapPlugin, MinimapNavigate, MinimapSettings};
    #[cfg(feature = "picking")]
    pub use crate::picking::{HexPick, HexPickingPlugin};
    pub use crate::{
        ChunkDespawned, ChunkSpawned, ChunkStreamer, FogState, HexChunk, HexMap, HexMapError, HexMapPlugin, HexProp,
        HexStreamingPlugin, HexTerrainAgent, HexTerrainPlugin, HexTerrainPlugins, HexTerrainSettings, HexTerrainStats,
        HexTerrainSystems, HexTileStatePlugin, HexWater, HexWorldPosition, Highlight, LoadHexMap, MapSource,
        PropSettings, SaveError, TerrainReady, TileHit, TileStateSave, TileStates, WaterSettings,
    };
    pub use hex_terrain::hexx::Hex;
    pub use hex_terrain::{
        Biome, ChunkCoord, MapConfig, MapSize, PlacedResource, PlacedWonder, ResourceClass, RiverTile, Setup,
        SetupConfig, TileInfo, TileKind,
    };
}

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

/// The system sets of the plugins, run in this order in `Update`.
#[derive(SystemSet, Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum HexTerrainSystems {
    /// Applies a loaded, hot-reloaded or switched map to [`HexMap`].
    Map,
    /// Decides the wanted chunks around agents, starts tasks, despawns far chunks.
    Stream,
    /// Inserts finished chunk meshes under the per-frame budget.
    Insert,
    /// Keeps the [`TileStates`] window on the map and around the loaded chunks.
    Tiles,
    /// Updates the terrain material (hot reload, appearance, tile state texture) and gives new
    /// chunk meshes their material.
    Render,
}

/// The terrain plugins: [`HexMapPlugin`] (the [`HexMap`] resource, map assets, switching),
/// [`HexStreamingPlugin`] (chunks around agents), [`HexTileStatePlugin`] (per-tile game state:
/// fog of war, territory, lenses, highlights), [`HexWaterPlugin`] (the water surface's
/// entities), [`HexPropsPlugin`] (trees, rocks, reeds) and, with the `render` feature,
/// `HexTerrainMaterialPlugin` (the terrain and water material, which needs Bevy's `PbrPlugin`)
/// and `HexLightPlugin` (sun, shadows, fog, occlusion for `HexTerrainCamera`s). Disable one
/// with `HexTerrainPlugins::default().build().disable::<…>()`.
#[derive(Debug, Clone, Default)]
pub struct HexTerrainPlugins {
    /// The map to show.
    pub map: MapSource,
    /// Streaming parameters.
    pub settings: HexTerrainSettings,
}

impl HexTerrainPlugins {
    /// The plugins showing a map config (a path or a config).
    #[must_use]
    pub fn new(map: impl Into<MapSource>) -> Self {
        Self { map: map.into(), settings: HexTerrainSettings::default() }
    }
}

impl PluginGroup for HexTerrainPlugins {
    fn build(self) -> PluginGroupBuilder {
        let group = PluginGroupBuilder::start::<Self>()
            .add(HexMapPlugin { map: self.map })
            .add(HexStreamingPlugin { settings: self.settings })
            .add(HexTileStatePlugin::default())
            .add(HexWaterPlugin)
            .add(HexPropsPlugin);
        #[cfg(feature = "picking")]
        let group = group.add(picking::HexPickingPlugin::default());
        #[cfg(feature = "render")]
        let group = group.add(material::HexTerrainMaterialPlugin).add(light::HexLightPlugin);
        group
    }
}

/// The one-line entry: adds every plugin of [`HexTerrainPlugins`]. Add it after
/// `DefaultPlugins`.
#[derive(Debug, Clone, Default)]
pub struct HexTerrainPlugin {
    /// The map to show.
    pub map: MapSource,
    /// Streaming parameters.
    pub settings: HexTerrainSettings,
}

impl HexTerrainPlugin {
    /// The plugin showing the map config at an asset path.
    #[must_use]
    pub fn from_asset(path: impl Into<String>) -> Self {
        Self { map: MapSource::Asset(path.into()), ..default() }
    }

    /// The plugin showing a config given in code.
    #[must_use]
    pub fn from_config(config: MapConfig) -> Self {
        Self { map: MapSource::Config(Box::new(config)), ..default() }
    }
}

impl Plugin for HexTerrainPlugin {
    fn build(&self, app: &mut App) {
        app.add_plugins(HexTerrainPlugins { map: self.map.clone(), settings: self.settings.clone() });
    }
}
