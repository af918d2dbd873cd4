//! Headless `App` tests of a globe's tile states: every vertex of the chunk meshes names the tile
//! its triangles lie in (checked against the grid's own `tile_at` of each triangle's centroid,
//! and each tile's count of triangles against the formula), which the material reads the states
//! of, and carries its tile's texture layer (against the default ruleset's rule written here); [`GlobeTileStates`] follows the globe (refusing writes before it loads, keeping the states
//! through a hot reload of the same frequency, starting afresh on another), refuses bad writes by
//! name, and shows a player's [`GlobeFog`] tile by tile.

use std::collections::HashMap;

use bevy::asset::AssetPlugin;
use bevy::mesh::VertexAttributeValues;
use bevy::prelude::*;
use bevy_hex_terrain::hex_terrain::{GlobeFog, GlobeTile};
use bevy_hex_terrain::prelude::*;
use bevy_hex_terrain::{GLOBE_ROW, GlobeStreamer, HexMapAsset, TileStateError};

mod common;

use common::run_until;

fn globe_config(frequency: u32, inner_rings: u32) -> MapConfig {
    let mut config =
        MapConfig { size: MapSize::Globe { frequency }, chunk_size: (3, 3), seed: 9, ..MapConfig::default() };
    config.terrain.inner_rings = inner_rings;
    config
}

fn settled(app: &mut App, generation: u64) {
    run_until(app, "the globe settled", |app| {
        app.world().resource::<HexGlobe>().generation() == generation
            && app.world().resource::<GlobeStreamer>().is_settled()
    });
}

#[test]
fn every_vertex_names_the_tile_its_triangles_lie_in() {
    for (frequency, rings, climate) in [(3, 1, false), (5, 2, true)] {
        let mut app = App::new();
        let assets = AssetPlugin { watch_for_changes_override: Some(false), ..default() };
        let mut config = globe_config(frequency, rings);
        config.climate.enabled = climate;
        app.add_plugins((MinimalPlugins, assets, TransformPlugin, HexGlobePlugin::from_config(config)));
        settled(&mut app, 1);
        let globe = app.world().resource::<HexGlobe>().globe().unwrap().clone();
        let n = rings + 1;
        let mut triangles: HashMap<u32, u32> = HashMap::new();
        let mut kinds: HashMap<u32, u32> = HashMap::new();
        let mut q = app.world_mut().query::<(&Mesh3d, &Transform)>();
        let meshes = app.world().resource::<Assets<Mesh>>();
        for (mesh, transform) in q.iter(app.world()) {
            let mesh = meshes.get(&mesh.0).unwrap();
            let Some(VertexAttributeValues::Float32x3(positions)) = mesh.attribute(Mesh::ATTRIBUTE_POSITION) else {
                panic!("positions")
            };
            let Some(VertexAttributeValues::Float32x2(uvs)) = mesh.attribute(Mesh::ATTRIBUTE_UV_0) else {
                panic!("the tiles in the first UV")
            };
            let Some(VertexAttributeValues::Float32x2(layers)) = mesh.attribute(Mesh::ATTRIBUTE_UV_1) else {
                panic!("the texture layers in the second UV")
            };
            let indices: Vec<usize> = mesh.indices().unwrap().iter().collect();
            for triangle in indices.chunks(3) {
                let tiles: Vec<u32> = triangle
                    .iter()
                    .map(|&v| {
                        let [u, w] = uvs[v];
                        assert!(u.fract() == 0.0 && w.fract() == 0.0 && u < GLOBE_ROW as f32, "{u}, {w}");
                        u as u32 + w as u32 * GLOBE_ROW
                    })
                    .collect();
                assert!(tiles.iter().all(|&t| t == tiles[0]), "a triangle's corners name {tiles:?}");
                // The default ruleset's layers: the sea's 0, the mountains' 2, the land's 1.
                let terrain = globe.tile_info(GlobeTile(tiles[0])).unwrap().terrain.terrain;
                let layer = match globe.ruleset().biome(terrain).unwrap() {
                    Biome::Ocean | Biome::Coast | Biome::Lake => 0.0,
                    Biome::Rock | Biome::SnowPeak => 2.0,
                    _ => 1.0,
                };
                for &v in triangle {
                    assert_eq!(layers[v], [layer, 0.0], "tile {}'s texture layer", tiles[0]);
                }
                *kinds.entry(layer as u32).or_default() += 1;
                let centroid = triangle
                    .iter()
                    .map(|&v| transform.translation + Vec3::from_array(positions[v]))
                    .sum::<Vec3>()
                    .as_dvec3();
                let under = globe.grid().tile_at(centroid.to_array()).unwrap();
                assert_eq!(
                    under,
                    GlobeTile(tiles[0]),
                    "f = {frequency}: a triangle of tile {} lies in {under:?}",
                    tiles[0]
                );
                *triangles.entry(tiles[0]).or_default() += 1;
            }
        }
        assert_eq!(triangles.len() as u32, globe.grid().tile_count());
        assert!(kinds.len() >= 2, "f = {frequency}: triangles of each layer {kinds:?}");
        for (t, count) in triangles {
            let sides = if globe.grid().is_pentagon(GlobeTile(t)) { 5 } else { 6 };
            assert_eq!(count, sides * n * n, "f = {frequency}: tile {t}");
        }
    }
}

