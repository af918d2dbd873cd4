//! A Bevy plugin generating 3D hexagonal tiled terrain for turn-based strategy games, after the
//! thesis "Applying Perlin noise on 3D hexagonal tiled maps".
//!
//! `app.add_plugins(HexTerrainPlugin::default())` registers the [`HexMap`] resource and the
//! systems that stream chunk meshes around every [`HexTerrainAgent`]; pick a map file with
//! [`HexTerrainPlugin::from_asset`]. Heights, tile types and meshes come from the Bevy-free
//! [`hex_terrain`] crate, so [`HexMap`]'s queries hold for tiles whose chunk is not loaded.
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

pub mod asset;
pub mod map;
#[cfg(feature = "render")]
pub mod material;
pub mod mesh;
pub mod streaming;

use bevy::prelude::*;
pub use hex_terrain;
use hex_terrain::MapConfig;

pub use crate::asset::{HexMapAsset, HexMapLoader, HexMapLoaderError};
pub use crate::map::{HexMap, HexMapError, HexMapHandle, TileHit};
#[cfg(feature = "render")]
pub use crate::material::{HexTerrainMaterial, TerrainAppearance, TileHighlights};
pub use crate::streaming::{
    ChunkDespawned, ChunkSpawned, ChunkStreamer, ChunkTask, HexChunk, HexTerrainAgent, HexTerrainSettings, TerrainReady,
};

/// Everything a game usually needs.
pub mod prelude {
    #[cfg(feature = "render")]
    pub use crate::material::{TerrainAppearance, TileHighlights};
    pub use crate::{
        ChunkDespawned, ChunkSpawned, HexChunk, HexMap, HexMapError, HexTerrainAgent, HexTerrainPlugin,
        HexTerrainSettings, HexTerrainSystems, MapSource, TerrainReady,
    };
    pub use hex_terrain::hexx::Hex;
    pub use hex_terrain::{MapConfig, TileKind};
}

/// Where the map comes from.
#[derive(Debug, Clone)]
pub enum MapSource {
    /// A config given in code.
    Config(Box<MapConfig>),
    /// A RON asset path (e.g. `maps/island.map.ron`), hot-reloaded when the asset server
    /// watches files.
    Asset(String),
}

impl Default for MapSource {
    /// An unbounded continent: the thesis' Map0 noise, two inner rings, a maximum elevation of
    /// four hex radii (Map0's ten makes unit-sized hexes look like needles).
    fn default() -> Self {
        let mut config =
            MapConfig { name: "Continent".into(), size: hex_terrain::MapSize::Unbounded, ..MapConfig::default() };
        config.terrain.max_elevation = 4.0;
        config.terrain.inner_rings = 2;
        config.noise.scale = 60.0;
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

/// The system sets of the plugin, run in this order in `Update`.
#[derive(SystemSet, Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum HexTerrainSystems {
    /// Applies a loaded or hot-reloaded map config to [`HexMap`].
    Map,
    /// Decides the wanted chunks around agents, starts tasks, despawns far chunks.
    Stream,
    /// Inserts finished chunk meshes under the per-frame budget.
    Insert,
    /// Updates the terrain material (hot reload, appearance, highlights) and gives new chunk
    /// meshes their material.
    Render,
}

/// The terrain plugin: [`HexMap`], map assets, chunk streaming and (with the `render` feature,
/// in an app that renders) the terrain material. Add it after `DefaultPlugins`.
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
        if !app.is_plugin_added::<AssetPlugin>() {
            panic!(
                "HexTerrainPlugin needs Bevy's AssetPlugin: add DefaultPlugins, or MinimalPlugins with \
                 AssetPlugin::default(), before HexTerrainPlugin"
            );
        }
        let (map, handle) = match &self.map {
            MapSource::Config(config) => match HexMap::new((**config).clone()) {
                Ok(map) => (map, None),
                Err(e) => panic!("HexTerrainPlugin: the map config given in code is invalid: {e}"),
            },
            MapSource::Asset(path) => {
                let mut map = HexMap::new(MapConfig::default()).unwrap_or_else(|e| panic!("default map: {e}"));
                map.set_waiting(true);
                (map, Some(path.clone()))
            }
        };
        if !app.world().contains_resource::<Assets<Mesh>>() {
            app.init_asset::<Mesh>();
        }
        app.init_asset::<HexMapAsset>()
            .init_asset_loader::<HexMapLoader>()
            .insert_resource(map)
            .insert_resource(self.settings.clone())
            .init_resource::<ChunkStreamer>()
            .init_resource::<HexMapHandle>()
            .add_message::<HexMapError>()
            .add_message::<ChunkSpawned>()
            .add_message::<ChunkDespawned>()
            .add_message::<TerrainReady>()
            .register_type::<HexTerrainAgent>()
            .register_type::<HexTerrainSettings>()
            .register_type::<HexChunk>()
            // A new config must be in place before chunks are requested against it, and a
            // chunk must be requested before its mesh can be inserted.
            .configure_sets(
                Update,
                (
                    HexTerrainSystems::Map,
                    HexTerrainSystems::Stream,
                    HexTerrainSystems::Insert,
                    HexTerrainSystems::Render,
                )
                    .chain(),
            )
            .add_systems(
                Update,
                (
                    HexMap::apply_asset.in_set(HexTerrainSystems::Map),
                    ChunkStreamer::update.in_set(HexTerrainSystems::Stream),
                    ChunkStreamer::insert_ready.in_set(HexTerrainSystems::Insert),
                ),
            );
        if let Some(path) = handle {
            app.add_systems(PreStartup, move |server: Res<AssetServer>, mut handle: ResMut<HexMapHandle>| {
                handle.0 = Some(server.load(path.clone()));
            });
        }
        // Only an app that renders (PbrPlugin, from DefaultPlugins added before this plugin)
        // gets the material; headless apps (tests, servers) stream meshes without it.
        #[cfg(feature = "render")]
        if app.is_plugin_added::<bevy::pbr::PbrPlugin>() {
            app.add_plugins(material::HexTerrainMaterialPlugin);
        } else {
            debug!("HexTerrainPlugin: no PbrPlugin, chunks get no material");
        }
    }
}
