//! Headless `App` tests of [`TileStates`]: writing state never touches a chunk mesh, a quiet
//! frame uploads nothing, state outlives streaming and hot reloads, another map clears it, and
//! the GPU window follows the loaded chunks.

use bevy::asset::AssetPlugin;
use bevy::prelude::*;
use bevy_hex_terrain::HexTileStateStats;
use bevy_hex_terrain::TileStateUpload;
use bevy_hex_terrain::prelude::*;

/// The terrain plugins headless (no material), streaming two chunks around agents.
fn headless(map: impl Into<MapSource>, asset_dir: Option<&std::path::Path>) -> App {
    let mut app = App::new();
    let file_path = asset_dir.map_or("assets".into(), |d| d.display().to_string());
    app.add_plugins((MinimalPlugins, AssetPlugin { file_path, ..default() }, TransformPlugin));
    app.insert_resource(HexStreamingSettings { load_radius: 1, max_inserts_per_frame: 16, ..default() });
    let plugins = HexTerrainPlugins::new(map);
    #[cfg(feature = "render")]
    app.add_plugins(plugins.build().disable::<HexTerrainMaterialPlugin>());
    #[cfg(not(feature = "render"))]
    app.add_plugins(plugins);
    app
}

mod common;

use common::{reload_asset, run_until as settle};

fn idle(app: &mut App) -> bool {
    app.world_mut().query::<&bevy_hex_terrain::ChunkTask>().iter(app.world()).next().is_none()
        && app.world_mut().query::<(&HexChunk, &Mesh3d)>().iter(app.world()).count() > 0
}

fn bounded(x: u32, z: u32) -> MapConfig {
    MapConfig { size: MapSize::Bounded { x, z }, chunk_size: (16, 16), ..MapConfig::default() }
}

/// Counts of everything a mesh rebuild or re-insertion would change.
#[derive(Resource, Default)]
struct MeshActivity {
    mesh_events: usize,
    spawned: usize,
}

fn count_mesh_activity(
    mut meshes: MessageReader<AssetEvent<Mesh>>,
    mut spawned: MessageReader<ChunkSpawned>,
    mut activity: ResMut<MeshActivity>,
) {
    activity.mesh_events += meshes.read().count();
    activity.spawned += spawned.read().count();
}

#[test]
fn writing_tile_state_never_rebuilds_or_reinserts_a_chunk_mesh() {
    // Civilization VI's Huge map: 106 x 66 tiles, held whole.
    let mut app = headless(bounded(106, 66), None);
    app.init_resource::<MeshActivity>().add_systems(Last, count_mesh_activity);
    settle(&mut app, "the whole map", |app| idle(app) && app.world().resource::<ChunkStreamer>().live_chunks() == 35);
    for _ in 0..5 {
        app.update();
    }
    *app.world_mut().resource_mut::<MeshActivity>() = MeshActivity::default();
    let meshes_before = app.world().resource::<Assets<Mesh>>().len();
    let handles = |app: &mut App| -> Vec<AssetId<Mesh>> {
        let mut ids: Vec<_> = app.world_mut().query::<&Mesh3d>().iter(app.world()).map(|m| m.0.id()).collect();
        ids.sort_unstable();
        ids
    };
    let before = handles(&mut app);
    let (origin, size) = app.world().resource::<TileStates>().window();
    assert_eq!((origin, size), (IVec2::ZERO, UVec2::new(106, 66)), "a Huge map fits the window whole");
    let tiles: Vec<Hex> = app.world().resource::<HexMap>().terrain().tiles().collect();
    for frame in 0..10 {
        {
            let mut states = app.world_mut().resource_mut::<TileStates>();
            for (i, &t) in tiles.iter().enumerate() {
                let fog = [FogState::Unexplored, FogState::Explored, FogState::Visible][(i + frame) % 3];
                states.set_visibility(t, fog).unwrap();
                states.set_owner(t, Some(((i + frame) % 8) as u32)).unwrap_or_else(|e| panic!("{e}"));
                if i % 7 == frame {
                    states.set_overlay(t, Some(Color::srgba(0.1, 0.9, 0.2, 0.5))).unwrap();
                }
            }
            states.replace_highlight(Highlight::Reachable, tiles.iter().copied().skip(frame * 300).take(3000));
        }
        app.update();
        let stats = app.world().resource::<HexTileStateStats>();
        assert!(stats.last_upload_bytes > 0, "frame {frame} uploaded its changes");
        assert!(stats.last_upload_bytes <= 106 * 66 * 8, "an upload is at most the texture");
    }
    for _ in 0..5 {
        app.update();
    }
    let activity = app.world().resource::<MeshActivity>();
    assert_eq!(activity.mesh_events, 0, "no mesh asset was added, modified or removed");
    assert_eq!(activity.spawned, 0, "no chunk mesh was inserted again");
    assert_eq!(app.world().resource::<Assets<Mesh>>().len(), meshes_before);
    assert_eq!(handles(&mut app), before, "every chunk keeps its mesh");
}

