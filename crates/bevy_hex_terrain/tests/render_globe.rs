//! A globe's tile states in a real renderer (Mesa's software Vulkan under Xvfb in CI): the fog of
//! war and an owner's tint land on the tiles [`GlobeTileStates`] gives them, pentagons included,
//! checked on a screenshot at each tile's center (found by casting the ray from the camera to
//! it, so a tile behind the limb or a hill is not read). The scenario runs in a process of its own.

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
}

/// Each tile seen at its center: the tile and the pixel.
type Seen = Vec<(GlobeTile, (u32, u32))>;

#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_globe_states() {
    let mut config = MapConfig { size: MapSize::Globe { frequency: 6 }, seed: 3, ..MapConfig::default() };
    config.terrain.inner_rings = 2;
    // Low relief: the globe a ball in the view, no tile hiding another's center.
    config.terrain.max_elevation = 0.6;
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("globe_states.png");
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
    .insert_resource(HexTileStateStyle { fog_of_war: true, borders: false, ..default() })
    // No trees over the tile centers read below.
    .insert_resource(HexPropSettings { enabled: false, ..default() })
    .insert_resource(GlobalAmbientLight { brightness: 600.0, ..default() });
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
        (|globe: Res<HexGlobe>, mut states: ResMut<GlobeTileStates>, mut written: Local<bool>| {
            let Some(globe) = globe.globe().filter(|_| !*written) else { return };
            *written = true;
            let grid = globe.grid();
            for tile in grid.tiles() {
                states.set_visibility(tile, fog_of(grid, tile)).unwrap();
                states.set_owner(tile, owned(grid, tile).then_some(1)).unwrap();
            }
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
    let img = image::open(&out).unwrap().to_rgb8();
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
