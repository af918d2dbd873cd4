//! [`HexMapPlugin`]: the [`HexMap`] resource, map assets and their hot reload, and switching
//! maps with [`LoadHexMap`]. A map that cannot be applied is reported as [`HexMapError`] and the
//! terrain stays as it was.

use bevy::asset::AssetLoadFailedEvent;
use bevy::prelude::*;
use std::sync::Arc;

use hex_terrain::{HeightImage, MapConfig, Terrain};

use super::MapSource;
use super::{HexMap, HexMapError};
use crate::HexTerrainSystems;
use crate::asset::{HexMapAsset, HexMapLoader, HexMapLoaderError};

/// The map asset the plugin follows, when the map comes from a file. Switch maps with
/// [`LoadHexMap`]; this resource only says which asset is followed.
#[derive(Resource, Debug, Clone, Default, Reflect)]
#[reflect(Resource, Debug, Default)]
pub struct HexMapHandle(Option<Handle<HexMapAsset>>);

impl HexMapHandle {
    /// The followed map asset, if the map comes from a file.
    #[must_use]
    pub fn handle(&self) -> Option<&Handle<HexMapAsset>> {
        self.0.as_ref()
    }
}

/// Asks the plugin to show another map: a map file (applied once loaded, then hot-reloaded) or
/// a config. The current terrain stays until the new map is valid; a bad one is reported as
/// [`HexMapError`].
#[derive(Message, Debug, Clone, Reflect)]
pub struct LoadHexMap(pub MapSource);

/// The map: [`HexMap`], the `*.map.ron` asset loader, hot reload, [`LoadHexMap`] and
/// [`HexMapError`], and the order of [`HexTerrainSystems`].
#[derive(Debug, Clone, Default)]
pub struct HexMapPlugin {
    /// The map to show first.
    pub map: MapSource,
    /// The game's terrain ruleset: the asset path of a `*.terrain.ron` file every map file
    /// that names no ruleset of its own takes ([`MapConfig::ruleset`]; the one a map file names
    /// wins). Read with the map file, as its dependency: editing it reloads the map. `None`
    /// (the default): such maps keep the 13 biomes of their biome table. A config given in code
    /// names its ruleset itself.
    pub ruleset: Option<String>,
}

impl Plugin for HexMapPlugin {
    fn build(&self, app: &mut App) {
        if !app.is_plugin_added::<AssetPlugin>() {
            panic!(
                "HexMapPlugin needs Bevy's AssetPlugin: add DefaultPlugins, or MinimalPlugins with \
                 AssetPlugin::default(), before the hex terrain plugins"
            );
        }
        let (map, path) = match &self.map {
            MapSource::Config(config) => match HexMap::new((**config).clone()) {
                Ok(map) => (map, None),
                Err(e) => panic!("HexMapPlugin: the map config given in code is invalid: {e}"),
            },
            MapSource::Asset(path) => {
                let mut map = HexMap::new(MapConfig::default()).unwrap_or_else(|e| panic!("default map: {e}"));
                map.set_waiting(true);
                (map, Some(path.clone()))
            }
        };
        app.init_asset::<HexMapAsset>()
            .register_asset_loader(HexMapLoader { ruleset: self.ruleset.clone() })
            .insert_resource(map)
            .init_resource::<HexMapHandle>()
            .add_message::<HexMapError>()
            .add_message::<LoadHexMap>()
            .add_message::<super::SetUpGame>()
            .add_message::<super::GameSetUp>()
            .register_type::<HexMapError>()
            .register_type::<LoadHexMap>()
            .register_type::<super::SetUpGame>()
            .register_type::<super::GameSetUp>()
            .register_type::<HexMap>()
            .register_type::<HexMapHandle>()
            // A new config must be in place before chunks are requested against it, and a
            // chunk must be requested before its mesh can be inserted.
            .configure_sets(
                Update,
                (
                    HexTerrainSystems::Map,
                    HexTerrainSystems::Stream,
                    HexTerrainSystems::Insert,
                    HexTerrainSystems::Children,
                    HexTerrainSystems::Tiles,
                    HexTerrainSystems::Place,
                    HexTerrainSystems::Render,
                )
                    .chain(),
            )
            // A request may name an asset that is already loaded: it is applied in the same frame.
            .add_systems(
                Update,
                (load_requested, apply_asset, super::setup::set_up_requested)
                    .chain()
                    .in_set(super::MapAssets)
                    .in_set(HexTerrainSystems::Map),
            );
        if let Some(path) = path {
            app.add_systems(PreStartup, move |server: Res<AssetServer>, mut handle: ResMut<HexMapHandle>| {
                handle.0 = Some(server.load(path.clone()));
            });
        }
    }
}

/// Reports a map that could not be applied; the terrain stays as it was.
fn refuse(errors: &mut MessageWriter<HexMapError>, error: HexMapError) {
    error!("{error}");
    errors.write(error);
}

/// The error of a failed map file load: the loader's own error when it is one, typed.
pub(crate) fn load_failure(failure: &AssetLoadFailedEvent<HexMapAsset>) -> HexMapError {
    let map = format!("map {}", failure.path);
    if let bevy::asset::AssetLoadError::AssetLoaderError(e) = &failure.error
        && let Some(e) = e.error().downcast_ref::<HexMapLoaderError>()
    {
        return match e {
            HexMapLoaderError::Map(e) => HexMapError::load(&map, e),
            other => HexMapError::Unreadable { map, message: other.to_string() },
        };
    }
    // The message, without the backtrace Bevy appends when `RUST_BACKTRACE` is set.
    let message = failure.error.to_string().lines().next().unwrap_or_default().to_owned();
    HexMapError::Unreadable { map, message }
}