#[test]
fn a_frame_without_changes_uploads_nothing() {
    let mut app = headless(bounded(40, 30), None);
    settle(&mut app, "the map", idle);
    let tile = app.world().resource::<HexMap>().terrain().tile_from_offset([3, 4]);
    app.world_mut().resource_mut::<TileStates>().set_visibility(tile, FogState::Visible).unwrap();
    app.update();
    let stats = app.world().resource::<HexTileStateStats>().clone();
    assert_eq!(stats.last_upload_bytes, 8, "one tile's texel");
    let upload_tick = |app: &App| app.world().resource_ref::<TileStateUpload>().last_changed();
    let tick = upload_tick(&app);
    for _ in 0..20 {
        // Writing what is already there is no change either.
        app.world_mut().resource_mut::<TileStates>().set_visibility(tile, FogState::Visible).unwrap();
        app.update();
    }
    let after = app.world().resource::<HexTileStateStats>();
    assert_eq!(after.uploads, stats.uploads, "no upload in quiet frames");
    assert_eq!(after.last_upload_bytes, 0);
    assert_eq!(upload_tick(&app), tick, "the upload resource was not touched, so nothing is extracted");
}

#[test]
fn state_outlives_streaming_and_the_window_follows_the_chunks() {
    let config = MapConfig { size: MapSize::Unbounded, chunk_size: (16, 16), ..MapConfig::default() };
    let mut app = headless(config, None);
    let agent = app.world_mut().spawn((HexTerrainAgent::default(), Transform::default())).id();
    settle(&mut app, "chunks at the origin", idle);
    let home = Hex::new(2, 3);
    app.world_mut().resource_mut::<TileStates>().set_owner(home, Some(3)).unwrap();
    // Far away: the home chunk unloads and the window moves with the chunks.
    let far = app.world().resource::<HexMap>().tile_center(Hex::new(3000, -1000)).unwrap();
    app.world_mut().entity_mut(agent).insert(Transform::from_translation(far));
    let home_chunk = app.world().resource::<HexMap>().chunk_of(home).unwrap();
    settle(&mut app, "chunks far away", |app| {
        idle(app) && !app.world().resource::<ChunkStreamer>().is_chunk_loaded(home_chunk)
    });
    app.update();
    let states = app.world().resource::<TileStates>();
    let (origin, size) = states.window();
    let window = IRect::from_corners(origin, origin + size.as_ivec2());
    let map = app.world().resource::<HexMap>();
    for chunk in app.world().resource::<ChunkStreamer>().loaded_chunks() {
        let r = map.terrain().chunk_rect(chunk).unwrap();
        assert!(
            window.contains(IVec2::from(r.min)) && window.contains(IVec2::from(r.max) - IVec2::ONE),
            "loaded chunk {chunk:?} lies inside the window {window:?}"
        );
    }
    assert!(!window.contains(states.offset_of(home)), "the window left home");
    assert_eq!(states.owner(home), Some(3), "state of a tile in an unloaded chunk is kept");
    assert!(app.world().resource::<HexTileStateStats>().window_moves >= 2);
    // Back home: the texture shows it again (the refill is tested in the unit tests).
    app.world_mut().entity_mut(agent).insert(Transform::default());
    settle(&mut app, "chunks at home", |app| {
        idle(app) && app.world().resource::<ChunkStreamer>().is_chunk_loaded(home_chunk)
    });
    app.update();
    let states = app.world().resource::<TileStates>();
    let (origin, size) = states.window();
    assert!(IRect::from_corners(origin, origin + size.as_ivec2()).contains(states.offset_of(home)));
    assert_eq!(states.owner(home), Some(3));
}

