//! The render test harness: a known small map from a fixed top-down camera, rendered in a real
//! window and saved with Bevy's screenshot API ([`render_scene`]), and the pixel helpers the
//! render tests share.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use bevy::camera::ScalingMode;
use bevy::core_pipeline::prepass::{DeferredPrepass, DepthPrepass};
use bevy::math::DVec3;
use bevy::pbr::DefaultOpaqueRendererMethod;
use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy::window::WindowResolution;
use bevy::winit::WinitPlugin;
use bevy_hex_terrain::hex_terrain::Terrain;
use bevy_hex_terrain::prelude::*;
use bevy_hex_terrain::{ChunkTask, HexTerrainMaterial};
use big_space::prelude::{BigSpaceCommands, BigSpaceDefaultPlugins, FloatingOrigin, Grid};

pub const WIDTH: u32 = 640;
pub const HEIGHT: u32 = 480;

pub fn map() -> MapConfig {
    let mut c =
        MapConfig { seed: 7, size: MapSize::Bounded { x: 20, z: 14 }, chunk_size: (8, 8), ..MapConfig::default() };
    c.terrain.max_elevation = 3.0;
    c.terrain.inner_rings = 2;
    c.noise.scale = 30.0;
    c
}

/// Where the camera looks and how much it shows.
pub fn view(terrain: &Terrain) -> (Vec2, Vec2) {
    let (mut lo, mut hi) = (Vec2::splat(f32::MAX), Vec2::splat(f32::MIN));
    for t in terrain.tiles() {
        let [x, _, z] = terrain.tile_center(t).unwrap().map(|v| v as f32);
        lo = lo.min(Vec2::new(x, z));
        hi = hi.max(Vec2::new(x, z));
    }
    let center = (lo + hi) / 2.0;
    // Keep the window's aspect ratio, with a margin.
    let span = (hi - lo) + Vec2::splat(3.0);
    let aspect = WIDTH as f32 / HEIGHT as f32;
    let size =
        if span.x / span.y > aspect { Vec2::new(span.x, span.x / aspect) } else { Vec2::new(span.y * aspect, span.y) };
    (center, size)
}

pub fn pixel(center: Vec2, size: Vec2, world: Vec3) -> (u32, u32) {
    let u = (world.x - center.x) / size.x + 0.5;
    let v = (world.z - center.y) / size.y + 0.5;
    ((u * WIDTH as f32) as u32, (v * HEIGHT as f32) as u32)
}

/// [`map`] with a climate, rivers and lakes.
pub fn wet_map() -> MapConfig {
    let mut c = map();
    c.climate.enabled = true;
    c.rivers.enabled = true;
    c.rivers.threshold = 2.5;
    c
}

/// What a scenario renders.
#[derive(Default)]
pub struct Scene {
    /// The map ([`map`] when `None`).
    pub config: Option<MapConfig>,
    /// The material's palette and outlines.
    pub material: HexTerrainMaterialSettings,
    /// How the tile states are drawn.
    pub style: HexTileStateStyle,
    /// Writes the tile states before the first frame.
    pub tiles: Option<fn(&Terrain, &mut TileStates)>,
    /// A deferred camera (deferred and depth prepasses) instead of a forward one.
    pub deferred: bool,
    /// Far out with `big_space`: the camera looks straight down on this f64 world position of an
    /// unbounded map, from a floating origin, over [`FAR_VIEW`] world units; the clear color is
    /// [`HOLE`], so any pixel of it is a hole in the terrain.
    pub far: Option<DVec3>,
    /// The water surface on (off: the thesis' flat look, which the older scenarios check).
    pub water: bool,
    /// Props on.
    pub props: bool,
    /// Light the scene with the plugin's sun (the camera is a `HexTerrainCamera`) instead of a
    /// fixed shadowless light.
    pub lighting: Option<HexLightSettings>,
    /// After the first picture: change the settings, let the change show, and take a second
    /// picture ([`render_pair`]).
    pub then: Option<fn(&mut HexPropSettings, &mut HexLightSettings, &mut HexTerrainMaterialSettings)>,
    /// Streaming settings (when `None`, the defaults with every chunk full).
    pub streaming: Option<HexStreamingSettings>,
    /// Look at this world `(x, z)` instead of the map's middle, with a streaming agent on the
    /// camera (so a wrapping map shows the copies past its edge), and clear to [`HOLE`].
    pub look_at: Option<Vec2>,
}