/// Handles [`LoadHexMap`]: a config applies at once, a file is loaded and applied by
/// [`apply_asset`] when ready.
fn load_requested(
    mut requests: MessageReader<LoadHexMap>,
    server: Res<AssetServer>,
    mut handle: ResMut<HexMapHandle>,
    mut map: ResMut<HexMap>,
    mut errors: MessageWriter<HexMapError>,
) {
    // Only the last request of a frame counts.
    let Some(LoadHexMap(source)) = requests.read().last() else { return };
    match source {
        MapSource::Asset(path) => handle.0 = Some(server.load(path.clone())),
        // A config naming the ruleset of the map shown (R's new seed of a map with its own
        // terrain) keeps that ruleset; another path is read from the file system.
        MapSource::Config(config) => {
            let made = if config.ruleset.is_some() && map.config().ruleset == config.ruleset {
                let ruleset = Arc::new(map.terrain().ruleset().clone());
                Terrain::with_sources((**config).clone(), None, Some(ruleset))
            } else {
                Terrain::new((**config).clone())
            };
            match made {
                Ok(terrain) => {
                    handle.0 = None;
                    map.replace(terrain);
                }
                Err(e) => refuse(&mut errors, HexMapError::invalid("map config", &e)),
            }
        }
    }
}

/// Applies a loaded, hot-reloaded or newly followed map asset; reports a bad one, keeping the
/// old terrain. [`HexMap`] is written only when a map is applied.
///
/// Bevy announces one reload twice (`Modified`, then `LoadedWithDependencies`), and retries a
/// failed reload once: the same content applies once, and the same failure of the same file is
/// reported once (until the file next loads).
/// What `apply_asset` remembers between frames.
#[derive(Default)]
struct Applied {
    /// The asset last refused (applied again only when it changes).
    refused: Option<AssetId<HexMapAsset>>,
    /// The failure last reported (reported again only when it differs).
    last_failure: Option<HexMapError>,
}

fn apply_asset(
    mut map: ResMut<HexMap>,
    handle: Res<HexMapHandle>,
    assets: Res<Assets<HexMapAsset>>,
    mut events: MessageReader<AssetEvent<HexMapAsset>>,
    mut failures: MessageReader<AssetLoadFailedEvent<HexMapAsset>>,
    mut errors: MessageWriter<HexMapError>,
    mut memory: Local<Applied>,
) {
    let Applied { refused, last_failure } = &mut *memory;
    let Some(handle) = &handle.0 else {
        events.clear();
        failures.clear();
        return;
    };
    for failure in failures.read() {
        let error = load_failure(failure);
        if failure.id == handle.id() && last_failure.as_ref() != Some(&error) {
            refuse(&mut errors, error.clone());
            *last_failure = Some(error);
        }
    }
    let changed = events.read().any(|e| match e {
        AssetEvent::LoadedWithDependencies { id } | AssetEvent::Modified { id } => *id == handle.id(),
        _ => false,
    });
    // A newly followed asset that was loaded before sends no event: apply it now (once, if it
    // is refused).
    let followed = map.applied.as_ref().map(|(id, _)| *id);
    let new = followed != Some(handle.id()) && *refused != Some(handle.id());
    if !(changed || new) {
        return;
    }
    let Some(asset) = assets.get(handle) else { return };
    *last_failure = None;
    // A hot reload of a file without a setup keeps the game set up on the map (`SetUpGame`).
    let mut config = asset.config.clone();
    if !new && config.setup.is_none() {
        config.setup.clone_from(&map.asked_setup);
    }
    let same_image = |applied: &Option<Arc<HeightImage>>| match (applied, &asset.image) {
        (None, None) => true,
        (Some(a), Some(b)) => Arc::ptr_eq(a, b),
        _ => false,
    };
    if !new
        && config == *map.config()
        && asset.appearance_fallback == map.appearance_fallback
        && map.applied.as_ref().is_some_and(|(_, image)| same_image(image))
        && asset.ruleset.as_deref().is_none_or(|r| r == map.terrain().ruleset())
    {
        return;
    }
    let asked = map.asked_setup.clone().filter(|_| !new && asset.config.setup.is_none());
    match Terrain::with_sources(config, asset.image.clone(), asset.ruleset.clone()) {
        Ok(terrain) => {
            info!("hex terrain: map {:?} applied", asset.config.name);
            // A newly followed file (the plugin's first replacing the placeholder, or another) is
            // another map; a hot reload keeps the map id.
            if new {
                map.replace(terrain);
            } else {
                map.reload(terrain);
            }
            map.appearance_fallback = asset.appearance_fallback;
            map.applied = Some((handle.id(), asset.image.clone()));
            map.asked_setup = asked;
        }
        Err(e) => {
            *refused = Some(handle.id());
            let map = handle.path().map_or_else(|| "map".into(), |p| format!("map {p}"));
            refuse(&mut errors, HexMapError::invalid(&map, &e));
        }
    }
}
