//! Headless `App` tests of the picking backend (`HexPickingPlugin`): a synthetic pointer's ray
//! (written into Bevy's `RayMap` as a window's pointer would be) yields `PointerHits` on the chunk
//! showing the hit, with the tile the map's queries give and a position on the surface; the sky
//! yields nothing; an observer on a chunk gets `Pointer<Click>` with the tile; `Pickable::IGNORE`
//! removes the hits.

#![cfg(feature = "picking")]

use bevy::asset::AssetPlugin;
use bevy::camera::NormalizedRenderTarget;
use bevy::math::DVec3;
use bevy::picking::backend::ray::{RayId, RayMap};
use bevy::picking::backend::{HitData, PointerHits};
use bevy::picking::events::{Click, Pointer};
use bevy::picking::pointer::{Location, PointerAction, PointerButton, PointerId, PointerInput};
use bevy::picking::{InteractionPlugin, Pickable, PickingPlugin, PickingSystems};
use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;
use bevy_hex_terrain::{HexPick, HexStreamingSettings};

mod common;

use common::run_until;

const POINTER: PointerId = PointerId::Touch(7);

/// The ray the synthetic pointer casts this frame (world space of the render frame).
#[derive(Resource, Default)]
struct PointerRay(Option<Ray3d>);

/// Every terrain hit reported, this frame.
#[derive(Resource, Default)]
struct Hits(Vec<(Entity, HitData)>);

/// Clicks an observer on a chunk received: the chunk and the tile.
#[derive(Resource, Default)]
struct Clicks(Vec<(Entity, Hex)>);

/// The ground alone: no water surface, no props (the tests of what stands on it turn them on).
fn app(config: MapConfig) -> App {
    let mut app = app_with(config, HexStreamingSettings { load_radius: 1, ..default() });
    app.insert_resource(HexWaterSettings { enabled: false, ..default() });
    app.insert_resource(HexPropSettings { enabled: false, ..default() });
    app
}

fn app_with(config: MapConfig, settings: HexStreamingSettings) -> App {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, AssetPlugin::default(), TransformPlugin, PickingPlugin, InteractionPlugin));
    app.insert_resource(settings);
    app.add_plugins(HexTerrainPlugins::new(config).build().disable::<HexTerrainMaterialPlugin>());
    app.init_resource::<Clicks>();
    add_pointer(&mut app);
    app.world_mut().spawn((HexTerrainAgent::default(), Transform::default()));
    app
}

/// The synthetic pointer, the system casting its ray and the collection of its hits.
fn add_pointer(app: &mut App) {
    app.init_resource::<PointerRay>().init_resource::<Hits>();
    app.add_systems(PreUpdate, cast.after(PickingSystems::ProcessInput).before(PickingSystems::Backend));
    app.add_systems(Last, |mut reader: MessageReader<PointerHits>, mut hits: ResMut<Hits>| {
        hits.0 = reader.read().filter(|h| h.pointer == POINTER).flat_map(|h| h.picks.clone()).collect();
    });
    app.world_mut().spawn(POINTER);
}

/// The synthetic pointer: its ray, for the first camera, as `RayMap::repopulate` would insert a
/// window pointer's.
fn cast(ray: Res<PointerRay>, cameras: Query<Entity, With<Camera>>, mut map: ResMut<RayMap>) {
    let (Some(ray), Some(camera)) = (ray.0, cameras.iter().next()) else { return };
    map.map.insert(RayId::new(camera, POINTER), ray);
}

fn location() -> Location {
    Location { target: NormalizedRenderTarget::None { width: 640, height: 480 }, position: Vec2::new(320.0, 240.0) }
}

fn loaded(app: &mut App) -> bool {
    let streamer = app.world().resource::<ChunkStreamer>();
    streamer.wanted().next().is_some() && streamer.wanted().all(|(c, _)| streamer.is_chunk_loaded(c))
}