/// World units the far camera shows, `x` by `z`.
pub const FAR_VIEW: Vec2 = Vec2::new(40.0, 30.0);

/// The far scene's clear color: magenta, which no terrain color is.
pub const HOLE: [u8; 3] = [255, 0, 255];

/// What happened besides the picture.
#[derive(Default, Clone, Copy)]
pub struct Counts {
    /// `AssetEvent::Modified` events of the terrain material over the whole run.
    pub material_modified: usize,
    /// Frames in which `HexMap` was changed.
    pub map_changed: usize,
    /// Frames run.
    pub frames: usize,
    /// Chunks showing a mesh at each level (`[full, coarse]`) in the frame of the first picture.
    pub levels: [usize; 2],
}

/// Renders the map with outlines on or off and returns the screenshot.
pub fn render(outlines: bool, name: &str) -> image::RgbImage {
    let material = HexTerrainMaterialSettings { outlines, outline_width: 0.1, ..default() };
    render_scene(Scene { material, ..default() }, name).0
}

/// Renders a scene and returns the screenshot and the counts.
pub fn render_scene(scene: Scene, name: &str) -> (image::RgbImage, Counts) {
    let (img, _, counts) = render_scenes(scene, name);
    (img, counts)
}

/// Renders a scene with [`Scene::then`], returning the pictures before and after the change.
pub fn render_pair(scene: Scene, name: &str) -> (image::RgbImage, image::RgbImage) {
    assert!(scene.then.is_some(), "a pair needs a change");
    let (before, after, _) = render_scenes(scene, name);
    (before, after.expect("a second picture"))
}

