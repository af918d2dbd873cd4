//! Headless `App` tests of the globe plugin: chunks stream to an agent's horizon as it flies over
//! a pole, with no gap (every chunk with a vertex in sight, measured from the chunk's own mesh)
//! and no duplicate, the far side left out; far chunks are drawn coarse; the orbit camera crosses a pole without a jump,
//! zooms with the wheel, turns with a drag and tilts toward the horizon near the ground; a flat
//! map's config is refused by name.

use std::collections::{BTreeSet, HashMap};
#[cfg(feature = "picking")]
use std::time::Duration;

use bevy::asset::AssetPlugin;
use bevy::input::InputPlugin;
#[cfg(feature = "picking")]
use bevy::input::mouse::{MouseMotion, MouseScrollUnit, MouseWheel};
#[cfg(feature = "picking")]
use bevy::input::touch::TouchPhase;
use bevy::mesh::VertexAttributeValues;
use bevy::prelude::*;
#[cfg(feature = "picking")]
use bevy::time::TimeUpdateStrategy;
use bevy_hex_terrain::hex_terrain::{GlobeChunk, GlobeMesh, GlobeTerrain};
use bevy_hex_terrain::prelude::*;
use bevy_hex_terrain::{GlobeStreamer, HexGlobeSettings, HexMapAsset, globe_horizon};

mod common;

use common::{keep, run_until, seen};

fn globe_config(frequency: u32) -> MapConfig {
    let mut config =
        MapConfig { size: MapSize::Globe { frequency }, chunk_size: (2, 2), seed: 4, ..MapConfig::default() };
    config.terrain.inner_rings = 1;
    config
}

fn app(config: MapConfig) -> App {
    let mut app = App::new();
    let assets = AssetPlugin { watch_for_changes_override: Some(false), ..default() };
    app.add_plugins((MinimalPlugins, assets, TransformPlugin, InputPlugin, HexGlobePlugin::from_config(config)));
    app
}

/// The chunks on screen: each entity's chunk, counted.
fn shown(app: &mut App) -> HashMap<GlobeChunk, usize> {
    let mut out = HashMap::new();
    let mut q = app.world_mut().query::<(&HexGlobeChunk, Option<&Mesh3d>)>();
    for (chunk, mesh) in q.iter(app.world()) {
        assert!(mesh.is_some(), "{:?} has no mesh", chunk.chunk);
        *out.entry(chunk.chunk).or_default() += 1;
    }
    out
}

/// The smallest angle between `direction` and a vertex of each chunk, from the chunk's mesh.
fn nearest_angles(globe: &GlobeTerrain, direction: Vec3) -> Vec<(GlobeChunk, f32)> {
    globe
        .chunks()
        .into_iter()
        .map(|chunk| {
            let mesh = globe.generate(chunk);
            let origin = Vec3::from_array(mesh.origin.map(|c| c as f32));
            let angle = mesh
                .buffers
                .positions
                .iter()
                .map(|&p| (origin + Vec3::from_array(p)).normalize().dot(direction).clamp(-1.0, 1.0).acos())
                .fold(f32::INFINITY, f32::min);
            (chunk, angle)
        })
        .collect()
}

fn direction(longitude: f32, latitude: f32) -> Vec3 {
    let (lon, lat) = (longitude.to_radians(), latitude.to_radians());
    Vec3::new(lat.cos() * lon.cos(), lat.sin(), -lat.cos() * lon.sin())
}

