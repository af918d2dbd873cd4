//! A globe in a real renderer (Mesa's software Vulkan under Xvfb in CI): the fog of war and an
//! owner's tint land on the tiles [`GlobeTileStates`] gives them, pentagons included, and the
//! water's look ([`HexWaterSettings`]) on exactly the tiles whose center lies under the sea,
//! checked on a screenshot at each tile's center (found by casting the ray from the camera to
//! it, so a tile behind the limb or a hill is not read). Each scenario runs in a process of its
//! own.

#[macro_use]
mod support;

use std::path::Path;
use std::sync::{Arc, Mutex};

use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy::window::WindowResolution;
use bevy::winit::WinitPlugin;
use bevy_hex_terrain::GlobeStreamer;
use bevy_hex_terrain::hex_terrain::{GlobeGrid, GlobeTerrain, GlobeTile};
use bevy_hex_terrain::prelude::*;

const WIDTH: u32 = 640;
const HEIGHT: u32 = 480;

/// Fog by the tile center's `x` (the screen's horizontal): unexplored on the left, explored in
/// the middle, visible on the right.
fn fog_of(grid: &GlobeGrid, tile: GlobeTile) -> FogState {
    match grid.center(tile).unwrap()[0] {
        x if x < -0.25 => FogState::Unexplored,
        x if x < 0.25 => FogState::Explored,
        _ => FogState::Visible,
    }
}

/// Player 1 owns the visible tiles in the upper part.
fn owned(grid: &GlobeGrid, tile: GlobeTile) -> bool {
    fog_of(grid, tile) == FogState::Visible && grid.center(tile).unwrap()[1] > -0.2
}

fn rgb(img: &image::RgbImage, (x, y): (u32, u32)) -> [f32; 3] {
    img.get_pixel(x.min(WIDTH - 1), y.min(HEIGHT - 1)).0.map(|c| f32::from(c) / 255.0)
}

fn spread(c: [f32; 3]) -> f32 {
    c[0].max(c[1]).max(c[2]) - c[0].min(c[1]).min(c[2])
}

in_own_process! {
    globe_tiles_show_their_fog_and_owner => scenario_globe_states,
    the_sea_is_drawn_as_water_on_the_submerged_tiles => scenario_globe_water,
}

/// Each tile seen at its center: the tile and the pixel.
type Seen = Vec<(GlobeTile, (u32, u32))>;

/// The scenarios' globe: low relief, so the globe is a ball in the view and no tile hides
/// another's center.
fn scenario_config() -> MapConfig {
    let mut config = MapConfig { size: MapSize::Globe { frequency: 6 }, seed: 3, ..MapConfig::default() };
    config.terrain.inner_rings = 2;
    config.terrain.max_elevation = 0.6;
    config
}

#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_globe_states() {
    let config = scenario_config();
    let (img, tiles) = shoot(
        &config,
        "globe_states.png",
        |app| {
            app.insert_resource(HexTileStateStyle { fog_of_war: true, borders: false, ..default() });
        },
        |globe, states| {
            let grid = globe.grid();
            for tile in grid.tiles() {
                states.set_visibility(tile, fog_of(grid, tile)).unwrap();
                states.set_owner(tile, owned(grid, tile).then_some(1)).unwrap();
            }
        },
    );
    let terrain = GlobeTerrain::new(config).unwrap();
    let grid = GlobeGrid::new(6).unwrap();
    // Tiles whose neighbors share their fog and owner: the blend across borders stays clear of
    // their centers.
    let inner = |t: GlobeTile| {
        grid.neighbors(t)
            .unwrap()
            .as_slice()
            .iter()
            .all(|&n| fog_of(&grid, n) == fog_of(&grid, t) && owned(&grid, n) == owned(&grid, t))
    };
    let mut counted = [0; 4];
    for &(tile, px) in tiles.iter().filter(|(t, _)| inner(*t)) {
        let c = rgb(&img, px);
        let brightness = (c[0] + c[1] + c[2]) / 3.0;
        match (fog_of(&grid, tile), owned(&grid, tile)) {
            (FogState::Unexplored, _) => {
                assert!(brightness < 0.16 && spread(c) < 0.08, "unexplored {tile:?} drawn {c:?}");
                counted[0] += 1;
            }
            (FogState::Explored, _) => {
                assert!(spread(c) < 0.2 && brightness > 0.08, "explored {tile:?} drawn {c:?}");
                counted[1] += 1;
            }
            (FogState::Visible, false) => {
                // In its kind's color: sea and land in color (mountains are grey when seen too).
                if terrain.tile_kind(tile) != Some(TileKind::Mountain) {
                    assert!(spread(c) > 0.1, "visible {tile:?} drawn grey {c:?}");
                    counted[2] += 1;
                }
            }
            (FogState::Visible, true) => {
                // Player 1's color is blue: tinted toward it.
                assert!(c[2] > c[0], "owned {tile:?} drawn {c:?}");
                counted[3] += 1;
            }
        }
    }
    assert!(counted.iter().all(|&n| n >= 2), "tiles read in each state: {counted:?}");
    println!("tiles read: {counted:?}");
}

