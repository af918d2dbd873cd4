//! A map's life as "once per map" code sees it: the placeholder shown while the map file loads
//! has a `map_id` of its own and is never `TerrainReady`; `TerrainReady` comes once per map,
//! `TerrainSettled` each time the terrain settles (edits, hot reloads); tile states written while
//! the file loads are kept on the map's tiles; and a system after `HexTerrainSystems::Map` writes
//! the new map's tiles on the frame it applies.

mod common;

use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;
use common::*;

fn asset_dir(name: &str, text: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("hexterrain-map-life-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("game.map.ron"), text).unwrap();
    dir
}

/// Updates until the terrain of the map now shown is settled.
fn settle(app: &mut App, what: &str) {
    run_until(app, what, |app| !app.world().resource::<HexMap>().is_waiting_for_asset() && ready(app));
}

#[test]
fn terrain_ready_comes_once_per_map_and_settled_each_time() {
    let dir = asset_dir("ready", "(seed: 5, size: Bounded(x: 24, z: 16), chunk_size: (8, 8))");
    let mut app = app_with(MapSource::Asset("game.map.ron".into()), settings(1), Some(&dir));
    keep::<TerrainReady>(&mut app);
    keep::<TerrainSettled>(&mut app);
    keep::<HexMapEdited>(&mut app);
    let placeholder = app.world().resource::<HexMap>().map_id();
    assert!(app.world().resource::<HexMap>().is_waiting_for_asset());
    settle(&mut app, "the map file");
    let map_id = app.world().resource::<HexMap>().map_id();
    assert_ne!(map_id, placeholder, "the placeholder is not the map");
    let generation = app.world().resource::<HexMap>().generation();
    assert_eq!(seen::<TerrainReady>(&app), [TerrainReady { map_id, generation }]);
    assert_eq!(seen::<TerrainSettled>(&app).last(), Some(&TerrainSettled { generation }));

    // An edit settles again: not ready again.
    let tile = app.world().resource::<HexMap>().terrain().tile_from_offset([6, 6]);
    app.world_mut().write_message(HexMapEdit::Stroke(Stroke { tool: Tool::Raise(0.25), brush: Brush::Range(1), tile }));
    run_until(&mut app, "the edit", |app| !seen::<HexMapEdited>(app).is_empty() && ready(app));
    let edited = app.world().resource::<HexMap>().generation();
    assert!(edited > generation);
    assert_eq!(seen::<TerrainReady>(&app).len(), 1, "an edit is the same map");
    assert_eq!(seen::<TerrainSettled>(&app).last(), Some(&TerrainSettled { generation: edited }));

    // A hot reload of the file settles again: not ready again.
    reload_asset(&mut app, |config| {
        config.seed = 6;
    });
    run_until(&mut app, "the reload", |app| app.world().resource::<HexMap>().config().seed == 6 && ready(app));
    let reloaded = app.world().resource::<HexMap>().generation();
    assert_eq!(app.world().resource::<HexMap>().map_id(), map_id);
    assert_eq!(seen::<TerrainReady>(&app).len(), 1, "a hot reload is the same map");
    assert_eq!(seen::<TerrainSettled>(&app).last(), Some(&TerrainSettled { generation: reloaded }));

    // Another map is ready once.
    let other = MapConfig { seed: 9, size: MapSize::Bounded { x: 16, z: 16 }, chunk_size: (8, 8), ..default() };
    app.world_mut().write_message(LoadHexMap(other.into()));
    run_until(&mut app, "the other map", |app| app.world().resource::<HexMap>().map_id() != map_id && ready(app));
    for _ in 0..5 {
        app.update();
    }
    let map = app.world().resource::<HexMap>();
    let (other_id, other_generation) = (map.map_id(), map.generation());
    assert_eq!(
        seen::<TerrainReady>(&app),
        [TerrainReady { map_id, generation }, TerrainReady { map_id: other_id, generation: other_generation }]
    );
    assert!(seen::<TerrainReady>(&app).iter().all(|r| r.map_id != placeholder));
    let _ = std::fs::remove_dir_all(&dir);
}

/// What the `Startup` system of the test below got from its writes.
#[derive(Resource, Default)]
struct StartupWrites {
    waiting: bool,
    results: Vec<Result<(), String>>,
    tiles: Vec<Hex>,
}

#[test]
fn states_written_while_the_map_file_loads_are_kept_on_its_tiles() {
    // A map wider than the placeholder (the thesis' Map0, 30 x 30).
    let dir = asset_dir("startup", "(seed: 4, size: Bounded(x: 48, z: 12), chunk_size: (8, 8))");
    let mut app = app_with(MapSource::Asset("game.map.ron".into()), settings(1), Some(&dir));
    app.init_resource::<StartupWrites>().add_systems(
        Startup,
        |map: Res<HexMap>, mut states: ResMut<TileStates>, mut out: ResMut<StartupWrites>| {
            out.waiting = map.is_waiting_for_asset();
            // Offsets of the map file's map: one past the placeholder's east edge, one past the map's.
            let terrain = map.terrain();
            for (offset, owner) in [([40, 5], 1), ([2, 3], 2), ([60, 5], 3)] {
                let tile = terrain.tile_from_offset(offset);
                out.results.push(states.set_owner(tile, Some(owner)).map_err(|e| e.to_string()));
                out.tiles.push(tile);
            }
        },
    );
    settle(&mut app, "the map file");
    let out = app.world().resource::<StartupWrites>();
    assert!(out.waiting, "Startup runs while the map file loads");
    assert!(out.results.iter().all(Result::is_ok), "{:?}", out.results);
    let tiles = out.tiles.clone();
    let map = app.world().resource::<HexMap>();
    assert!(map.contains(tiles[0]) && map.contains(tiles[1]) && !map.contains(tiles[2]));
    let states = app.world().resource::<TileStates>();
    assert_eq!(states.owner(tiles[0]), Some(1), "past the placeholder, on the map: kept");
    assert_eq!(states.owner(tiles[1]), Some(2));
    assert_eq!(states.owner(tiles[2]), None, "off the map: dropped");
    assert_eq!(states.stored_tiles(), 2);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The results of the writes made on the frame another map applied.
#[derive(Resource, Default)]
struct SwitchWrites(Vec<(u64, Result<(), String>)>);

#[test]
fn a_system_after_the_map_set_writes_the_new_maps_tiles_on_the_frame_it_applies() {
    let small = MapConfig { seed: 2, size: MapSize::Bounded { x: 16, z: 16 }, chunk_size: (8, 8), ..default() };
    let mut app = app(small, 1);
    settle(&mut app, "the first map");
    let first = app.world().resource::<HexMap>().map_id();
    app.init_resource::<SwitchWrites>().add_systems(
        Update,
        (move |map: Res<HexMap>, mut states: ResMut<TileStates>, mut out: ResMut<SwitchWrites>| {
            if map.map_id() != first && out.0.is_empty() {
                // Past the first map's east edge, on the new one.
                let tile = map.terrain().tile_from_offset([30, 4]);
                out.0.push((map.map_id(), states.set_owner(tile, Some(4)).map_err(|e| e.to_string())));
            }
        })
        .after(HexTerrainSystems::Map),
    );
    let wide = MapConfig { seed: 2, size: MapSize::Bounded { x: 40, z: 16 }, chunk_size: (8, 8), ..default() };
    app.world_mut().write_message(LoadHexMap(wide.into()));
    app.update();
    let map_id = app.world().resource::<HexMap>().map_id();
    assert_ne!(map_id, first, "a map given as a config applies on the frame it is sent");
    assert_eq!(app.world().resource::<SwitchWrites>().0, [(map_id, Ok(()))]);
    settle(&mut app, "the new map");
    let tile = app.world().resource::<HexMap>().terrain().tile_from_offset([30, 4]);
    assert_eq!(app.world().resource::<TileStates>().owner(tile), Some(4));
}

/// A game set up on a map loaded without one (`SetUpGame`): the same map (its id, its tiles),
/// `GameSetUp` once the starts are there, the setup the core places; kept over an edit and a hot
/// reload of the file; a setup that does not fit is refused and the map stays as it was. A map
/// whose config has a setup says `GameSetUp` beside `TerrainReady`.
#[test]
fn a_game_set_up_on_any_map() {
    let text = "(seed: 5, size: Bounded(x: 32, z: 24), chunk_size: (8, 8), climate: (enabled: true))";
    let dir = asset_dir("set-up", text);
    let mut app = app_with(MapSource::Asset("game.map.ron".into()), settings(1), Some(&dir));
    keep::<TerrainReady>(&mut app);
    keep::<GameSetUp>(&mut app);
    keep::<HexMapError>(&mut app);
    keep::<HexMapEdited>(&mut app);
    settle(&mut app, "the map file");
    let (map_id, plain) = {
        let map = app.world().resource::<HexMap>();
        (map.map_id(), map.terrain().clone())
    };
    assert!(plain.setup().is_none());
    assert!(seen::<GameSetUp>(&app).is_empty(), "no setup, no starts");

    // Too many players for the map: refused by name, the map unchanged.
    let crowd = SetupConfig { players: 60, min_distance: 9, ..default() };
    app.world_mut().write_message(SetUpGame(crowd));
    app.update();
    let errors = seen::<HexMapError>(&app);
    assert_eq!(errors.len(), 1, "{errors:?}");
    assert!(errors[0].to_string().contains("setup."), "{}", errors[0]);
    assert!(app.world().resource::<HexMap>().setup().is_none());

    let setup = SetupConfig { players: 2, min_distance: 5, ..default() };
    app.world_mut().write_message(SetUpGame(setup.clone()));
    app.update();
    let map = app.world().resource::<HexMap>();
    let expected = plain.with_setup(Some(setup.clone())).unwrap();
    assert_eq!(map.map_id(), map_id, "the same map");
    assert_eq!(map.setup().unwrap().starts(), expected.setup().unwrap().starts());
    assert_eq!(seen::<GameSetUp>(&app), [GameSetUp { map_id, generation: map.generation() }]);
    for tile in plain.tiles() {
        assert_eq!(map.tile_info(tile), plain.tile_info(tile), "the same tiles");
    }
    settle(&mut app, "the set up map");
    assert_eq!(seen::<TerrainReady>(&app).len(), 1, "the same map is not ready again");

    // An edit keeps the setup.
    let tile = plain.tile_from_offset([3, 3]);
    app.world_mut().write_message(HexMapEdit::Stroke(Stroke { tool: Tool::Raise(0.1), brush: Brush::Range(0), tile }));
    run_until(&mut app, "the edit", |app| !seen::<HexMapEdited>(app).is_empty() && ready(app));
    assert_eq!(app.world().resource::<HexMap>().config().setup.as_ref(), Some(&setup));
    assert!(app.world().resource::<HexMap>().setup().is_some());

    // A hot reload of the file, which has no setup, keeps the game set up.
    reload_asset(&mut app, |config| config.seed = 6);
    run_until(&mut app, "the reload", |app| app.world().resource::<HexMap>().config().seed == 6 && ready(app));
    let map = app.world().resource::<HexMap>();
    assert_eq!(map.map_id(), map_id);
    assert_eq!(map.config().setup.as_ref(), Some(&setup));
    assert_eq!(map.setup().unwrap().starts().len(), 2);
    assert_eq!(seen::<GameSetUp>(&app).len(), 1, "a reload keeps the players where they are");

    // Another map with a setup of its own: its starts come beside its TerrainReady.
    let mut other = MapConfig { seed: 9, size: MapSize::Bounded { x: 32, z: 24 }, chunk_size: (8, 8), ..default() };
    other.setup = Some(setup);
    app.world_mut().write_message(LoadHexMap(other.into()));
    run_until(&mut app, "the other map", |app| seen::<TerrainReady>(app).len() == 2);
    let map = app.world().resource::<HexMap>();
    let last = *seen::<GameSetUp>(&app).last().unwrap();
    assert_eq!(last, GameSetUp { map_id: map.map_id(), generation: map.generation() });
    assert_eq!(seen::<GameSetUp>(&app).len(), 2);
    let _ = std::fs::remove_dir_all(&dir);
}
