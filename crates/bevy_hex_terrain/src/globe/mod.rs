//! A hex globe in Bevy: [`HexGlobePlugin`] loads a globe map file (a `*.map.ron` of size
//! `Globe`, hot-reloaded; a broken reload keeps the old globe and says why in a
//! [`HexMapError`]; another globe with [`LoadHexMap`]; [`TerrainReady`] once a globe's chunks are
//! in, [`TerrainSettled`] each time they all show it) into the [`HexGlobe`] resource, streams its
//! chunks around every [`HexTerrainAgent`] by angle, to the agent's horizon (the far side is
//! neither built nor drawn; chunks far from every agent coarse, [`HexGlobeSettings`]), meshes on
//! Bevy's async compute pool; and [`GlobeCamera`] orbits it. The globe's center is the world's
//! origin, its axis the world's `y`.
//!
//! [`OnGlobeTile`] keeps units and cities standing on their tiles (their up the globe's up there)
//! and [`GlobeTileWalk`] walks them along a path over the sphere, pentagons included.
//!
//! With the `picking` feature the globe is a `bevy_picking` backend: pointer events on its
//! chunks carry a [`HexGlobePick`] (the tile, pentagons as any other), and [`HoveredGlobeTile`]
//! holds the tile under the mouse.
//!
//! [`GlobeTileStates`] holds the game's per-tile state (fog of war, owners, the lens,
//! highlights), which the globe's material ([`HexGlobeMaterial`], with the `render` feature)
//! draws over the vertex colors (the biome colors with a climate, else the kinds') with
//! `StandardMaterial`'s lighting and the tiles' outlines, styled by [`HexTileStateStyle`]. The
//! same material draws the sea as water where the ground lies below the sea's sphere (the flat
//! map's [`HexWaterSettings`](crate::HexWaterSettings): depth colors over the sea floor, foam
//! along the shore, waves that catch the sun) and, with
//! [`HexTerrainMaterialSettings::textures`](crate::HexTerrainMaterialSettings::textures) on,
//! each tile's terrain texture layer over its color.
//!
//! Trees, rocks and reeds stand on the globe's tiles as [`HexGlobeProp`]s (the flat map's rule
//! and meshes, [`HexPropSettings`]), hidden on unexplored tiles under fog of war.
//! [`HexGlobeEditorPlugin`] is the world builder on a globe: `HexMapEdit<GlobeStroke>` messages
//! edit, undo, redo and save it, and only the chunks an operation changed are built again.

mod camera;
mod editor;
#[cfg(feature = "render")]
mod material;
#[cfg(feature = "minimap")]
mod minimap;
#[cfg(feature = "picking")]
mod picking;
mod placement;
mod props;
mod stream;
mod tiles;

use std::sync::Arc;

use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use hex_terrain::{GlobeChunk, GlobeTerrain, MapConfig};

pub use camera::GlobeCamera;
pub use editor::{HexGlobeEditor, HexGlobeEditorPlugin};
#[cfg(feature = "render")]
pub use material::{GlobeParams, HexGlobeExtension, HexGlobeMaterial};
#[cfg(feature = "minimap")]
pub use minimap::{GlobeMinimapNavigate, GlobeMinimapPicture, HexGlobeMinimap, HexGlobeMinimapPlugin};
#[cfg(feature = "picking")]
pub use picking::{HexGlobePick, HoveredGlobeTile};
pub use placement::{GlobeTileWalk, GlobeWalkEnded, OnGlobeTile};
pub use props::HexGlobeProp;
pub use stream::{GLOBE_ROW, GlobeStreamer, HexGlobeChunk, HexGlobeSettings, NEAR_ANGLE, globe_horizon};
pub use tiles::GlobeTileStates;

use crate::asset::{HexMapAsset, HexMapLoader};
use crate::map::{HexMapError, load_failure};
use crate::tiles::{HexTileStateStyle, HexTileStateSystems};
use crate::{HexPropSettings, HexTerrainSystems, LoadHexMap, MapSource, TerrainReady, TerrainSettled};