#[test]
fn chunks_stream_to_the_horizon_over_a_pole_with_no_gap_and_no_duplicate() {
    let mut app = app(globe_config(8));
    let agent = app.world_mut().spawn((HexTerrainAgent::default(), Transform::default())).id();
    app.update();
    let globe = app.world().resource::<HexGlobe>().globe().expect("the config applied").clone();
    let radius = globe.radius() as f32;
    let max_elevation = globe.config().terrain.max_elevation;
    let all = globe.chunks().len();
    // Over the pole from 40 degrees north at longitude 0 to 40 north at 180, 1.6 radii out.
    for latitude in [40.0, 70.0, 90.0, 110.0, 140.0] {
        let (lon, lat) = if latitude > 90.0 { (180.0, 180.0 - latitude) } else { (0.0, latitude) };
        let at = direction(lon, lat) * radius * 1.6;
        app.world_mut().entity_mut(agent).insert(Transform::from_translation(at));
        // Streaming reads the agent's global transform, propagated at the end of the frame.
        app.update();
        run_until(&mut app, "the globe settled", |app| app.world().resource::<GlobeStreamer>().is_settled());
        let chunks = shown(&mut app);
        assert!(chunks.values().all(|&n| n == 1), "a chunk shown twice at latitude {latitude}");
        let limit = globe_horizon(radius, max_elevation, at.length());
        let mut far = 0;
        for (chunk, angle) in nearest_angles(&globe, at.normalize()) {
            if angle < limit - 1e-3 {
                assert!(
                    chunks.contains_key(&chunk),
                    "lat {latitude}: {chunk:?} in sight ({angle} < {limit}) is not shown"
                );
            }
            far += usize::from(angle > limit + 0.3);
            assert!(angle <= limit + 0.3 || !chunks.contains_key(&chunk), "{chunk:?} far beyond the horizon shown");
        }
        assert!(
            far > 0 && chunks.len() < all,
            "latitude {latitude}: the far side is culled ({} of {all})",
            chunks.len()
        );
        let kept: BTreeSet<GlobeChunk> = app.world().resource::<GlobeStreamer>().chunks().collect();
        assert_eq!(kept, chunks.keys().copied().collect(), "the streamer's chunks are the entities'");
    }
}

/// Every shown chunk's mesh positions (as bits, a border point once) and level, by chunk.
fn shown_meshes(app: &mut App) -> HashMap<GlobeChunk, (Detail, BTreeSet<[u32; 3]>, usize)> {
    let mut q = app.world_mut().query::<(&HexGlobeChunk, &Mesh3d)>();
    let meshes = app.world().resource::<Assets<Mesh>>();
    q.iter(app.world())
        .map(|(c, m)| {
            let mesh = meshes.get(&m.0).unwrap();
            let Some(VertexAttributeValues::Float32x3(p)) = mesh.attribute(Mesh::ATTRIBUTE_POSITION) else {
                panic!("a chunk without positions")
            };
            (c.chunk, (c.detail, p.iter().map(|v| v.map(f32::to_bits)).collect(), mesh.indices().unwrap().len() / 3))
        })
        .collect()
}

