//! Every plugin's settings resource is added with `init_resource`: a value a user inserts
//! before adding the plugins is kept (one way to set them, the way Bevy's own plugins do).
//! `HexMinimapSettings` is checked the same way in `minimap.rs`, whose app has what the minimap
//! needs.

use bevy::asset::AssetPlugin;
use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;
use bevy_hex_terrain::{HexTerrainPlugins, HexTileStateSettings};

/// A headless app with the terrain plugins (no material), after `before` ran on it before they
/// were added, updated once.
fn app_after(before: impl FnOnce(&mut App)) -> App {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, AssetPlugin::default(), TransformPlugin));
    before(&mut app);
    let plugins = HexTerrainPlugins::new(MapConfig::default());
    #[cfg(feature = "render")]
    app.add_plugins(plugins.build().disable::<HexTerrainMaterialPlugin>());
    #[cfg(not(feature = "render"))]
    app.add_plugins(plugins);
    app.update();
    app
}

#[test]
fn settings_inserted_before_the_plugins_are_kept() {
    let streaming = HexStreamingSettings { load_radius: 5, prefetch: 3, max_tasks_in_flight: 7, ..default() };
    let tiles = HexTileStateSettings { max_window: UVec2::new(64, 32) };
    let water = HexWaterSettings { enabled: false, ..default() };
    let props = HexPropSettings { max_per_chunk: 17, ..default() };
    #[cfg(feature = "picking")]
    let picking = bevy_hex_terrain::HexPickingSettings { max_distance: 123.0, require_markers: true, ..default() };
    #[cfg(feature = "render")]
    let lighting = HexLightSettings { shadows: false, ..default() };
    let app = app_after(|app| {
        app.insert_resource(streaming.clone())
            .insert_resource(tiles.clone())
            .insert_resource(water)
            .insert_resource(props);
        #[cfg(feature = "picking")]
        app.insert_resource(picking.clone());
        #[cfg(feature = "render")]
        app.insert_resource(lighting.clone());
    });
    let world = app.world();
    assert_eq!(world.resource::<HexStreamingSettings>(), &streaming);
    assert_eq!(world.resource::<HexTileStateSettings>(), &tiles);
    assert_eq!(world.resource::<HexWaterSettings>(), &water);
    assert_eq!(world.resource::<HexPropSettings>(), &props);
    #[cfg(feature = "picking")]
    assert_eq!(world.resource::<bevy_hex_terrain::HexPickingSettings>(), &picking);
    #[cfg(feature = "render")]
    assert_eq!(world.resource::<HexLightSettings>(), &lighting);
}

/// Without a value inserted, each plugin adds its default.
#[test]
fn each_plugin_adds_its_default_settings() {
    let app = app_after(|_| {});
    let world = app.world();
    assert_eq!(world.resource::<HexStreamingSettings>(), &HexStreamingSettings::default());
    assert_eq!(world.resource::<HexTileStateSettings>(), &HexTileStateSettings::default());
}

/// The plugins' public resources are reflected and registered (an inspector lists them).
#[test]
fn public_resources_are_reflected_and_registered() {
    use bevy::reflect::Reflect;
    let app = app_after(|_| {});
    let registry = app.world().resource::<AppTypeRegistry>().read();
    let world = app.world();
    let reflected: [&dyn Reflect; 6] = [
        world.resource::<HexMap>(),
        world.resource::<ChunkStreamer>(),
        world.resource::<HexStreamingStats>(),
        world.resource::<HexEditor>(),
        world.resource::<HexStreamingSettings>(),
        world.resource::<TileStates>(),
    ];
    for value in reflected {
        let path = value.reflect_type_path();
        assert!(registry.get_with_type_path(path).is_some(), "{path} is not registered");
    }
    // Every other resource of the crate a headless app has: registered, as a resource.
    fn registered<T: Resource>(world: &World, registry: &bevy::reflect::TypeRegistry) {
        let name = std::any::type_name::<T>();
        assert!(world.contains_resource::<T>(), "{name} is not in the app");
        let registration = registry.get(std::any::TypeId::of::<T>());
        assert!(
            registration.is_some_and(|r| r.data::<bevy::ecs::reflect::ReflectResource>().is_some()),
            "{name} is not a registered, reflected resource"
        );
    }
    registered::<bevy_hex_terrain::HexMapHandle>(world, &registry);
    registered::<bevy_hex_terrain::HexTileStateStats>(world, &registry);
    registered::<HexTileStateStyle>(world, &registry);
    registered::<HexTileStateSettings>(world, &registry);
    registered::<bevy_hex_terrain::TileStateUpload>(world, &registry);
    registered::<HexWaterSettings>(world, &registry);
    registered::<HexPropSettings>(world, &registry);
    registered::<bevy_hex_terrain::HexPropStats>(world, &registry);
    #[cfg(feature = "picking")]
    {
        registered::<HexPickingSettings>(world, &registry);
        registered::<HoveredTile>(world, &registry);
    }
}