/// The globe shown: its compiled terrain and a generation that grows with each config applied.
/// While its file loads, no globe (nothing is streamed).
#[derive(Resource, Debug, Clone, Default, Reflect)]
#[reflect(Resource, Default)]
pub struct HexGlobe {
    /// The compiled globe (not reflected: the core's stages hold no reflected state).
    #[reflect(ignore)]
    globe: Option<Arc<GlobeTerrain>>,
    generation: u64,
    /// Grows when another globe takes effect (not over hot reloads and edits).
    map_id: u64,
    /// The generation of the config applied last: every chunk's mesh is out of date before it.
    base_generation: u64,
    /// The chunks edits changed since, with the generation of the last edit that changed each.
    #[reflect(ignore)]
    edited_chunks: HashMap<GlobeChunk, u64>,
    /// The file the globe comes from, if any.
    #[reflect(ignore)]
    handle: Option<Handle<HexMapAsset>>,
    /// Whether the file followed is new (its first config takes effect as another globe).
    followed_anew: bool,
    /// Whether the file was followed this frame (it may be loaded already: no event comes).
    just_followed: bool,
}

impl HexGlobe {
    /// The compiled globe; `None` while its file loads.
    #[must_use]
    pub fn globe(&self) -> Option<&Arc<GlobeTerrain>> {
        self.globe.as_ref()
    }

    /// Grows by one each time a config is applied (the first, a hot reload) and each time the
    /// globe is edited ([`HexGlobeEditorPlugin`]).
    #[must_use]
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// The generation since which `chunk` looks as it does now: the last config applied, or the
    /// last edit that changed the chunk after it. A mesh built for it or later shows the globe.
    #[must_use]
    pub fn chunk_generation(&self, chunk: GlobeChunk) -> u64 {
        self.edited_chunks.get(&chunk).map_or(self.base_generation, |&g| g.max(self.base_generation))
    }

    /// Whether a mesh of `chunk` built for globe generation `built` shows the globe now.
    #[must_use]
    pub fn is_current(&self, chunk: GlobeChunk, built: Option<u64>) -> bool {
        built.is_some_and(|g| g >= self.chunk_generation(chunk) && g <= self.generation)
    }

    /// Changes each time another globe takes effect (the plugin's first, [`LoadHexMap`]); stays
    /// the same over edits and hot reloads of the same file. 0 before the first.
    #[must_use]
    pub fn map_id(&self) -> u64 {
        self.map_id
    }

    /// Applies a config as another globe (a new [`HexGlobe::map_id`]): compiles it and makes it
    /// the globe (every chunk out of date), or keeps the globe as it was.
    ///
    /// # Errors
    /// The config's first invalid field (`size` for a flat map's config).
    pub fn apply(&mut self, config: MapConfig) -> Result<(), hex_terrain::ConfigError> {
        self.set(config, true)
    }

    /// Applies a config, as another globe or as a hot reload of this one.
    fn set(&mut self, config: MapConfig, another: bool) -> Result<(), hex_terrain::ConfigError> {
        self.globe = Some(Arc::new(GlobeTerrain::new(config)?));
        self.generation += 1;
        self.map_id += u64::from(another);
        self.base_generation = self.generation;
        self.edited_chunks.clear();
        Ok(())
    }

    /// Shows an edit of the globe: a new generation in which only `chunks` are out of date.
    pub(crate) fn edit(&mut self, globe: GlobeTerrain, chunks: &[GlobeChunk]) {
        self.globe = Some(Arc::new(globe));
        self.generation += 1;
        for &chunk in chunks {
            self.edited_chunks.insert(chunk, self.generation);
        }
    }
}

/// Shows a hex globe: the [`HexGlobe`] resource from a map file or a config, its chunks streamed
/// around every [`HexTerrainAgent`](crate::HexTerrainAgent) to the agent's horizon
/// ([`GlobeStreamer`], [`HexGlobeChunk`]), the [`GlobeCamera`] orbit controls, and the
/// [`GlobeTileStates`] drawn by the globe's material (when Bevy's `PbrPlugin` is there) in the
/// [`HexTileStateStyle`] (settings resources a game may insert first). Its systems run in
/// [`HexTerrainSystems`]: applying the file and following it with the tile states in `Map` (the
/// camera moves there too, before streaming), streaming in `Stream`, inserting meshes in
/// `Insert`, the material in `Render`. Not a part of
/// [`HexTerrainPlugins`](crate::HexTerrainPlugins): a globe game adds it instead. Like the flat
/// map's plugin it answers [`LoadHexMap`] (another globe; the globe shown stays until the new
/// one is valid) and sends [`TerrainReady`] (per [`HexGlobe::map_id`]) and [`TerrainSettled`];
/// while the first file loads there is no globe and nothing is streamed (the flat map's
/// placeholder streams nothing either).
///
/// ```no_run
/// use bevy::prelude::*;
/// use bevy_hex_terrain::prelude::*;
///
/// App::new()
///     .add_plugins((DefaultPlugins, HexGlobePlugin::from_asset("maps/globe/continents.map.ron")))
///     .add_systems(Startup, |mut commands: Commands| {
///         // An orbit camera that keeps the globe streamed to its horizon.
///         commands.spawn((GlobeCamera::default(), HexTerrainAgent::default()));
///         commands.spawn((DirectionalLight::default(), Transform::from_xyz(1.0, 0.5, 1.0).looking_at(Vec3::ZERO, Vec3::Y)));
///     })
///     .run();
/// ```
#[derive(Debug, Clone)]
pub struct HexGlobePlugin {
    /// The globe to show: a map file's asset path or a config of size `Globe`.
    pub globe: MapSource,
}