/// Levels of detail: with ground of a chunk nearer the agent than the coarse distance less the
/// hysteresis (measured here from the chunk's full mesh, on the sphere of height 0) the chunk is
/// full, with none within the distance and a tile more it is coarse, and each mesh is the core's
/// full or coarse mesh; at a planet's distance every chunk is coarse and draws a fraction of the
/// triangles; back near the ground the chunks under the agent are full again.
#[test]
fn chunks_far_from_the_agent_are_drawn_coarse() {
    let mut app = app(globe_config(8));
    let coarse_distance = 8.0;
    app.insert_resource(HexGlobeSettings { coarse_distance: Some(coarse_distance) });
    let agent = app.world_mut().spawn((HexTerrainAgent::default(), Transform::default())).id();
    app.update();
    let globe = app.world().resource::<HexGlobe>().globe().unwrap().clone();
    let (radius, hex) = (globe.radius() as f32, globe.config().layout.hex_size);
    let full_meshes: HashMap<GlobeChunk, GlobeMesh> =
        globe.chunks().into_iter().map(|c| (c, globe.generate(c))).collect();
    let bits = |m: &GlobeMesh| m.buffers.positions.iter().map(|v| v.map(f32::to_bits)).collect::<BTreeSet<_>>();
    let settle_at = |app: &mut App, at: Vec3| {
        app.world_mut().entity_mut(agent).insert(Transform::from_translation(at));
        app.update();
        run_until(app, "the levels", |app| app.world().resource::<GlobeStreamer>().is_settled());
        shown_meshes(app)
    };
    // Near the ground: some chunks full, some coarse.
    let at = direction(30.0, 20.0) * (radius + 3.0);
    let near = settle_at(&mut app, at);
    let mut levels = [0; 2];
    for (chunk, (detail, positions, _)) in &near {
        let full = &full_meshes[chunk];
        let nearest = full
            .buffers
            .positions
            .iter()
            .map(|&p| {
                let ground =
                    (Vec3::from_array(full.origin.map(|c| c as f32)) + Vec3::from_array(p)).normalize() * radius;
                ground.distance(at)
            })
            .fold(f32::INFINITY, f32::min);
        if nearest < coarse_distance * hex * 0.9 - 1e-3 {
            assert_eq!(*detail, Detail::Full, "{chunk:?}: ground {nearest} from the agent");
        } else if nearest > coarse_distance * hex + 2.0 * hex {
            assert_eq!(*detail, Detail::Coarse, "{chunk:?}: ground {nearest} from the agent");
        }
        let want = match detail {
            Detail::Full => bits(full),
            Detail::Coarse => bits(&full.coarse()),
        };
        assert!(*positions == want, "{chunk:?}: the mesh is not the core's {detail:?} mesh");
        levels[usize::from(*detail == Detail::Coarse)] += 1;
    }
    assert!(levels.iter().all(|&n| n > 0), "full and coarse chunks near the ground: {levels:?}");
    // A planet's distance: every chunk coarse, a fraction of the triangles.
    let far = settle_at(&mut app, direction(30.0, 20.0) * radius * 6.0);
    assert!(far.values().all(|(d, ..)| *d == Detail::Coarse), "a full chunk seen from afar");
    let drawn: usize = far.values().map(|(.., triangles)| triangles).sum();
    let full_triangles: usize = far.keys().map(|c| full_meshes[c].buffers.indices.len() / 3).sum();
    assert!(drawn * 2 < full_triangles, "{drawn} triangles drawn of {full_triangles}");
    // Back near the ground.
    let again = settle_at(&mut app, at);
    for (chunk, (detail, ..)) in &again {
        assert_eq!(detail, &near[chunk].0, "{chunk:?} at another level on coming back");
    }
}

#[cfg(feature = "picking")]
fn camera_app() -> (App, Entity) {
    let mut app = app(globe_config(4));
    app.insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_millis(50)));
    let camera = app.world_mut().spawn(GlobeCamera::above(0.0, 60f32.to_radians())).id();
    app.update();
    (app, camera)
}

#[cfg(feature = "picking")]
fn place(app: &App, camera: Entity) -> (Transform, GlobeCamera) {
    (*app.world().get::<Transform>(camera).unwrap(), *app.world().get::<GlobeCamera>(camera).unwrap())
}

// The camera reads Bevy's keyboard and mouse input, which come with the `picking` feature.
#[cfg(feature = "picking")]
#[test]
fn the_orbit_camera_crosses_a_pole_without_a_jump() {
    let (mut app, camera) = camera_app();
    let radius = app.world().resource::<HexGlobe>().globe().unwrap().radius() as f32;
    let (start, _) = place(&app, camera);
    assert!(start.translation.normalize().abs_diff_eq(direction(0.0, 60.0), 1e-4), "{:?}", start.translation);
    app.world_mut().resource_mut::<ButtonInput<KeyCode>>().press(KeyCode::ArrowUp);
    let (mut last, mut highest, mut frames) = (start, f32::MIN, 0);
    // North until the camera has passed the pole and come down to 60 degrees on the far side.
    loop {
        app.update();
        frames += 1;
        let (now, c) = place(&app, camera);
        let p = now.translation;
        assert!(p.is_finite() && (p.length() - (radius + c.altitude)).abs() < 1e-3, "{p:?}");
        // No jump: the view's up and forward turn a little a frame.
        assert!(now.up().dot(*last.up()) > 0.99 && now.forward().dot(*last.forward()) > 0.99, "a jump at {p:?}");
        highest = highest.max(p.normalize().y);
        last = now;
        if highest > 0.999 && p.normalize().y < 60f32.to_radians().sin() {
            break;
        }
        assert!(frames < 2_000, "the camera did not cross the pole");
    }
    // On the far side: longitude 180.
    let p = last.translation.normalize();
    assert!(p.x < -0.4 && p.z.abs() < 0.05, "{p:?}");
}

