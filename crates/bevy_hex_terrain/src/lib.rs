//! A Bevy plugin generating 3D hexagonal tiled terrain for turn-based strategy games, after the
//! thesis "Applying Perlin noise on 3D hexagonal tiled maps". Heights, tile types and meshes come
//! from the Bevy-free [`hex_terrain`] crate, so [`HexMap`]'s queries hold for tiles whose chunk is
//! not loaded.
//!
//! `app.add_plugins(HexTerrainPlugins::from_asset("maps/island.map.ron"))` adds every plugin;
//! each owns its settings resource and runs in the public [`HexTerrainSystems`] sets, in the
//! order data flows through them:
//!
//! | set | plugin | what it does | its settings |
//! | --- | --- | --- | --- |
//! | [`Map`](HexTerrainSystems::Map) | [`HexMapPlugin`] | loads `*.map.ron` assets (hot reload, [`LoadHexMap`]) into the [`HexMap`] resource, sets up a game on it ([`SetUpGame`], then [`GameSetUp`]); a bad file is a [`HexMapError`] and the old map stays | [`MapSource`] |
//! | [`Map`](HexTerrainSystems::Map) | [`HexEditorPlugin`] | the world builder: [`HexMapEdit`] strokes, undo, redo and save run on the async compute pool; each edit makes a [`HexMap`] generation in which only its chunks are rebuilt ([`HexMapEdited`]; one that changes nothing, [`HexMapUnchanged`]) | |
//! | [`Stream`](HexTerrainSystems::Stream) | [`HexStreamingPlugin`] | keeps [`HexChunk`]s around every [`HexTerrainAgent`], each built on the async compute pool from a snapshot of the settings below; a dropped chunk is hidden at once and its children despawned a budget a frame | [`HexStreamingSettings`] |
//! | [`Insert`](HexTerrainSystems::Insert) | [`HexStreamingPlugin`] | inserts finished meshes and their [`ChunkContent`] under a per-frame budget, sends [`ChunkSpawned`], [`TerrainReady`] (once per map), [`TerrainSettled`] | |
//! | [`Children`](HexTerrainSystems::Children) | [`HexWaterPlugin`], [`HexPropsPlugin`] | spawn each chunk's [`HexWater`] surface and [`HexProp`]s (a budget a frame, nearest chunks first) from its content | [`HexWaterSettings`], [`HexPropSettings`] |
//! | [`Tiles`](HexTerrainSystems::Tiles) | [`HexTileStatePlugin`] | keeps the [`TileStates`] window (fog of war, owners, lens, highlights) on the map; packs changed rows in `PostUpdate` | [`HexTileStateSettings`], [`HexTileStateStyle`] |
//! | [`Place`](HexTerrainSystems::Place) | [`HexPlacementPlugin`] | keeps [`OnTile`] entities (units, cities) on the surface of their tiles, walks [`TileWalk`]s, hides entities under the fog the [`TileStates`] show | |
//! | [`Render`](HexTerrainSystems::Render) | `HexTerrainMaterialPlugin`, `HexLightPlugin` (`render`) | the terrain and water material and its tile state texture; the sun, fog and ambient light of `HexTerrainCamera`s | `HexTerrainMaterialSettings`, `HexLightSettings` |
//!
//! Besides them: [`HexGlobePlugin`], a hex globe (a map file of size `Globe`) streamed to each
//! agent's horizon with its [`GlobeCamera`], in place of the flat map's plugins, picked with
//! the `picking` feature (`HexGlobePick`, `HoveredGlobeTile`; the flat map's material and tile
//! states do not reach it yet);
//! with the `picking` feature `HexPickingPlugin`, a `bevy_picking` backend whose
//! hits carry the tile (`HexPick`);
//! with `minimap` `HexMinimapPlugin` (and `HexGlobeMinimapPlugin`, a globe's equirectangular
//! minimap); with `big_space` `HexBigSpacePlugin` (floating origin).
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_hex_terrain::prelude::*;
//!
//! App::new()
//!     .add_plugins((DefaultPlugins, HexTerrainPlugins::from_asset("maps/island.map.ron")))
//!     .add_systems(Startup, |mut commands: Commands| {
//!         // A terrain camera (it brings its `Camera3d`, distance fog and ambient light) that
//!         // keeps terrain streamed around itself.
//!         commands.spawn((HexTerrainCamera, HexTerrainAgent::default(),
//!             Transform::from_xyz(0.0, 30.0, 30.0).looking_at(Vec3::ZERO, Vec3::Y)));
//!     })
//!     .run();
//! ```
//!
//! A headless app (a server, a test) streams meshes without the material (or builds the crate
//! with `default-features = false`, which has no renderer at all):
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