impl HexGlobePlugin {
    /// The plugin showing the globe of the map file at an asset path (hot-reloaded when the
    /// asset server watches files).
    #[must_use]
    pub fn from_asset(path: impl Into<String>) -> Self {
        Self { globe: MapSource::Asset(path.into()) }
    }

    /// The plugin showing a globe config given in code.
    #[must_use]
    pub fn from_config(config: MapConfig) -> Self {
        Self { globe: MapSource::Config(Box::new(config)) }
    }
}

impl Plugin for HexGlobePlugin {
    fn build(&self, app: &mut App) {
        if !app.world().contains_resource::<Assets<HexMapAsset>>() {
            app.init_asset::<HexMapAsset>().init_asset_loader::<HexMapLoader>();
        }
        if !app.world().contains_resource::<Assets<Mesh>>() {
            app.init_asset::<Mesh>();
        }
        app.init_resource::<HexGlobe>()
            .init_resource::<GlobeStreamer>()
            .init_resource::<HexGlobeSettings>()
            .register_type::<HexGlobeSettings>()
            .init_resource::<GlobeTileStates>()
            .init_resource::<HexTileStateStyle>()
            .init_resource::<HexPropSettings>()
            .init_resource::<crate::water::HexWaterSettings>()
            .register_type::<crate::water::HexWaterSettings>()
            .register_type::<GlobeTileStates>()
            .register_type::<HexPropSettings>()
            .register_type::<HexGlobeProp>()
            .register_type::<HexTileStateStyle>()
            .add_message::<HexMapError>()
            .add_message::<LoadHexMap>()
            .add_message::<TerrainReady>()
            .add_message::<TerrainSettled>()
            .register_type::<HexGlobe>()
            .register_type::<GlobeCamera>()
            .register_type::<HexGlobeChunk>()
            .register_type::<OnGlobeTile>()
            .register_type::<GlobeTileWalk>()
            .configure_sets(
                Update,
                (HexTerrainSystems::Map, HexTerrainSystems::Stream, HexTerrainSystems::Insert).chain(),
            )
            .configure_sets(Update, HexTerrainSystems::Place.after(HexTerrainSystems::Map))
            .add_systems(
                Update,
                (
                    (load_requested, apply_asset, tiles::follow_globe, camera::place)
                        .chain()
                        .in_set(HexTerrainSystems::Map),
                    stream::stream.in_set(HexTerrainSystems::Stream),
                    (stream::insert, props::sync_props).chain().in_set(HexTerrainSystems::Insert),
                    (placement::walk, placement::place).chain().in_set(HexTerrainSystems::Place),
                ),
            )
            .add_systems(PostUpdate, tiles::clear_journal.in_set(HexTileStateSystems::Pack));
        // The states' rows packed for the GPU after `Update` (for the material, headless too, so
        // a benchmark measures what a game pays).
        #[cfg(feature = "render")]
        app.init_resource::<material::GlobeStateUpload>()
            .add_systems(PostUpdate, material::pack_upload.in_set(HexTileStateSystems::Pack));
        // Props on unexplored tiles hidden after every game system's writes of the frame, before
        // their list starts again.
        #[cfg(feature = "render")]
        app.add_systems(
            PostUpdate,
            props::hide_unexplored.in_set(HexTileStateSystems::Pack).before(tiles::clear_journal),
        );
        #[cfg(feature = "render")]
        if app.is_plugin_added::<bevy::pbr::PbrPlugin>() {
            material::build(app);
            app.add_systems(Startup, crate::props::create_assets);
        }
        #[cfg(feature = "picking")]
        {
            app.add_systems(Update, camera::orbit.before(camera::place).in_set(HexTerrainSystems::Map));
            picking::build(app);
        }
        match &self.globe {
            MapSource::Config(config) => {
                let config = (**config).clone();
                app.add_systems(
                    PreStartup,
                    move |mut globe: ResMut<HexGlobe>, mut errors: MessageWriter<HexMapError>| {
                        if let Err(e) = globe.apply(config.clone()) {
                            refuse(&mut errors, HexMapError::invalid("globe config", &e));
                        }
                    },
                );
            }
            MapSource::Asset(path) => {
                let path = path.clone();
                app.add_systems(PreStartup, move |server: Res<AssetServer>, mut globe: ResMut<HexGlobe>| {
                    globe.follow(server.load(path.clone()));
                });
            }
        }
    }
}