#[cfg(feature = "picking")]
#[test]
fn the_orbit_camera_zooms_turns_with_a_drag_and_tilts_near_the_ground() {
    let (mut app, camera) = camera_app();
    let (_, before) = place(&app, camera);
    app.world_mut().write_message(MouseWheel {
        unit: MouseScrollUnit::Line,
        x: 0.0,
        y: 3.0,
        window: Entity::PLACEHOLDER,
        phase: TouchPhase::Moved,
    });
    app.update();
    let (_, zoomed) = place(&app, camera);
    let expected = before.altitude * (1.0 - before.zoom_speed).powi(3);
    assert!((zoomed.altitude - expected).abs() < 1e-3, "{} for {expected}", zoomed.altitude);
    // Far out the view looks straight at the center.
    let (t, _) = place(&app, camera);
    assert!(t.forward().dot(-t.translation.normalize()) > 0.9999);
    // A drag to the right moves the globe with the pointer: the view goes west.
    let lon = |t: Transform| (-t.translation.z).atan2(t.translation.x);
    let west = lon(t);
    app.world_mut().resource_mut::<ButtonInput<MouseButton>>().press(MouseButton::Left);
    app.world_mut().write_message(MouseMotion { delta: Vec2::new(80.0, 0.0) });
    app.update();
    let (dragged, _) = place(&app, camera);
    assert!(lon(dragged) < west - 0.05, "{} then {}", west, lon(dragged));
    app.world_mut().resource_mut::<ButtonInput<MouseButton>>().release(MouseButton::Left);
    // Down to the lowest altitude: the view tilts by max_tilt toward the horizon.
    for _ in 0..100 {
        app.world_mut().write_message(MouseWheel {
            unit: MouseScrollUnit::Line,
            x: 0.0,
            y: 5.0,
            window: Entity::PLACEHOLDER,
            phase: TouchPhase::Moved,
        });
        app.update();
    }
    let (low, c) = place(&app, camera);
    assert_eq!(c.altitude, c.min_altitude);
    let tilt = low.forward().dot(-low.translation.normalize()).clamp(-1.0, 1.0).acos();
    assert!((tilt - c.max_tilt).abs() < 1e-3, "tilt {tilt} for {}", c.max_tilt);
}

#[test]
fn a_flat_map_config_is_refused_by_name() {
    let mut app = app(MapConfig { size: MapSize::Bounded { x: 8, z: 8 }, ..MapConfig::default() });
    app.update();
    assert!(app.world().resource::<HexGlobe>().globe().is_none());
    let errors: Vec<HexMapError> = app.world_mut().resource_mut::<Messages<HexMapError>>().drain().collect();
    assert!(errors.iter().any(|e| matches!(e, HexMapError::Invalid { field, .. } if field == "size")), "{errors:?}");
}

/// Updates until every chunk of the globe (no agent: the whole globe) shows generation
/// `generation`.
fn settled_at(app: &mut App, generation: u64) {
    run_until(app, "the globe settled", |app| {
        app.world().resource::<HexGlobe>().generation() == generation
            && app.world().resource::<GlobeStreamer>().is_settled()
    });
    let mut q = app.world_mut().query::<&HexGlobeChunk>();
    assert!(q.iter(app.world()).all(|c| c.generation == Some(generation)));
}