mod asset;
mod editor;
#[cfg(feature = "big_space")]
mod far;
mod globe;
// The guide is built with the `minimap` and `big_space` features, as on docs.rs.
#[cfg(all(feature = "minimap", feature = "big_space"))]
pub mod guide;
#[cfg(feature = "render")]
mod light;
mod map;
#[cfg(feature = "render")]
mod material;
mod mesh;
#[cfg(feature = "minimap")]
mod minimap;
#[cfg(feature = "picking")]
mod picking;
mod placement;
mod props;
#[cfg(feature = "render")]
mod screenshot;
mod streaming;
mod tiles;
mod water;

use bevy::app::PluginGroupBuilder;
use bevy::prelude::*;
pub use hex_terrain;
use hex_terrain::MapConfig;

pub use crate::asset::{HexMapAsset, HexMapLoader, HexMapLoaderError};
pub use crate::editor::{
    EditAction, HexEditor, HexEditorPlugin, HexMapEdit, HexMapEdited, HexMapSaved, HexMapUnchanged,
};
#[cfg(feature = "big_space")]
pub use crate::far::{HexBigSpacePlugin, HexTerrainGrid};
pub use crate::globe::{
    GLOBE_ROW, GlobeCamera, GlobeStreamer, GlobeTileStates, GlobeTileWalk, GlobeWalkEnded, HexGlobe, HexGlobeChunk,
    HexGlobeEditor, HexGlobeEditorPlugin, HexGlobePlugin, HexGlobeProp, HexGlobeSettings, NEAR_ANGLE, OnGlobeTile,
    globe_horizon,
};
#[cfg(feature = "minimap")]
pub use crate::globe::{GlobeMinimapNavigate, GlobeMinimapPicture, HexGlobeMinimap, HexGlobeMinimapPlugin};
#[cfg(feature = "render")]
pub use crate::globe::{GlobeParams, HexGlobeExtension, HexGlobeMaterial};
#[cfg(feature = "picking")]
pub use crate::globe::{HexGlobePick, HoveredGlobeTile};
#[cfg(feature = "render")]
pub use crate::light::{HexLightPlugin, HexLightSettings, HexSun, HexTerrainCamera};
pub use crate::map::{
    GameSetUp, HexMap, HexMapError, HexMapHandle, HexMapPlugin, LoadHexMap, MapSource, SetUpGame, TileHit, TileHitF64,
};
#[cfg(feature = "render")]
pub use crate::material::{
    HexTerrainExtension, HexTerrainKey, HexTerrainMaterial, HexTerrainMaterialPlugin, HexTerrainMaterialSettings,
    MAX_TEXTURE_LAYERS, OwnerColors, RenderOrigin, TerrainParams,
};
#[cfg(feature = "minimap")]
pub use crate::minimap::{
    HexMinimap, HexMinimapCamera, HexMinimapPlugin, HexMinimapSettings, HexMinimapSystems, MinimapCorner,
    MinimapNavigate, MinimapPicture,
};
#[cfg(feature = "picking")]
pub use crate::picking::{
    HexPick, HexPickingCamera, HexPickingPlugin, HexPickingSettings, HexPickingStats, HoveredTile,
};
pub use crate::placement::{HexPlacementPlugin, OnTile, TileWalk, WalkEnded};
pub use crate::props::{HexProp, HexPropSettings, HexPropStats, HexPropsPlugin, PropAssets};
#[cfg(feature = "render")]
pub use crate::screenshot::HexScreenshotPlugin;
pub use crate::streaming::{
    ChunkContent, ChunkDespawned, ChunkSpawned, ChunkStreamer, ChunkTask, ChunkThreads, DEFAULT_COARSE_DISTANCE,
    DETAIL_HYSTERESIS, HexChunk, HexStreamingPlugin, HexStreamingSettings, HexStreamingStats, HexTerrainAgent,
    HexWorldPosition, MAX_RETIRED_CHUNKS, TerrainReady, TerrainSettled,
};
pub use crate::tiles::{
    FogState, HexTileStatePlugin, HexTileStateSettings, HexTileStateStats, HexTileStateStyle, HexTileStateSystems,
    Highlight, MAX_OWNERS, SaveError, Texel, TileStateError, TileStateSave, TileStateUpload, TileStates,
};
pub use crate::water::{HexWater, HexWaterPlugin, HexWaterSettings};