#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_globe_water() {
    // Half of it sea.
    let mut config = scenario_config();
    config.terrain.sea_threshold = 0.5;
    config.terrain.mountain_threshold = 0.8;
    // A water of one vivid red, still, over no sea floor: every fragment under the sea is at
    // least 62 % of it, whatever its depth.
    let red = Color::srgb(0.85, 0.08, 0.06);
    let water = HexWaterSettings {
        shallow_color: red,
        deep_color: red,
        foam_color: red,
        sea_floor: false,
        waves: 0.0,
        ..default()
    };
    let (img, tiles) = shoot(
        &config,
        "globe_water.png",
        move |app| {
            app.insert_resource(water);
        },
        |_, _| {},
    );
    let terrain = GlobeTerrain::new(config.clone()).unwrap();
    let sea_level = f64::from(config.terrain.sea_threshold * config.terrain.max_elevation);
    let grid = terrain.grid();
    // A tile whose center lies under the sea (its neighbors too, so the shore's band is away)
    // is red; one whose center is above it, with its neighbors, is not.
    let depth = |t: GlobeTile| sea_level - f64::from(terrain.tile_info(t).unwrap().elevation);
    let all = |t: GlobeTile, f: &dyn Fn(GlobeTile) -> bool| {
        f(t) && grid.neighbors(t).unwrap().as_slice().iter().all(|&n| f(n))
    };
    let (mut sea, mut land) = (0, 0);
    for &(tile, px) in &tiles {
        let c = rgb(&img, px);
        if all(tile, &|t| depth(t) > 0.02) {
            assert!(c[0] > 2.0 * c[1] && c[0] > 2.0 * c[2], "sea {tile:?} drawn {c:?}, not as the water");
            sea += 1;
        } else if all(tile, &|t| depth(t) < -0.02) {
            assert!(c[0] < c[1].max(c[2]) + 0.05, "land {tile:?} drawn {c:?}, as the water");
            land += 1;
        }
    }
    assert!(sea >= 3 && land >= 3, "tiles read: {sea} at sea, {land} on land");
    println!("tiles read: {sea} at sea, {land} on land");
}