/// Points the pointer straight down at world `(x, z)` and runs a frame.
fn point_at(app: &mut App, x: f32, z: f32) -> Vec<(Entity, HitData)> {
    app.world_mut().resource_mut::<PointerRay>().0 = Some(Ray3d::new(Vec3::new(x, 80.0, z), Dir3::NEG_Y));
    app.update();
    app.world().resource::<Hits>().0.clone()
}

fn map_config() -> MapConfig {
    MapConfig { size: MapSize::Bounded { x: 40, z: 30 }, chunk_size: (8, 8), ..MapConfig::default() }
}

#[test]
fn pointer_hits_carry_the_tile_on_the_surface() {
    let mut app = app(map_config());
    app.world_mut().spawn((Camera::default(), Transform::from_xyz(0.0, 50.0, 0.0)));
    run_until(&mut app, "the chunks around the agent", loaded);
    let map = app.world().resource::<HexMap>().clone();
    let mut checked = 0;
    for (x, z) in [(0.4, 0.3), (2.2, 1.9), (5.0, 3.7), (-0.6, 1.2), (7.3, 6.1)] {
        let hits = point_at(&mut app, x, z);
        let expected = DVec3::new(f64::from(x), 0.0, f64::from(z));
        let Some(tile) = map.tile_at_f64(expected).filter(|&t| map.contains(t)) else {
            assert!(hits.is_empty(), "({x}, {z}) is off the map: no hit");
            continue;
        };
        assert_eq!(hits.len(), 1, "one terrain hit at ({x}, {z})");
        let (entity, hit) = &hits[0];
        let pick = hit.extra_as::<HexPick>().expect("the tile rides with the hit");
        assert_eq!(pick.tile, tile);
        let chunk = app.world().entity(*entity).get::<HexChunk>().expect("the hit is on a chunk entity");
        assert_eq!(Some(chunk.coord), map.chunk_of(tile));
        let position = hit.position.unwrap();
        let surface = map.surface_height_f64(position.as_dvec3()).unwrap();
        assert!((f64::from(position.y) - surface).abs() < 1e-3, "{position} on the surface at {surface}");
        assert!((position.x - x).abs() < 1e-4 && (position.z - z).abs() < 1e-4);
        assert!((hit.depth - (80.0 - position.y)).abs() < 1e-3, "depth along the ray");
        let normal = hit.normal.unwrap();
        assert!((normal.length() - 1.0).abs() < 1e-4 && normal.y > 0.0);
        checked += 1;
    }
    assert!(checked >= 4, "{checked} points on the map");
    // Looking at the sky: nothing.
    app.world_mut().resource_mut::<PointerRay>().0 = Some(Ray3d::new(Vec3::new(3.0, 5.0, 3.0), Dir3::Y));
    app.update();
    assert!(app.world().resource::<Hits>().0.is_empty(), "the sky is not terrain");
}

#[test]
fn a_chunk_observer_gets_the_click_with_its_tile_and_pickable_ignore_removes_hits() {
    let mut app = app(map_config());
    app.world_mut().spawn((Camera::default(), Transform::from_xyz(0.0, 50.0, 0.0)));
    run_until(&mut app, "the chunks around the agent", loaded);
    let map = app.world().resource::<HexMap>().clone();
    let (x, z) = (2.2, 1.9);
    let tile = map.tile_at_f64(DVec3::new(f64::from(x), 0.0, f64::from(z))).unwrap();
    let chunk = app.world().resource::<ChunkStreamer>().entity(map.chunk_of(tile).unwrap()).unwrap();
    app.world_mut().entity_mut(chunk).observe(|click: On<Pointer<Click>>, mut clicks: ResMut<Clicks>| {
        let pick = click.hit.extra_as::<HexPick>().unwrap();
        clicks.0.push((click.entity, pick.tile));
    });
    assert_eq!(point_at(&mut app, x, z).len(), 1);
    for action in [PointerAction::Press(PointerButton::Primary), PointerAction::Release(PointerButton::Primary)] {
        app.world_mut().write_message(PointerInput::new(POINTER, location(), action));
        point_at(&mut app, x, z);
    }
    assert_eq!(app.world().resource::<Clicks>().0, vec![(chunk, tile)], "one click on the chunk, with its tile");

    app.world_mut().entity_mut(chunk).insert(Pickable::IGNORE);
    assert!(point_at(&mut app, x, z).is_empty(), "an ignored chunk is not hit");
    app.world_mut().entity_mut(chunk).remove::<Pickable>();
    assert_eq!(point_at(&mut app, x, z).len(), 1);
    // Off: nothing.
    app.world_mut().resource_mut::<bevy_hex_terrain::HexPickingSettings>().enabled = false;
    assert!(point_at(&mut app, x, z).is_empty());
}