/// Everything a game usually needs.
pub mod prelude {
    #[cfg(feature = "big_space")]
    pub use crate::far::{HexBigSpacePlugin, HexTerrainGrid};
    #[cfg(feature = "render")]
    pub use crate::light::{HexLightPlugin, HexLightSettings, HexTerrainCamera};
    #[cfg(feature = "render")]
    pub use crate::material::{HexTerrainMaterialPlugin, HexTerrainMaterialSettings};
    #[cfg(feature = "minimap")]
    pub use crate::minimap::{HexMinimapPlugin, HexMinimapSettings, MinimapNavigate};
    #[cfg(feature = "picking")]
    pub use crate::picking::{HexPick, HexPickingPlugin, HexPickingSettings, HoveredTile};
    #[cfg(feature = "render")]
    pub use crate::screenshot::HexScreenshotPlugin;
    pub use crate::{
        ChunkContent, ChunkDespawned, ChunkSpawned, ChunkStreamer, FogState, GameSetUp, GlobeCamera, GlobeTileStates,
        HexChunk, HexEditor, HexGlobe, HexGlobeChunk, HexGlobeEditor, HexGlobeEditorPlugin, HexGlobePlugin, HexMap,
        HexMapEdit, HexMapEdited, HexMapError, HexMapPlugin, HexMapUnchanged, HexProp, HexPropSettings, HexPropsPlugin,
        HexStreamingPlugin, HexStreamingSettings, HexStreamingStats, HexTerrainAgent, HexTerrainPlugins,
        HexTerrainSystems, HexTileStatePlugin, HexTileStateSettings, HexTileStateStyle, HexWater, HexWaterPlugin,
        HexWaterSettings, HexWorldPosition, Highlight, LoadHexMap, MapSource, OnTile, SaveError, SetUpGame,
        TerrainReady, TerrainSettled, TileHit, TileStateSave, TileStates, TileWalk, WalkEnded,
    };
    pub use hex_terrain::hexx::Hex;
    pub use hex_terrain::{
        Biome, Brush, Change, ChunkCoord, Detail, EditError, Landform, MapConfig, MapSize, MapStats, MapType,
        MapTypeConfig, MapTypeReport, MovementConfig, PlacedResource, PlacedWonder, ResourceClass, RiverTile, Setup,
        SetupConfig, Stroke, TerrainRuleset, TileEdit, TileInfo, TileKind, TileTerrain, Tool, WaterLevel,
    };
}