/// Renders `config`'s globe from the front (the app set up further by `setup`, the tile states
/// written by `write` once the globe is in), and returns the first screenshot showing the globe
/// (saved as `name`) with each tile seen at its center.
fn shoot(
    config: &MapConfig,
    name: &str,
    setup: impl FnOnce(&mut App),
    write: impl Fn(&GlobeTerrain, &mut GlobeTileStates) + Send + Sync + 'static,
) -> (image::RgbImage, Seen) {
    let config = config.clone();
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_file(&out);
    let seen: Arc<Mutex<Option<Seen>>> = Arc::default();
    let mut app = App::new();
    app.add_plugins((
        DefaultPlugins
            .set(WindowPlugin {
                primary_window: Some(Window { resolution: WindowResolution::new(WIDTH, HEIGHT), ..default() }),
                ..default()
            })
            .set(WinitPlugin { run_on_any_thread: true }),
        HexGlobePlugin::from_config(config.clone()),
    ))
    // No trees over the tile centers read below.
    .insert_resource(HexPropSettings { enabled: false, ..default() })
    .insert_resource(GlobalAmbientLight { brightness: 600.0, ..default() });
    setup(&mut app);
    let terrain = GlobeTerrain::new(config.clone()).unwrap();
    let radius = terrain.radius() as f32;
    app.world_mut()
        .spawn((Camera3d::default(), Transform::from_xyz(0.0, 0.0, 3.0 * radius).looking_at(Vec3::ZERO, Vec3::Y)));
    app.world_mut().spawn((
        DirectionalLight { illuminance: 6000.0, shadow_maps_enabled: false, ..default() },
        Transform::from_xyz(0.0, 0.0, 10.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    app.add_systems(
        Update,
        (move |globe: Res<HexGlobe>, mut states: ResMut<GlobeTileStates>, mut written: Local<bool>| {
            let Some(globe) = globe.globe().filter(|_| !*written) else { return };
            *written = true;
            write(globe, &mut states);
        })
        .after(HexTerrainSystems::Map),
    );
    let (flag, path) = (seen.clone(), out.clone());
    let (mut settled_frames, mut frames) = (0, 0);
    app.add_systems(
        Last,
        move |mut commands: Commands,
              globe: Res<HexGlobe>,
              streamer: Res<GlobeStreamer>,
              cameras: Query<(&Camera, &GlobalTransform)>,
              mut exit: MessageWriter<AppExit>| {
            if flag.lock().unwrap().as_ref().is_some_and(|s| !s.is_empty()) {
                exit.write(AppExit::Success);
                return;
            }
            settled_frames = if streamer.is_settled() { settled_frames + 1 } else { 0 };
            frames += 1;
            assert!(frames < 3000, "no picture of the globe after {frames} frames");
            // Pipelines compile in the background: shoot every 40 frames once the globe is in,
            // and keep the first picture that shows it.
            if settled_frames == 0 || settled_frames % 40 != 0 {
                return;
            }
            let (Some(globe), Ok((camera, at))) = (globe.globe(), cameras.single()) else { return };
            let eye = at.translation().as_dvec3();
            let mut tiles = Vec::new();
            for tile in globe.grid().tiles() {
                let c = bevy::math::DVec3::from_array(globe.grid().center(tile).unwrap());
                let Some(hit) = globe.raycast(eye.to_array(), (c * globe.radius() - eye).to_array(), f64::MAX) else {
                    continue;
                };
                let p = Vec3::from_array(hit.point.map(|v| v as f32));
                // Facing the camera, not near the limb.
                if hit.tile != tile || c.normalize().dot(eye.normalize()) < 0.5 {
                    continue;
                }
                if let Ok(px) = camera.world_to_viewport(at, p) {
                    tiles.push((tile, (px.x.round() as u32, px.y.round() as u32)));
                }
            }
            assert!(!tiles.is_empty(), "no tile faces the camera");
            let (flag, path) = (flag.clone(), path.clone());
            commands.spawn(Screenshot::primary_window()).observe(move |shot: On<ScreenshotCaptured>| {
                let img = shot.image.clone().try_into_dynamic().unwrap().to_rgb8();
                let background = *img.get_pixel(0, 0);
                if img.pixels().filter(|p| **p != background).count() > img.pixels().len() / 5 {
                    img.save(&path).unwrap();
                    *flag.lock().unwrap() = Some(tiles.clone());
                }
            });
        },
    );
    app.run();
    let tiles = seen.lock().unwrap().take().expect("a picture of the globe");
    (image::open(&out).unwrap().to_rgb8(), tiles)
}