/// A ray down onto a prop hits the prop (its unit box: headless props have no mesh) before the
/// ground, on the prop entity, with the tile it stands on; a hidden prop or one with
/// `Pickable::IGNORE` lets the ray through to the ground. A ray onto the sea hits its water
/// surface at sea level, on the water entity, unless that is ignored.
#[test]
fn props_and_the_sea_surface_come_before_the_ground() {
    let mut app = app_with(map_config(), HexStreamingSettings { load_radius: 1, ..default() });
    app.world_mut().spawn((Camera::default(), Transform::from_xyz(0.0, 50.0, 0.0)));
    run_until(&mut app, "the chunks around the agent", loaded);
    app.update();
    let map = app.world().resource::<HexMap>().clone();
    let props: Vec<(Entity, HexProp, Vec3, Vec3)> = app
        .world_mut()
        .query::<(Entity, &HexProp, &GlobalTransform)>()
        .iter(app.world())
        .map(|(e, p, t)| (e, *p, t.translation(), t.scale()))
        .collect();
    assert!(props.len() > 10, "{} props", props.len());
    let mut checked = 0;
    for &(entity, prop, at, scale) in props.iter().step_by(props.len() / 8) {
        // Straight down onto the prop's middle: the top of its box.
        let hits = point_at(&mut app, at.x, at.z);
        assert_eq!(hits.len(), 1);
        let (hit_entity, hit) = &hits[0];
        if *hit_entity != entity {
            // Another prop's box stands in the way; it must be one.
            assert!(app.world().entity(*hit_entity).contains::<HexProp>(), "{hit_entity} for the prop {entity}");
            continue;
        }
        let pick = hit.extra_as::<HexPick>().unwrap();
        assert_eq!(pick.tile, prop.tile, "the tile the prop stands on");
        let top = at.y + scale.y;
        assert!((hit.position.unwrap().y - top).abs() < 1e-3, "{:?} at the top of the box {top}", hit.position);
        assert!(hit.depth < 80.0 - at.y, "before the ground");
        // Ignored, then hidden: the ground behind it.
        app.world_mut().entity_mut(entity).insert(Pickable::IGNORE);
        let through = point_at(&mut app, at.x, at.z);
        assert!(through.iter().all(|(e, _)| *e != entity), "an ignored prop is not hit");
        app.world_mut().entity_mut(entity).remove::<Pickable>().insert(Visibility::Hidden);
        let through = point_at(&mut app, at.x, at.z);
        assert!(through.iter().all(|(e, _)| *e != entity), "a hidden prop is not hit");
        app.world_mut().entity_mut(entity).insert(Visibility::Inherited);
        checked += 1;
    }
    assert!(checked >= 3, "{checked} props checked");

    // The sea: a sea tile's center, straight down.
    let sea = map.terrain().tiles().find(|&t| {
        map.tile_kind(t) == Some(TileKind::Sea) && {
            let c = map.tile_center(t).unwrap();
            c.x.abs() < 8.0 && c.z.abs() < 8.0
        }
    });
    let Some(sea) = sea else { panic!("no sea tile near the agent") };
    let c = map.tile_center(sea).unwrap();
    let hits = point_at(&mut app, c.x, c.z);
    assert_eq!(hits.len(), 1);
    let (water, hit) = &hits[0];
    assert!(app.world().entity(*water).contains::<HexWater>(), "the sea's surface is hit");
    assert_eq!(hit.extra_as::<HexPick>().unwrap().tile, sea);
    let level = map.terrain().sea_level();
    assert!((hit.position.unwrap().y - level).abs() < 1e-3, "at sea level {level}: {:?}", hit.position);
    app.world_mut().entity_mut(*water).insert(Pickable::IGNORE);
    let hits = point_at(&mut app, c.x, c.z);
    assert_eq!(hits.len(), 1);
    assert!(app.world().entity(hits[0].0).contains::<HexChunk>(), "through an ignored surface, the floor");
    assert!(hits[0].1.position.unwrap().y < level);
}