fn render_scenes(scene: Scene, name: &str) -> (image::RgbImage, Option<image::RgbImage>, Counts) {
    let Scene { config, material, style, tiles, deferred, far, water, props, lighting, then, streaming, look_at } =
        scene;
    let config = config.unwrap_or_else(map);
    // The scenarios of other features look at full detail; those of levels of detail say theirs.
    let settings = streaming.unwrap_or(HexStreamingSettings { coarse_distance: None, ..default() });
    let out_after = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}_after.png"));
    let _ = std::fs::remove_file(&out_after);
    let terrain = Terrain::new(config.clone()).unwrap();
    let (center, size) = match (far, look_at) {
        (Some(_), _) => (Vec2::ZERO, FAR_VIEW),
        (None, Some(at)) => (at, view(&terrain).1),
        (None, None) => view(&terrain),
    };
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}.png"));
    let _ = std::fs::remove_file(&out);
    let done: Arc<Mutex<bool>> = Arc::default();
    let mut app = App::new();
    let plugins = DefaultPlugins
        .set(WindowPlugin {
            primary_window: Some(Window { resolution: WindowResolution::new(WIDTH, HEIGHT), ..default() }),
            ..default()
        })
        .set(WinitPlugin { run_on_any_thread: true });
    if far.is_some() {
        app.add_plugins((plugins.disable::<TransformPlugin>(), BigSpaceDefaultPlugins));
    } else {
        app.add_plugins(plugins);
    }
    let plugin = HexTerrainPlugins::new(MapSource::Config(Box::new(config)));
    let sun = lighting.is_some();
    app.insert_resource(settings)
        .add_plugins(plugin)
        .insert_resource(lighting.unwrap_or_default())
        .insert_resource(material)
        .insert_resource(style)
        .insert_resource(HexWaterSettings { enabled: water, ..default() })
        .insert_resource(HexPropSettings { enabled: props, ..default() })
        .insert_resource(GlobalAmbientLight { brightness: 600.0, ..default() });
    let camera_bundle = (
        Camera3d::default(),
        Projection::Orthographic(OrthographicProjection {
            scaling_mode: ScalingMode::Fixed { width: size.x, height: size.y },
            ..OrthographicProjection::default_3d()
        }),
    );
    let light = (
        DirectionalLight { illuminance: 6000.0, shadow_maps_enabled: false, ..default() },
        Transform::from_xyz(0.0, 10.0, 0.0).looking_at(Vec3::ZERO, Vec3::Z),
    );
    let camera = if let Some(at) = far {
        app.add_plugins(HexBigSpacePlugin).insert_resource(ClearColor(Color::srgb_u8(HOLE[0], HOLE[1], HOLE[2])));
        let mut commands = app.world_mut().commands();
        let mut camera = Entity::PLACEHOLDER;
        commands.spawn_big_space(Grid::default(), |grid| {
            grid.insert(HexTerrainGrid);
            let (cell, local) = grid.grid().translation_to_grid(DVec3::new(at.x, 50.0, at.z));
            camera = grid
                .spawn_spatial((
                    camera_bundle,
                    FloatingOrigin,
                    HexTerrainAgent { radius: Some(2) },
                    cell,
                    Transform::from_translation(local).looking_to(Vec3::NEG_Y, Vec3::NEG_Z),
                ))
                .id();
            grid.spawn_spatial(light);
        });
        app.world_mut().flush();
        camera
    } else {
        let camera = app
            .world_mut()
            .spawn((
                camera_bundle,
                Transform::from_xyz(center.x, 50.0, center.y)
                    .looking_at(Vec3::new(center.x, 0.0, center.y), Vec3::NEG_Z),
            ))
            .id();
        if look_at.is_some() {
            app.world_mut().entity_mut(camera).insert(HexTerrainAgent { radius: Some(8) });
            app.insert_resource(ClearColor(Color::srgb_u8(HOLE[0], HOLE[1], HOLE[2])));
        }
        if sun {
            app.world_mut().entity_mut(camera).insert(HexTerrainCamera);
        } else {
            app.world_mut().spawn(light);
        }
        camera
    };
    if deferred {
        app.world_mut().entity_mut(camera).insert((Msaa::Off, DepthPrepass, DeferredPrepass));
        app.insert_resource(DefaultOpaqueRendererMethod::deferred());
    }
    if let Some(write) = tiles {
        let state_terrain = terrain.clone();
        app.add_systems(
            Update,
            (move |mut states: ResMut<TileStates>| write(&state_terrain, &mut states))
                .run_if(run_once)
                .after(HexTerrainSystems::Tiles),
        );
    }
    let counts: Arc<Mutex<Counts>> = Arc::default();
    let levels = counts.clone();
    let shot = done.clone();
    // The levels shown, every frame until the first picture is kept.
    app.add_systems(Last, move |chunks: Query<&HexChunk, With<Mesh3d>>| {
        if !*shot.lock().unwrap() {
            let mut l = [0; 2];
            for c in &chunks {
                l[c.detail as usize] += 1;
            }
            levels.lock().unwrap().levels = l;
        }
    });
    let seen = counts.clone();
    app.add_systems(Last, move |map: Res<HexMap>, mut events: MessageReader<AssetEvent<HexTerrainMaterial>>| {
        let mut c = seen.lock().unwrap();
        c.frames += 1;
        c.map_changed += usize::from(map.is_changed());
        c.material_modified += events.read().filter(|e| matches!(e, AssetEvent::Modified { .. })).count();
    });
    let path: PathBuf = out.clone();
    let flag = done.clone();
    let mut frames = 0;
    let mut ready_frames = 0;
    // With a change: frames since it was made, and whether the second picture is saved.
    let mut changed_for: Option<u32> = None;
    let second: Arc<Mutex<bool>> = Arc::default();
    let second_saved = second.clone();
    let after_path = out_after.clone();
    app.add_systems(
        Last,
        move |mut commands: Commands,
              mut ready: MessageReader<TerrainSettled>,
              mut exit: MessageWriter<AppExit>,
              mut settings: ResMut<HexPropSettings>,
              mut lighting: ResMut<HexLightSettings>,
              mut material: ResMut<HexTerrainMaterialSettings>,
              tasks: Query<(), With<ChunkTask>>| {
            frames += 1;
            if *flag.lock().unwrap() {
                let Some(change) = then else {
                    exit.write(AppExit::Success);
                    return;
                };
                if *second_saved.lock().unwrap() {
                    exit.write(AppExit::Success);
                    return;
                }
                match changed_for.as_mut() {
                    None => {
                        change(&mut settings, &mut lighting, &mut material);
                        changed_for = Some(0);
                    }
                    Some(n) => {
                        // 30 frames with no chunk task left: whatever the change rebuilt is on
                        // screen, however many frames the machine took to build it.
                        *n = if tasks.is_empty() { *n + 1 } else { 0 };
                        if *n == 30 {
                            let path = after_path.clone();
                            let saved = second_saved.clone();
                            commands.spawn(Screenshot::primary_window()).observe(
                                move |shot: On<ScreenshotCaptured>| {
                                    let img = shot.image.clone().try_into_dynamic().unwrap().to_rgb8();
                                    img.save(&path).unwrap();
                                    *saved.lock().unwrap() = true;
                                },
                            );
                        }
                    }
                }
                assert!(frames < 8000, "no second picture after {frames} frames");
                return;
            }
            if ready.read().count() > 0 || ready_frames > 0 {
                ready_frames += 1;
            }
            assert!(frames < 5000, "no terrain on screen after {frames} frames");
            // Pipelines compile in the background: shoot every 20 frames once the terrain is
            // complete, and keep the first picture that shows it.
            if ready_frames > 0 && ready_frames % 20 == 0 {
                let path = path.clone();
                let flag = flag.clone();
                commands.spawn(Screenshot::primary_window()).observe(move |shot: On<ScreenshotCaptured>| {
                    let img = shot.image.clone().try_into_dynamic().unwrap().to_rgb8();
                    let background = *img.get_pixel(0, 0);
                    let drawn = img.pixels().filter(|p| **p != background).count();
                    if drawn > img.pixels().len() / 2 {
                        img.save(&path).unwrap();
                        *flag.lock().unwrap() = true;
                    }
                });
            }
        },
    );
    app.run();
    assert!(*done.lock().unwrap(), "no screenshot was taken");
    let counts = *counts.lock().unwrap();
    let after = then.map(|_| image::open(&out_after).expect("the second picture").to_rgb8());
    (image::open(&out).unwrap().to_rgb8(), after, counts)
}