fn asset(config: MapConfig) -> HexMapAsset {
    HexMapAsset { config, image: None, ruleset: None, appearance_fallback: false }
}

#[test]
fn the_states_follow_the_globe_and_refuse_bad_writes_by_name() {
    let dir = std::env::temp_dir().join(format!("hexterrain-globe-tiles-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("globe.map.ron"),
        "(seed: 2, size: Globe(frequency: 4), chunk_size: (3, 3), terrain: (inner_rings: 1))",
    )
    .unwrap();
    let mut app = App::new();
    let assets =
        AssetPlugin { file_path: dir.display().to_string(), watch_for_changes_override: Some(false), ..default() };
    app.add_plugins((MinimalPlugins, assets, TransformPlugin, HexGlobePlugin::from_asset("globe.map.ron")));
    // Before the globe loads: no tiles, every write refused.
    let states = app.world().resource::<GlobeTileStates>();
    assert_eq!(states.tile_count(), 0);
    let mut states = app.world_mut().resource_mut::<GlobeTileStates>();
    assert_eq!(states.set_owner(GlobeTile(0), Some(0)), Err(TileStateError::NotOnGlobe { tile: 0, tiles: 0 }));
    settled(&mut app, 1);
    let tiles = 10 * 4 * 4 + 2;
    let mut states = app.world_mut().resource_mut::<GlobeTileStates>();
    assert_eq!(states.tile_count(), tiles);
    let (a, b) = (GlobeTile(5), GlobeTile(tiles - 1));
    states.set_owner(a, Some(3)).unwrap();
    states.set_visibility(a, FogState::Visible).unwrap();
    states.set_overlay(b, Some(Color::srgba_u8(10, 200, 30, 128))).unwrap();
    states.set_highlight(b, Highlight::Selected, true).unwrap();
    // Bad writes: refused by what is wrong, nothing changed.
    let writes = states.writes();
    let error = states.set_owner(GlobeTile(tiles), Some(0)).unwrap_err();
    assert_eq!(error, TileStateError::NotOnGlobe { tile: tiles, tiles });
    assert!(error.to_string().contains(&format!("0..{tiles}")), "{error}");
    assert_eq!(states.set_owner(a, Some(64)), Err(TileStateError::OwnerOutOfRange { owner: 64 }));
    assert!(matches!(
        states.set_overlay(a, Some(Color::srgb(f32::NAN, 0.0, 0.0))),
        Err(TileStateError::OverlayNotFinite { .. })
    ));
    assert_eq!(states.writes(), writes);
    assert_eq!(states.owner(a), Some(3));
    assert_eq!(states.visibility(a), FogState::Visible);
    assert_eq!(states.overlay(b).map(|c| c.to_srgba().to_u8_array()), Some([10, 200, 30, 128]));
    assert!(states.is_highlighted(b, Highlight::Selected));
    assert_eq!(states.highlighted(Highlight::Selected).collect::<Vec<_>>(), vec![b]);
    assert_eq!(states.replace_highlight(Highlight::Selected, [a, GlobeTile(tiles + 3)]), 1);
    assert!(!states.is_highlighted(b, Highlight::Selected) && states.is_highlighted(a, Highlight::Selected));
    states.hide_visible();
    assert_eq!(states.visibility(a), FogState::Explored);
    // A hot reload of the same frequency keeps every state; another frequency starts afresh.
    let id = app.world().resource::<Assets<HexMapAsset>>().ids().next().unwrap();
    let mut config = app.world().resource::<HexGlobe>().globe().unwrap().config().clone();
    config.seed = 5;
    app.world_mut().resource_mut::<Assets<HexMapAsset>>().insert(id, asset(config.clone())).unwrap();
    settled(&mut app, 2);
    let states = app.world().resource::<GlobeTileStates>();
    assert_eq!((states.owner(a), states.visibility(a)), (Some(3), FogState::Explored));
    config.size = MapSize::Globe { frequency: 5 };
    app.world_mut().resource_mut::<Assets<HexMapAsset>>().insert(id, asset(config)).unwrap();
    settled(&mut app, 3);
    let states = app.world().resource::<GlobeTileStates>();
    assert_eq!(states.tile_count(), 10 * 5 * 5 + 2);
    assert_eq!((states.owner(a), states.visibility(a)), (None, FogState::Unexplored));
    assert_eq!(states.highlighted(Highlight::Selected).count(), 0);
}

#[test]
fn a_players_fog_is_shown_tile_by_tile() {
    let mut app = App::new();
    let assets = AssetPlugin { watch_for_changes_override: Some(false), ..default() };
    app.add_plugins((MinimalPlugins, assets, TransformPlugin, HexGlobePlugin::from_config(globe_config(6, 1))));
    settled(&mut app, 1);
    let globe = app.world().resource::<HexGlobe>().globe().unwrap().clone();
    let mut fog = GlobeFog::new(&globe, 2).unwrap();
    fog.update(&globe, 0, [(GlobeTile(0), 3)]).unwrap();
    fog.update(&globe, 0, [(GlobeTile(100), 2)]).unwrap();
    fog.update(&globe, 1, [(GlobeTile(200), 2)]).unwrap();
    let mut states = app.world_mut().resource_mut::<GlobeTileStates>();
    states.set_owner(GlobeTile(7), Some(1)).unwrap();
    for player in [0, 1, 0] {
        states.show_fog(&fog, player).unwrap();
        let mut counts = [0; 3];
        for t in 0..globe.grid().tile_count() {
            let tile = GlobeTile(t);
            assert_eq!(Some(states.visibility(tile)), fog.state(player, tile), "player {player}, {tile:?}");
            counts[states.visibility(tile) as usize] += 1;
        }
        assert!(counts[FogState::Visible as usize] > 0 && counts[FogState::Unexplored as usize] > 0, "{counts:?}");
        assert_eq!(counts[FogState::Explored as usize] > 0, player == 0, "{counts:?}");
        // The other states are the game's, not the fog's.
        assert_eq!(states.owner(GlobeTile(7)), Some(1));
    }
    assert_eq!(states.show_fog(&fog, 2), Err(TileStateError::NoSuchPlayer { player: 2, players: 2 }));
    // A fog of a globe of another size.
    let other = bevy_hex_terrain::hex_terrain::GlobeTerrain::new(globe_config(5, 1)).unwrap();
    let small = GlobeFog::new(&other, 1).unwrap();
    let tiles = globe.grid().tile_count();
    assert_eq!(states.show_fog(&small, 0), Err(TileStateError::NotOnGlobe { tile: tiles - 1, tiles }));
}