/// A million units out, with `big_space`: the floating origin's cell is the render frame's
/// origin, and the hit's tile is the one under the pointer's f64 position.
#[cfg(feature = "big_space")]
#[test]
fn picking_is_exact_a_million_units_out_with_big_space() {
    use bevy_hex_terrain::{HexBigSpacePlugin, HexTerrainGrid};
    use big_space::prelude::*;

    let config = MapConfig { size: MapSize::Unbounded, ..MapConfig::default() };
    let mut app = App::new();
    // The input plugin: big_space's camera controller reads the keyboard.
    let input = bevy::input::InputPlugin;
    app.add_plugins((MinimalPlugins, AssetPlugin::default(), input, PickingPlugin, InteractionPlugin));
    app.add_plugins(BigSpaceDefaultPlugins);
    let settings = HexStreamingSettings { load_radius: 1, ..default() };
    app.insert_resource(settings);
    app.add_plugins(HexTerrainPlugins::new(config).build().disable::<HexTerrainMaterialPlugin>());
    app.add_plugins(HexBigSpacePlugin);
    add_pointer(&mut app);
    let far = DVec3::new(1.0e6 + 0.37, 0.0, -1.0e6 - 0.21);
    let mut camera_cell = CellCoord::default();
    let mut commands = app.world_mut().commands();
    commands.spawn_big_space(Grid::default(), |grid| {
        grid.insert(HexTerrainGrid);
        let (cell, local) = grid.grid().translation_to_grid(far + DVec3::Y * 50.0);
        camera_cell = cell;
        grid.spawn_spatial((
            Camera::default(),
            FloatingOrigin,
            HexTerrainAgent::default(),
            cell,
            Transform::from_translation(local),
        ));
    });
    app.world_mut().flush();
    app.update();
    run_until(&mut app, "the chunks around the far camera", loaded);
    let map = app.world().resource::<HexMap>().clone();
    let origin = Grid::default().cell_to_float(&camera_cell);
    for (dx, dz) in [(0.0, 0.0), (1.3, -0.8), (-2.1, 2.6)] {
        let at = far + DVec3::new(dx, 0.0, dz);
        let local = (at - origin).as_vec3();
        app.world_mut().resource_mut::<PointerRay>().0 = Some(Ray3d::new(local + Vec3::Y * 80.0, Dir3::NEG_Y));
        app.update();
        let hits = app.world().resource::<Hits>().0.clone();
        assert_eq!(hits.len(), 1, "one hit at {at}");
        let pick = hits[0].1.extra_as::<HexPick>().unwrap();
        assert_eq!(Some(pick.tile), map.tile_at_f64(at), "the tile under {at}");
        assert!((pick.world.x - at.x).abs() < 1e-6 && (pick.world.z - at.z).abs() < 1e-6, "{} vs {at}", pick.world);
        let surface = map.surface_height_f64(pick.world).unwrap();
        assert!((pick.world.y - surface).abs() < 1e-3);
        let position = hits[0].1.position.unwrap();
        assert!((position - local).xz().length() < 1e-3, "the position is in the render frame: {position} vs {local}");
    }
}