pub fn rgb(img: &image::RgbImage, (x, y): (u32, u32)) -> [f32; 3] {
    img.get_pixel(x.min(WIDTH - 1), y.min(HEIGHT - 1)).0.map(|c| f32::from(c) / 255.0)
}

/// The median color, by brightness, of the 7x7 pixels around a pixel: what a patch of a surface
/// shows, without the glint of one moving wave in the sun (the water's normals follow the time,
/// so a single pixel's highlight depends on the frame the picture was taken in).
#[allow(dead_code, reason = "not every test binary that includes the scene support reads patches")]
pub fn patch(img: &image::RgbImage, (x, y): (u32, u32)) -> [f32; 3] {
    let mut colors: Vec<[f32; 3]> = (-3..=3_i32)
        .flat_map(|dy| (-3..=3_i32).map(move |dx| (dx, dy)))
        .map(|(dx, dy)| rgb(img, (x.saturating_add_signed(dx), y.saturating_add_signed(dy))))
        .collect();
    colors.sort_by(|a, b| brightness(*a).total_cmp(&brightness(*b)));
    colors[colors.len() / 2]
}

pub fn brightness(c: [f32; 3]) -> f32 {
    (c[0] + c[1] + c[2]) / 3.0
}

/// Tile centers well inside their type's range (away from the blend zone), by kind.
pub fn clear_tiles(terrain: &Terrain) -> Vec<(Hex, TileKind, Vec3)> {
    let c = terrain.config();
    let (s, m, b) = (c.terrain.sea_threshold, c.terrain.mountain_threshold, c.appearance.blend);
    terrain
        .tiles()
        .filter_map(|t| {
            let info = terrain.tile_info(t).unwrap();
            let h = info.elevation / c.terrain.max_elevation;
            ((h - s).abs() > b && (h - m).abs() > b)
                .then(|| (t, info.kind, DVec3::from_array(terrain.tile_center(t).unwrap()).as_vec3()))
        })
        .collect()
}