/// The system sets of the plugins, run in this order in `Update`.
#[derive(SystemSet, Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum HexTerrainSystems {
    /// Applies a loaded, hot-reloaded or switched map to [`HexMap`].
    Map,
    /// Decides the wanted chunks around agents, starts tasks, retires far chunks and despawns
    /// their children a budget a frame.
    Stream,
    /// Inserts finished chunk meshes and their [`ChunkContent`] under the per-frame budget.
    Insert,
    /// Spawns and despawns the chunks' children from their [`ChunkContent`]: water surfaces
    /// ([`HexWaterPlugin`]) and props ([`HexPropsPlugin`]).
    Children,
    /// Keeps the [`TileStates`] window on the map and around the loaded chunks.
    Tiles,
    /// Walks [`TileWalk`]s and keeps [`OnTile`] entities on the surface of their tiles
    /// ([`HexPlacementPlugin`]).
    Place,
    /// Updates the terrain material (hot reload, its settings, the tile state style, the water's
    /// look, the tile state texture), gives new chunk meshes their material, and lights the
    /// terrain cameras.
    Render,
}

/// The terrain plugins: [`HexMapPlugin`] (the [`HexMap`] resource, map assets, switching),
/// [`HexStreamingPlugin`] (chunks around agents), [`HexTileStatePlugin`] (per-tile game state:
/// fog of war, territory, lenses, highlights), [`HexWaterPlugin`] (the water surface's
/// entities), [`HexPropsPlugin`] (trees, rocks, reeds), [`HexPlacementPlugin`] (units and cities on tiles), [`HexEditorPlugin`] (the world
/// builder: edit, undo, redo, save), with the `picking` feature
/// `HexPickingPlugin` and, with the `render` feature, `HexTerrainMaterialPlugin` (the terrain
/// and water material, which needs Bevy's `PbrPlugin`) and `HexLightPlugin` (sun, shadows, fog
/// for `HexTerrainCamera`s). Add it after `DefaultPlugins`. Each plugin owns its settings
/// resource, added with `init_resource`: insert yours before or after adding the plugins to
/// change them (a value inserted first is kept); disable one with
/// `HexTerrainPlugins::default().build().disable::<…>()`.
#[derive(Debug, Clone, Default)]
pub struct HexTerrainPlugins {
    /// The map to show.
    pub map: MapSource,
    /// The game's terrain ruleset, for every map file that names none
    /// ([`HexMapPlugin::ruleset`]).
    pub ruleset: Option<String>,
}

impl HexTerrainPlugins {
    /// The plugins showing a map (an asset path or a config).
    #[must_use]
    pub fn new(map: impl Into<MapSource>) -> Self {
        Self { map: map.into(), ruleset: None }
    }

    /// The same plugins with the game's terrain ruleset (the asset path of a `*.terrain.ron`
    /// file), taken by every map file that names none of its own ([`HexMapPlugin::ruleset`]).
    #[must_use]
    pub fn with_ruleset(self, path: impl Into<String>) -> Self {
        Self { ruleset: Some(path.into()), ..self }
    }

    /// The plugins showing the map config at an asset path (hot-reloaded when the asset server
    /// watches files).
    #[must_use]
    pub fn from_asset(path: impl Into<String>) -> Self {
        Self::new(MapSource::Asset(path.into()))
    }

    /// The plugins showing a config given in code.
    #[must_use]
    pub fn from_config(config: MapConfig) -> Self {
        Self::new(config)
    }
}

impl PluginGroup for HexTerrainPlugins {
    fn build(self) -> PluginGroupBuilder {
        let group = PluginGroupBuilder::start::<Self>()
            .add(HexMapPlugin { map: self.map, ruleset: self.ruleset })
            .add(HexStreamingPlugin)
            .add(HexTileStatePlugin)
            .add(HexWaterPlugin)
            .add(HexPropsPlugin)
            .add(HexPlacementPlugin)
            .add(HexEditorPlugin);
        #[cfg(feature = "picking")]
        let group = group.add(picking::HexPickingPlugin);
        #[cfg(feature = "render")]
        let group = group.add(material::HexTerrainMaterialPlugin).add(light::HexLightPlugin);
        group
    }
}