/// Reports a globe that could not be applied; the globe stays as it was.
fn refuse(errors: &mut MessageWriter<HexMapError>, error: HexMapError) {
    error!("{error}");
    errors.write(error);
}

impl HexGlobe {
    /// Follows a map file: its first config applied takes effect as another globe.
    fn follow(&mut self, handle: Handle<HexMapAsset>) {
        self.handle = Some(handle);
        self.followed_anew = true;
        self.just_followed = true;
    }
}

/// Handles [`LoadHexMap`] (the last of a frame): a config applies at once as another globe, a
/// file is followed and applied by [`apply_asset`] once loaded. The globe shown stays until the
/// new one is valid; a bad one is a [`HexMapError`].
fn load_requested(
    mut requests: MessageReader<LoadHexMap>,
    server: Res<AssetServer>,
    mut globe: ResMut<HexGlobe>,
    mut errors: MessageWriter<HexMapError>,
) {
    let Some(LoadHexMap(source)) = requests.read().last() else { return };
    match source {
        MapSource::Asset(path) => globe.follow(server.load(path.clone())),
        MapSource::Config(config) => match globe.apply((**config).clone()) {
            Ok(()) => globe.handle = None,
            Err(e) => refuse(&mut errors, HexMapError::invalid("globe config", &e)),
        },
    }
}

/// Applies the globe's map file when it loads or changes (a file newly followed as another
/// globe, its changes as hot reloads); a file that does not load or is not a valid globe is
/// reported and the globe kept.
fn apply_asset(
    mut globe: ResMut<HexGlobe>,
    assets: Res<Assets<HexMapAsset>>,
    mut events: MessageReader<AssetEvent<HexMapAsset>>,
    mut failures: MessageReader<bevy::asset::AssetLoadFailedEvent<HexMapAsset>>,
    mut errors: MessageWriter<HexMapError>,
    mut last_failure: Local<Option<HexMapError>>,
) {
    let Some(handle) = globe.handle.clone() else {
        events.clear();
        failures.clear();
        return;
    };
    let name = handle.path().map_or_else(|| "globe".into(), |p| format!("globe {p}"));
    for failure in failures.read().filter(|f| f.id == handle.id()) {
        // Malformed RON with its line and column, a bad field by name: as a flat map's file,
        // and the same failure said once.
        let error = load_failure(failure);
        if last_failure.as_ref() != Some(&error) {
            refuse(&mut errors, error.clone());
            *last_failure = Some(error);
        }
    }
    let changed = events.read().any(|e| match e {
        AssetEvent::LoadedWithDependencies { id } | AssetEvent::Modified { id } => *id == handle.id(),
        _ => false,
    });
    // A file newly followed may be loaded already (no event comes): applied at once.
    let just_followed = globe.just_followed;
    if just_followed {
        globe.just_followed = false;
    }
    if !changed && !just_followed {
        return;
    }
    let Some(asset) = assets.get(&handle) else { return };
    *last_failure = None;
    let another = globe.followed_anew;
    if !another && globe.globe.as_ref().is_some_and(|g| *g.config() == asset.config) {
        return;
    }
    match globe.set(asset.config.clone(), another) {
        Ok(()) => {
            globe.followed_anew = false;
            info!("hex terrain: globe {:?} applied", asset.config.name);
        }
        Err(e) => {
            // A new file that is no globe: the globe shown stays, and the file is still followed
            // (a fixed file takes effect as another globe).
            refuse(&mut errors, HexMapError::invalid(&name, &e));
        }
    }
}

/// The chunks of a globe within `angle` radians of `direction` (a unit vector from its center).
fn chunks_within(globe: &GlobeTerrain, direction: Vec3, angle: f32) -> Vec<GlobeChunk> {
    globe.chunks_within(direction.as_dvec3().to_array(), f64::from(angle))
}