/// Mean brightness ratio of mid-edge pixels to tile-center pixels.
pub fn border_to_center(img: &image::RgbImage, terrain: &Terrain) -> f32 {
    let (center, size) = view(terrain);
    let layout = terrain.layout();
    let ratios: Vec<f32> = terrain
        .tiles()
        .filter(|t| terrain.contains(t.all_neighbors()[0]))
        .map(|t| {
            let a = layout.hex_to_world_pos(t);
            let b = layout.hex_to_world_pos(t.all_neighbors()[0]);
            let mid = (a + b) / 2.0;
            let edge =
                Vec3::new(mid.x, terrain.surface_height(f64::from(mid.x), f64::from(mid.y)).unwrap() as f32, mid.y);
            let center_px = pixel(center, size, Vec3::new(a.x, 0.0, a.y));
            // The darkest pixel around the edge point: lines are a pixel or two wide.
            let (ex, ey) = pixel(center, size, edge);
            let darkest = (0..9)
                .map(|k| brightness(rgb(img, ((ex + k % 3).saturating_sub(1), (ey + k / 3).saturating_sub(1)))))
                .fold(f32::MAX, f32::min);
            darkest / brightness(rgb(img, center_px)).max(1e-3)
        })
        .collect();
    ratios.iter().sum::<f32>() / ratios.len() as f32
}

/// Asserts every clear tile center shows its type's color, skipping `except`, and that the test
/// map has tiles of every type.
pub fn assert_type_colors(img: &image::RgbImage, terrain: &Terrain, except: &[Hex]) {
    let seen = check_type_colors(img, terrain, except);
    assert!(seen.iter().all(|&n| n > 0), "the test map has every type: {seen:?}");
}

/// Asserts every clear tile center shows its type's color, skipping `except`; returns how many
/// tiles of each type were checked.
pub fn check_type_colors(img: &image::RgbImage, terrain: &Terrain, except: &[Hex]) -> [usize; 3] {
    let (center, size) = view(terrain);
    let mut seen = [0; 3];
    for (hex, kind, at) in clear_tiles(terrain).into_iter().filter(|(h, _, _)| !except.contains(h)) {
        assert_kind_color(hex, kind, rgb(img, pixel(center, size, at)));
        seen[kind as usize] += 1;
    }
    seen
}

/// Asserts a tile center's pixel shows its type's color.
pub fn assert_kind_color(hex: Hex, kind: TileKind, [r, g, b]: [f32; 3]) {
    {
        match kind {
            TileKind::Sea => assert!(b > r + 0.1 && b > g, "sea tile {hex:?} drawn {:?}", [r, g, b]),
            TileKind::Land => assert!(g > r + 0.05 && g > b + 0.05, "land tile {hex:?} drawn {:?}", [r, g, b]),
            TileKind::Mountain => {
                assert!(
                    (r - g).abs() < 0.12 && (g - b).abs() < 0.12 && r > 0.35,
                    "mountain {hex:?} drawn {:?}",
                    [r, g, b]
                );
            }
        }
    }
}