#[test]
fn a_globe_file_loads_hot_reloads_and_a_broken_reload_keeps_the_globe() {
    let dir = std::env::temp_dir().join(format!("hexterrain-globe-file-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("globe.map.ron");
    std::fs::write(&file, "(seed: 2, size: Globe(frequency: 4), chunk_size: (2, 2), terrain: (inner_rings: 1))")
        .unwrap();
    let mut app = App::new();
    let assets =
        AssetPlugin { file_path: dir.display().to_string(), watch_for_changes_override: Some(false), ..default() };
    app.add_plugins((MinimalPlugins, assets, TransformPlugin, HexGlobePlugin::from_asset("globe.map.ron")));
    keep::<HexMapError>(&mut app);
    keep::<TerrainReady>(&mut app);
    keep::<TerrainSettled>(&mut app);
    settled_at(&mut app, 1);
    let globe = app.world().resource::<HexGlobe>().globe().unwrap().clone();
    assert_eq!(shown(&mut app).len(), globe.chunks().len(), "no agent: the whole globe");
    // A hot reload with another seed: every chunk is built again.
    let id = app.world().resource::<Assets<HexMapAsset>>().ids().next().unwrap();
    let mut config = globe.config().clone();
    config.seed = 3;
    let asset = |config: MapConfig| HexMapAsset { config, image: None, ruleset: None, appearance_fallback: false };
    app.world_mut().resource_mut::<Assets<HexMapAsset>>().insert(id, asset(config.clone())).unwrap();
    settled_at(&mut app, 2);
    assert_eq!(app.world().resource::<HexGlobe>().globe().unwrap().config().seed, 3);
    // A flat map's config in the file: refused by name, the globe kept.
    let flat = MapConfig { size: MapSize::Bounded { x: 8, z: 8 }, ..config.clone() };
    app.world_mut().resource_mut::<Assets<HexMapAsset>>().insert(id, asset(flat)).unwrap();
    for _ in 0..5 {
        app.update();
    }
    assert!(
        seen::<HexMapError>(&app).iter().any(|e| matches!(e, HexMapError::Invalid { field, .. } if field == "size"))
    );
    assert_eq!(app.world().resource::<HexGlobe>().generation(), 2);
    // Malformed RON on disk: refused (once) with its line and column, the globe kept.
    std::fs::write(&file, "(seed: 2,\n size: Globe(frequency: ))").unwrap();
    app.world().resource::<AssetServer>().reload("globe.map.ron");
    let malformed = |app: &App| {
        seen::<HexMapError>(app).iter().filter(|e| e.to_string().contains("malformed map config at 2:24")).count()
    };
    run_until(&mut app, "the malformed file refused", |app| malformed(app) > 0);
    for _ in 0..20 {
        app.update();
    }
    assert_eq!(malformed(&app), 1, "said once: {:?}", seen::<HexMapError>(&app));
    assert_eq!(app.world().resource::<HexGlobe>().generation(), 2);
    assert!(app.world().resource::<GlobeStreamer>().is_settled());
    // One globe so far: ready once, settled after the load and after the hot reload.
    assert_eq!(app.world().resource::<HexGlobe>().map_id(), 1);
    assert_eq!(seen::<TerrainReady>(&app), vec![TerrainReady { map_id: 1, generation: 1 }]);
    assert_eq!(seen::<TerrainSettled>(&app), vec![TerrainSettled { generation: 1 }, TerrainSettled { generation: 2 }]);

    // Another globe's file (`LoadHexMap`): another map id, ready when its chunks are in, the
    // tile states started afresh on its tiles.
    std::fs::write(
        dir.join("other.map.ron"),
        "(seed: 5, size: Globe(frequency: 5), chunk_size: (2, 2), terrain: (inner_rings: 1))",
    )
    .unwrap();
    app.world_mut().write_message(LoadHexMap(MapSource::Asset("other.map.ron".into())));
    settled_at(&mut app, 3);
    assert_eq!(app.world().resource::<HexGlobe>().map_id(), 2);
    assert_eq!(app.world().resource::<HexGlobe>().globe().unwrap().grid().frequency(), 5);
    assert_eq!(seen::<TerrainReady>(&app).last(), Some(&TerrainReady { map_id: 2, generation: 3 }));
    assert_eq!(app.world().resource::<GlobeTileStates>().tile_count(), 252);
    // The same file again: already loaded, applied at once as another globe.
    app.world_mut().write_message(LoadHexMap(MapSource::Asset("globe.map.ron".into())));
    std::fs::write(&file, "(seed: 2, size: Globe(frequency: 4), chunk_size: (2, 2), terrain: (inner_rings: 1))")
        .unwrap();
    app.world().resource::<AssetServer>().reload("globe.map.ron");
    settled_at(&mut app, 4);
    assert_eq!(app.world().resource::<HexGlobe>().map_id(), 3);
    // A config in code that is no globe: refused by name, the globe and its id kept.
    let flat = MapConfig { size: MapSize::Bounded { x: 8, z: 8 }, ..MapConfig::default() };
    app.world_mut().write_message(LoadHexMap(MapSource::Config(Box::new(flat))));
    app.update();
    assert_eq!(app.world().resource::<HexGlobe>().map_id(), 3);
    assert_eq!(app.world().resource::<HexGlobe>().generation(), 4);
    let refused = seen::<HexMapError>(&app);
    assert!(matches!(refused.last(), Some(HexMapError::Invalid { field, .. }) if field == "size"), "{refused:?}");
    // A globe config in code: another globe at once.
    app.world_mut().write_message(LoadHexMap(MapSource::Config(Box::new(globe_config(3)))));
    settled_at(&mut app, 5);
    assert_eq!(app.world().resource::<HexGlobe>().map_id(), 4);
    assert_eq!(seen::<TerrainReady>(&app).last(), Some(&TerrainReady { map_id: 4, generation: 5 }));
}

/// The ray the test's pointer casts this frame.
#[cfg(feature = "picking")]
#[derive(Resource, Default)]
struct PointerRay(Option<(Entity, Ray3d)>);

/// The globe hits reported for the mouse this frame.
#[cfg(feature = "picking")]
#[derive(Resource, Default)]
struct Hits(Vec<(Entity, bevy::picking::backend::HitData)>);

/// Picking at each of the twelve pentagons (a ray straight down from three radii out) and at
/// tiles toward the limb (55 to 66 degrees from under the camera; the horizon is at 70.5): each
/// ray aimed at a tile's center reports that tile, the tile `tile_at` gives for the direction
/// it was aimed at, on the entity of the chunk holding it, and the mouse's hovered tile follows.
/// The relief is kept low so that no tile hides another's center.
#[cfg(feature = "picking")]
#[test]
fn picking_returns_the_tile_at_every_pentagon_and_near_the_limb() {
    use bevy::math::DVec3;
    use bevy::picking::backend::PointerHits;
    use bevy::picking::backend::ray::{RayId, RayMap};
    use bevy::picking::pointer::PointerId;
    use bevy::picking::{InteractionPlugin, PickingPlugin, PickingSystems};
    use bevy_hex_terrain::hex_terrain::GlobeTile;
    use bevy_hex_terrain::{HexGlobePick, HoveredGlobeTile};

    let mut config = globe_config(6);
    config.terrain.max_elevation = 0.01;
    let mut app = app(config);
    app.add_plugins((PickingPlugin, InteractionPlugin)).init_resource::<PointerRay>().init_resource::<Hits>();
    app.add_systems(
        PreUpdate,
        (|ray: Res<PointerRay>, mut map: ResMut<RayMap>| {
            if let Some((camera, ray)) = ray.0 {
                map.map.insert(RayId::new(camera, PointerId::Mouse), ray);
            }
        })
        .after(PickingSystems::ProcessInput)
        .before(PickingSystems::Backend),
    );
    app.add_systems(Last, |mut reader: MessageReader<PointerHits>, mut hits: ResMut<Hits>| {
        hits.0 = reader.read().filter(|h| h.pointer == PointerId::Mouse).flat_map(|h| h.picks.clone()).collect();
    });
    app.world_mut().spawn(PointerId::Mouse);
    let camera = app.world_mut().spawn((Camera::default(), Transform::default(), HexTerrainAgent::default())).id();
    app.update();
    let globe = app.world().resource::<HexGlobe>().globe().expect("the config applied").clone();
    let grid = globe.grid();
    let pentagons: Vec<GlobeTile> = grid.tiles().filter(|&t| grid.is_pentagon(t)).collect();
    assert_eq!(pentagons.len(), 12);
    let radius = globe.radius();
    let (mut limb, mut picked) = (0, 0);
    for pentagon in pentagons {
        let up = DVec3::from_array(grid.center(pentagon).unwrap());
        let eye = up * radius * 3.0;
        app.world_mut().entity_mut(camera).insert(Transform::from_translation(eye.as_vec3()));
        app.update();
        run_until(&mut app, "the globe settled", |app| app.world().resource::<GlobeStreamer>().is_settled());
        let toward_limb = grid.tiles().filter(|&t| {
            let angle = DVec3::from_array(grid.center(t).unwrap()).dot(up).clamp(-1.0, 1.0).acos().to_degrees();
            (55.0..66.0).contains(&angle)
        });
        for tile in std::iter::once(pentagon).chain(toward_limb.step_by(3)) {
            let center = DVec3::from_array(grid.center(tile).unwrap());
            assert_eq!(globe.tile_at(center.to_array()), Some(tile));
            let aim = (center * radius - eye).normalize();
            let ray = Ray3d::new(eye.as_vec3(), Dir3::new(aim.as_vec3()).unwrap());
            app.world_mut().resource_mut::<PointerRay>().0 = Some((camera, ray));
            app.update();
            let hits = &app.world().resource::<Hits>().0;
            assert_eq!(hits.len(), 1, "one hit for {tile:?}");
            let (entity, hit) = &hits[0];
            let pick = hit.extra_as::<HexGlobePick>().expect("a globe pick");
            assert_eq!(pick.tile, tile, "the ray aimed at {tile:?} (pentagon {pentagon:?} below)");
            let chunk = globe.chunk_of(tile).unwrap();
            assert_eq!(pick.chunk, chunk);
            assert_eq!(Some(*entity), app.world().resource::<GlobeStreamer>().chunk(chunk));
            assert!((pick.world.length() - radius).abs() < 0.02, "on the surface: {}", pick.world.length());
            assert_eq!(app.world().resource::<HoveredGlobeTile>().tile(), Some(tile));
            limb += usize::from(tile != pentagon);
            picked += 1;
        }
    }
    assert!(limb > 60, "{limb} tiles toward the limb of {picked} picked");
    // The sky: no hit, no hovered tile.
    app.world_mut().resource_mut::<PointerRay>().0 = Some((camera, Ray3d::new(Vec3::splat(1e3), Dir3::X)));
    app.update();
    assert!(app.world().resource::<Hits>().0.is_empty());
    assert_eq!(app.world().resource::<HoveredGlobeTile>().tile(), None);
}

/// Where the surface as meshed lies along `up` (a unit vector), by the core's ray cast down.
fn surface_along(globe: &GlobeTerrain, up: bevy::math::DVec3) -> f64 {
    let above = up * (globe.radius() + 10.0);
    let hit = globe.raycast(above.to_array(), (-up).to_array(), f64::MAX).expect("the ray meets the globe");
    bevy::math::DVec3::from_array(hit.point).length()
}

/// A unit walks from a neighbor of a pentagon through the pentagon to another of its neighbors:
/// every frame it stands on the surface as meshed (its distance from the center the surface's
/// along its direction, found by the core's ray cast), its up the globe's up there, and it
/// enters the tiles in order, then the walk ends on the last. A unit standing on the pentagon
/// stays on its center through an edit that raises the tile.
#[test]
fn units_stand_on_their_tiles_and_walk_across_a_pentagon() {
    use bevy::math::DVec3;
    use bevy_hex_terrain::hex_terrain::{GlobeTile, TileEdit};
    use bevy_hex_terrain::{GlobeTileWalk, GlobeWalkEnded, OnGlobeTile};

    #[derive(Resource, Default)]
    struct Ended(Vec<GlobeTile>);

    let config = globe_config(6);
    let mut app = app(config.clone());
    app.insert_resource(bevy::time::TimeUpdateStrategy::ManualDuration(std::time::Duration::from_millis(50)))
        .init_resource::<Ended>()
        .add_observer(|ended: On<GlobeWalkEnded>, mut all: ResMut<Ended>| all.0.push(ended.tile));
    app.update();
    let globe = app.world().resource::<HexGlobe>().globe().expect("the config applied").clone();
    let grid = globe.grid();
    let pentagon = grid.tiles().find(|&t| grid.is_pentagon(t) && t != GlobeTile(0)).unwrap();
    let around = grid.neighbors(pentagon).unwrap().as_slice().to_vec();
    assert_eq!(around.len(), 5);
    let (from, to) = (around[0], around[2]);
    let walker = app.world_mut().spawn((OnGlobeTile::new(from), GlobeTileWalk::new([pentagon, to], 3.0))).id();
    let stander = app.world_mut().spawn(OnGlobeTile::new(pentagon)).id();
    let mut entered = vec![from];
    for _ in 0..400 {
        app.update();
        let transform = *app.world().get::<Transform>(walker).unwrap();
        let at = transform.translation.as_dvec3();
        let surface = surface_along(&globe, at.normalize());
        assert!((at.length() - surface).abs() < 1e-3, "off the surface: {} against {surface}", at.length());
        assert!((transform.rotation * Vec3::Y).abs_diff_eq(at.normalize().as_vec3(), 1e-4), "its up is the globe's");
        let tile = app.world().get::<OnGlobeTile>(walker).unwrap().tile;
        if entered.last() != Some(&tile) {
            entered.push(tile);
        }
        if !app.world().resource::<Ended>().0.is_empty() {
            break;
        }
    }
    assert_eq!(entered, [from, pentagon, to], "the tiles entered");
    assert_eq!(app.world().resource::<Ended>().0, [to]);
    assert!(app.world().get::<GlobeTileWalk>(walker).is_none(), "the walk is over");

    let stands = |app: &App, globe: &GlobeTerrain| {
        let at = app.world().get::<Transform>(stander).unwrap().translation.as_dvec3();
        let center = DVec3::from_array(globe.grid().center(pentagon).unwrap());
        let want = center * (globe.radius() + f64::from(globe.tile_info(pentagon).unwrap().elevation));
        assert!(at.abs_diff_eq(want, 1e-3), "on its center: {at} against {want}");
        at.length()
    };
    let before = stands(&app, &globe);
    let mut edited = config;
    edited.edits = vec![TileEdit { height: Some(0.95), ..TileEdit::at(pentagon.at()) }];
    app.world_mut().resource_mut::<HexGlobe>().apply(edited).expect("a valid edit");
    app.update();
    let globe = app.world().resource::<HexGlobe>().globe().unwrap().clone();
    let after = stands(&app, &globe);
    assert!(after > before + 0.1, "raised with its tile: {before} to {after}");
}
