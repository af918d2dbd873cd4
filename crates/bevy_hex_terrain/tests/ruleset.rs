//! A map file naming a terrain ruleset: the asset loader reads the ruleset beside it, a terrain
//! added to the ruleset file shows after a reload (the map file unchanged), and a broken
//! ruleset is refused by file, entry and field, keeping the terrain as it was.

mod common;

use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;
use common::*;

const CIV5: &str = include_str!("../assets/rulesets/civ5.terrain.ron");

/// Civilization V's ruleset with a savanna terrain between its plains and desert.
fn with_savanna() -> String {
    let savanna = r#"
        (id: "savanna", name: "Savanna",
            occurs: [(landform: [Flat, Hills], temperature: (0.5, 1.0), moisture: (0.0, 0.4), priority: 3)],
            traits: (movement: 1, yields: (food: 1.0, production: 1.0)),
            look: (color: (196, 170, 90), texture: 1)),
    ],
    features: ["#;
    CIV5.replacen("    ],\n    features: [", savanna, 1)
}

/// A folder of assets: `map.map.ron` naming `rules/own.terrain.ron`, Civilization V's ruleset;
/// the folder and the ruleset's path.
fn asset_dir(name: &str) -> (std::path::PathBuf, std::path::PathBuf) {
    let dir = std::env::temp_dir().join(format!("hex-terrain-{name}-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("rules")).unwrap();
    std::fs::write(
        dir.join("map.map.ron"),
        "(seed: 4, size: Bounded(x: 32, z: 20), chunk_size: (16, 10), climate: (enabled: true), \
         ruleset: Some(\"rules/own.terrain.ron\"))",
    )
    .unwrap();
    let ruleset = dir.join("rules/own.terrain.ron");
    std::fs::write(&ruleset, CIV5).unwrap();
    (dir, ruleset)
}

fn terrain_ids(app: &App) -> Vec<String> {
    let map = app.world().resource::<HexMap>();
    let terrain = map.terrain();
    let mut ids: Vec<String> = terrain
        .tiles()
        .filter_map(|t| terrain.tile_info(t).map(|i| i.terrain))
        .map(|t| terrain.ruleset().terrain(t.terrain).id.clone())
        .collect();
    ids.sort();
    ids.dedup();
    ids
}

#[test]
fn a_terrain_added_to_the_ruleset_file_shows_after_a_reload() {
    let (dir, ruleset) = asset_dir("ruleset");
    let mut app = app_with("map.map.ron".into(), HexStreamingSettings::default(), Some(&dir));
    keep::<HexMapError>(&mut app);
    run_until(&mut app, "the map under its ruleset", |app| {
        app.world().resource::<HexMap>().terrain().ruleset().name == "Civilization V" && ready(app)
    });
    let before = terrain_ids(&app);
    assert!(!before.contains(&"savanna".to_owned()) && before.contains(&"grassland".to_owned()), "{before:?}");
    let generation = app.world().resource::<HexMap>().generation();

    // The ruleset file gains a terrain; the map file is the same.
    std::fs::write(&ruleset, with_savanna()).unwrap();
    app.world().resource::<AssetServer>().reload("map.map.ron");
    run_until(&mut app, "the savanna", |app| terrain_ids(app).contains(&"savanna".to_owned()) && ready(app));
    assert!(app.world().resource::<HexMap>().generation() > generation);

    // A broken ruleset (two terrains at one priority on the same tiles): refused, naming the
    // ruleset file, the entry and the field; the savanna stays.
    std::fs::write(
        &ruleset,
        with_savanna().replace("moisture: (0.0, 0.4), priority: 3", "moisture: (0.0, 0.4), priority: 0"),
    )
    .unwrap();
    app.world().resource::<AssetServer>().reload("map.map.ron");
    run_until(&mut app, "the refusal", |app| !seen::<HexMapError>(app).is_empty());
    let error = seen::<HexMapError>(&app)[0].to_string();
    assert!(error.contains("own.terrain.ron") && error.contains("savanna") && error.contains("priority"), "{error}");
    for _ in 0..30 {
        app.update();
    }
    assert!(terrain_ids(&app).contains(&"savanna".to_owned()), "the old terrain kept");
}

/// With Bevy's file watcher on (as in the demo's build), saving the ruleset file alone reloads
/// the map: the ruleset is a dependency of the map file's asset.
#[test]
fn saving_the_ruleset_file_reloads_the_map() {
    use bevy::asset::AssetPlugin;
    let (dir, ruleset) = asset_dir("ruleset-watch");
    let mut app = App::new();
    let assets =
        AssetPlugin { file_path: dir.display().to_string(), watch_for_changes_override: Some(true), ..default() };
    app.add_plugins((MinimalPlugins, assets, TransformPlugin));
    let map: bevy_hex_terrain::MapSource = "map.map.ron".into();
    #[cfg(feature = "render")]
    app.add_plugins(HexTerrainPlugins::new(map).build().disable::<bevy_hex_terrain::HexTerrainMaterialPlugin>());
    #[cfg(not(feature = "render"))]
    app.add_plugins(HexTerrainPlugins::new(map));
    run_until(&mut app, "the map under its ruleset", |app| {
        app.world().resource::<HexMap>().terrain().ruleset().name == "Civilization V" && ready(app)
    });
    // Let the watcher settle on the files as they are, then save the ruleset with a savanna.
    for _ in 0..200 {
        app.update();
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
    std::fs::write(&ruleset, with_savanna()).unwrap();
    run_until(&mut app, "the savanna", |app| terrain_ids(app).contains(&"savanna".to_owned()) && ready(app));
}

/// The game's ruleset set on the plugins: a map file naming none takes it (named relative to
/// the map file, so the map saved keeps it); a map file naming its own keeps its own.
#[test]
fn the_plugins_ruleset_is_taken_by_maps_that_name_none() {
    let (dir, _) = asset_dir("game-ruleset");
    std::fs::write(
        dir.join("plain.map.ron"),
        "(seed: 4, size: Bounded(x: 32, z: 20), chunk_size: (16, 10), climate: (enabled: true))",
    )
    .unwrap();
    let fantasy = include_str!("../assets/rulesets/fantasy.terrain.ron");
    std::fs::create_dir_all(dir.join("game")).unwrap();
    std::fs::write(dir.join("game/realm.terrain.ron"), fantasy).unwrap();
    let realm = hex_terrain::TerrainRuleset::from_ron(fantasy).unwrap();
    let civ = hex_terrain::TerrainRuleset::from_ron(CIV5).unwrap();
    for (map, name, path) in
        [("plain.map.ron", &realm.name, "game/realm.terrain.ron"), ("map.map.ron", &civ.name, "rules/own.terrain.ron")]
    {
        let plugins = HexTerrainPlugins::from_asset(map).with_ruleset("game/realm.terrain.ron");
        let mut app = app_with_plugins(plugins, HexStreamingSettings::default(), Some(&dir));
        run_until(&mut app, "the map applied", |app| app.world().resource::<HexMap>().terrain().has_own_ruleset());
        let hex = app.world().resource::<HexMap>();
        assert_eq!(&hex.terrain().ruleset().name, name, "{map}");
        assert_eq!(hex.config().ruleset.as_deref(), Some(path), "{map}");
        // Every tile's terrain is one of that ruleset's.
        let ids = terrain_ids(&app);
        let ruleset = if map == "plain.map.ron" { &realm } else { &civ };
        assert!(ids.iter().all(|id| ruleset.terrain_id(id).is_some()), "{map}: {ids:?}");
    }
}