#[test]
fn a_hot_reload_keeps_the_state_and_another_map_clears_it() {
    let dir = std::env::temp_dir().join(format!("hexterrain-tile-state-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("a.map.ron"), "(seed: 5, size: Bounded(x: 16, z: 16), chunk_size: (8, 8))").unwrap();
    let mut app = headless("a.map.ron", Some(&dir));
    settle(&mut app, "the map file", |app| app.world().resource::<HexMap>().config().seed == 5 && idle(app));
    let (kept, dropped) = (Hex::new(2, 2), Hex::new(14, 0));
    {
        let mut states = app.world_mut().resource_mut::<TileStates>();
        states.set_owner(kept, Some(1)).unwrap();
        states.set_owner(dropped, Some(2)).unwrap();
        states.set_visibility(kept, FogState::Explored).unwrap();
        // Outside the 16 x 16 map: refused.
        assert!(states.set_owner(Hex::new(40, 40), Some(1)).is_err());
    }
    let id = app.world().resource::<HexMap>().map_id();
    // A hot reload of the same file that also shrinks the map: state on the map is kept.
    reload_asset(&mut app, |config| {
        config.seed = 6;
        config.size = MapSize::Bounded { x: 12, z: 16 };
    });
    settle(&mut app, "the reload", |app| app.world().resource::<HexMap>().config().seed == 6);
    app.update();
    assert_eq!(app.world().resource::<HexMap>().map_id(), id, "a reload is the same map");
    let states = app.world().resource::<TileStates>();
    assert_eq!(states.owner(kept), Some(1));
    assert_eq!(states.visibility(kept), FogState::Explored);
    assert_eq!(states.owner(dropped), None, "a tile that fell off the map is dropped");
    assert_eq!(states.window().1, UVec2::new(12, 16), "the window follows the new size");
    // Another map: the state is cleared.
    app.world_mut().write_message(LoadHexMap(bounded(20, 20).into()));
    settle(&mut app, "the switch", |app| app.world().resource::<HexMap>().map_id() != id);
    app.update();
    let states = app.world().resource::<TileStates>();
    assert_eq!(states.owner(kept), None);
    assert_eq!(states.stored_tiles(), 0);
    let _ = std::fs::remove_dir_all(&dir);
}

/// What the GPU texture holds, rebuilt on the CPU from every upload the plugin packs.
#[derive(Resource, Default, Debug, PartialEq)]
struct TextureMirror {
    texture: u64,
    size: UVec2,
    texels: Vec<[u16; 4]>,
}

fn mirror_uploads(upload: Res<TileStateUpload>, mut mirror: ResMut<TextureMirror>) {
    if !upload.is_changed() || upload.size == UVec2::ZERO {
        return;
    }
    if upload.size != mirror.size || upload.texture != mirror.texture {
        *mirror = TextureMirror {
            texture: upload.texture,
            size: upload.size,
            texels: vec![[0; 4]; (upload.size.x * upload.size.y) as usize],
        };
    }
    let mut data = upload.data.iter();
    for span in &upload.spans {
        let start = (span.y * mirror.size.x + span.x) as usize;
        for texel in &mut mirror.texels[start..start + span.z as usize] {
            *texel = *data.next().unwrap();
        }
    }
}

fn with_mirror(mut app: App) -> App {
    app.init_resource::<TextureMirror>().add_systems(Last, mirror_uploads);
    app
}

/// A tile's state as the public API reads it: fog, owner, overlay, each highlight.
type TileState = (Hex, FogState, Option<u32>, Option<Color>, [bool; 3]);

/// Every tile's state, read through the public API.
fn every_state(app: &App) -> Vec<TileState> {
    let (map, states) = (app.world().resource::<HexMap>(), app.world().resource::<TileStates>());
    map.terrain()
        .tiles()
        .map(|t| {
            let lit = Highlight::ALL.map(|h| states.is_highlighted(t, h));
            (t, states.visibility(t), states.owner(t), states.overlay(t), lit)
        })
        .collect()
}

#[test]
fn a_save_mid_game_loads_into_a_fresh_app_bit_for_bit() {
    // A wrapping 40x30 map: highlights across the seam are the map's own tiles.
    let config = MapConfig { wrap: true, ..bounded(40, 30) };
    let mut app = with_mirror(headless(config.clone(), None));
    settle(&mut app, "the map", idle);
    // Some turns of a game: fog follows a unit east, owners grow, a lens overlay, highlights.
    let terrain = app.world().resource::<HexMap>().terrain().clone();
    for turn in 0..12 {
        let here = terrain.tile_from_offset([3 * turn, 10 + turn % 3]);
        let mut states = app.world_mut().resource_mut::<TileStates>();
        states.hide_visible();
        for tile in here.range(3) {
            let _ = states.set_visibility(tile, FogState::Visible);
        }
        for tile in here.range(1) {
            let _ = states.set_owner(tile, Some((turn % 5) as u32));
        }
        let _ = states.set_overlay(here, Some(Color::srgba(0.2, 0.8, 0.1, 0.5)));
        states.replace_highlight(Highlight::Reachable, here.range(2));
        let _ = states.set_highlight(here, Highlight::Selected, true);
        app.update();
    }
    // One east of the east edge: the map's tile in column 0.
    let seam = terrain.tile_from_offset([40, 4]);
    app.world_mut().resource_mut::<TileStates>().set_highlight(seam, Highlight::Hovered, true).unwrap();
    app.update();
    let states = app.world().resource::<TileStates>();
    let (ron, bytes) = (states.save_ron(&config), states.save_bytes(&config));
    assert!(states.stored_tiles() > 100, "a game's worth of state: {}", states.stored_tiles());
    println!("save of {} tiles: binary {} bytes, RON {} bytes", states.stored_tiles(), bytes.len(), ron.len());
    assert!(bytes.len() < ron.len() / 3, "binary {} bytes, RON {}", bytes.len(), ron.len());
    let before = every_state(&app);
    let window = states.window();
    let highlighted: Vec<Vec<Hex>> = Highlight::ALL.map(|h| sorted(states.highlighted(h))).to_vec();

    for encoding in ["ron", "binary"] {
        let mut fresh = with_mirror(headless(config.clone(), None));
        settle(&mut fresh, "the fresh map", idle);
        let mut states = fresh.world_mut().resource_mut::<TileStates>();
        match encoding {
            "ron" => states.load_ron(&config, &ron).unwrap(),
            _ => states.load_bytes(&config, &bytes).unwrap(),
        }
        fresh.update();
        assert_eq!(every_state(&fresh), before, "{encoding}: every tile's state");
        let states = fresh.world().resource::<TileStates>();
        assert_eq!(Highlight::ALL.map(|h| sorted(states.highlighted(h))).to_vec(), highlighted, "{encoding}");
        assert_eq!(states.window(), window, "{encoding}: the same window");
        assert_eq!(states.save_bytes(&config), bytes, "{encoding}: saved again, the same bytes");
        let (a, b) = (app.world().resource::<TextureMirror>(), fresh.world().resource::<TextureMirror>());
        assert_eq!((a.size, &a.texels), (b.size, &b.texels), "{encoding}: the uploaded texture window");
        assert!(a.texels.iter().any(|t| *t != [0; 4]), "the texture holds the game's state");
    }

    // A save of another map and a damaged file are refused, and change nothing.
    let mut fresh = headless(config.clone(), None);
    settle(&mut fresh, "a third map", idle);
    let other = MapConfig { seed: config.seed + 1, ..config.clone() };
    let mut states = fresh.world_mut().resource_mut::<TileStates>();
    states.set_owner(seam, Some(7)).unwrap();
    let err = states.load_bytes(&other, &bytes).unwrap_err();
    assert!(err.to_string().contains("another map") && err.to_string().contains("seed"), "{err}");
    let mut damaged = bytes.clone();
    let middle = damaged.len() / 2;
    damaged[middle] ^= 0x40;
    let err = states.load_bytes(&config, &damaged).unwrap_err();
    assert!(err.to_string().contains("corrupted"), "{err}");
    let err = states.load_ron(&config, &ron[..ron.len() / 2]).unwrap_err();
    assert!(err.to_string().contains("line"), "{err}");
    assert_eq!(states.stored_tiles(), 1);
    assert_eq!(states.owner(seam), Some(7), "a refused load changes nothing");
}

fn sorted(tiles: impl Iterator<Item = Hex>) -> Vec<Hex> {
    let mut v: Vec<Hex> = tiles.collect();
    v.sort_unstable_by_key(|h| (h.x, h.y));
    v
}
