//! Headless `App` tests of the minimap (`HexMinimapPlugin`): the image's pixels have the tiles'
//! colors and unexplored tiles are black; a `TileStates` write changes, in the next frame,
//! exactly the pixels of the tiles it touches (and of their neighbors' borders), as a full paint
//! would; a press on a minimap pixel sends the camera to that pixel's tile.

#![cfg(feature = "minimap")]

use bevy::asset::AssetPlugin;
use bevy::camera::NormalizedRenderTarget;
use bevy::picking::backend::{HitData, PointerHits};
use bevy::picking::pointer::{Location, PointerAction, PointerButton, PointerId, PointerInput};
use bevy::picking::{InteractionPlugin, PickingPlugin, PickingSystems};
use bevy::prelude::*;
use bevy_hex_terrain::hex_terrain;
use bevy_hex_terrain::hex_terrain::minimap::TileLook;
use bevy_hex_terrain::prelude::*;
use bevy_hex_terrain::{HexMinimap, MinimapPicture};

mod common;

use common::run_until;

const POINTER: PointerId = PointerId::Touch(3);

/// Where on the minimap node the synthetic pointer is (`-0.5..0.5`), if on it.
#[derive(Resource, Default)]
struct OnMinimap(Option<Vec2>);

/// Every `MinimapNavigate` received.
#[derive(Resource, Default)]
struct Navigations(Vec<MinimapNavigate>);

fn app(config: MapConfig) -> App {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, AssetPlugin::default(), TransformPlugin, PickingPlugin, InteractionPlugin));
    app.init_asset::<Image>();
    let settings = HexStreamingSettings { load_radius: 1, ..default() };
    app.insert_resource(settings);
    app.add_plugins(HexTerrainPlugins::new(config).build().disable::<HexTerrainMaterialPlugin>());
    app.add_plugins(HexMinimapPlugin);
    // The minimap draws fog of war as the terrain does: while the tile states' style has it on.
    app.insert_resource(HexTileStateStyle { fog_of_war: true, ..default() });
    app.init_resource::<OnMinimap>().init_resource::<Navigations>();
    // The UI backend's hit, as Bevy's reports it: the node and the position on it.
    app.add_systems(
        PreUpdate,
        (|on: Res<OnMinimap>, nodes: Query<Entity, With<HexMinimap>>, mut hits: MessageWriter<PointerHits>| {
            let (Some(at), Ok(node)) = (on.0, nodes.single()) else { return };
            let hit = HitData::new(node, 0.0, Some(at.extend(0.0)), None);
            hits.write(PointerHits::new(POINTER, vec![(node, hit)], 10.0));
        })
        .in_set(PickingSystems::Backend),
    );
    app.add_systems(Last, |mut read: MessageReader<MinimapNavigate>, mut all: ResMut<Navigations>| {
        all.0.extend(read.read().copied());
    });
    app.world_mut().spawn(POINTER);
    app.world_mut().spawn((HexTerrainAgent::default(), Transform::default()));
    app
}

fn config() -> MapConfig {
    MapConfig { size: MapSize::Bounded { x: 30, z: 20 }, ..MapConfig::default() }
}

fn built(app: &mut App) -> bool {
    app.world().resource::<MinimapPicture>().minimap().is_some()
}

/// The image the node shows.
fn image(app: &App) -> Vec<u8> {
    let handle = app.world().resource::<MinimapPicture>().image().clone();
    app.world().resource::<Assets<Image>>().get(&handle).unwrap().data.clone().unwrap()
}

fn look(states: &TileStates, t: Hex) -> TileLook {
    TileLook { fog: states.visibility(t), owner: states.owner(t) }
}

#[test]
fn pixels_have_the_tiles_colors_and_unexplored_tiles_are_black() {
    let mut app = app(config());
    run_until(&mut app, "the minimap's picture", built);
    app.update();
    let map = app.world().resource::<HexMap>().clone();
    let settings = app.world().resource::<HexMinimapSettings>().clone();
    let minimap = app.world().resource::<MinimapPicture>().minimap().unwrap().clone();
    let [w, h] = minimap.size();
    assert!(w <= settings.size.x && h <= settings.size.y && (w == settings.size.x || h == settings.size.y));
    // Nothing explored yet: every pixel on the map is black.
    let rgba = image(&app);
    assert_eq!(rgba.len(), (w * h * 4) as usize);
    let tiles: Vec<Hex> = map.terrain().tiles().collect();
    for &t in &tiles {
        for &i in minimap.pixels_of(t) {
            assert_eq!(&rgba[i as usize * 4..i as usize * 4 + 4], &[0, 0, 0, 255], "tile {t:?}");
        }
    }
    // A set of tiles in sight: their pixels take their type's color (no climate, no rivers).
    let shown: Vec<Hex> = tiles.iter().copied().step_by(7).collect();
    let mut states = app.world_mut().resource_mut::<TileStates>();
    for &t in &shown {
        states.set_visibility(t, FogState::Visible).unwrap();
    }
    app.update();
    let rgba = image(&app);
    let style = settings.style();
    for &t in &shown {
        let kind = map.tile_kind(t).unwrap();
        for &i in minimap.pixels_of(t) {
            assert_eq!(&rgba[i as usize * 4..i as usize * 4 + 3], &style.kind_colors[kind as usize][..], "tile {t:?}");
        }
    }
}

#[test]
fn a_write_changes_exactly_the_affected_pixels_in_the_next_frame() {
    let mut app = app(config());
    run_until(&mut app, "the minimap's picture", built);
    {
        let mut states = app.world_mut().resource_mut::<TileStates>();
        for tile in map_tiles(&config()) {
            states.set_visibility(tile, FogState::Visible).unwrap();
        }
    }
    app.update();
    app.update();
    let minimap = app.world().resource::<MinimapPicture>().minimap().unwrap().clone();
    let before = image(&app);
    let repainted = app.world().resource::<MinimapPicture>().repainted_pixels();
    // A frame without writes repaints nothing.
    app.update();
    assert_eq!(app.world().resource::<MinimapPicture>().repainted_pixels(), repainted);
    assert_eq!(image(&app), before);

    let tile = Hex::new(12, 3);
    {
        let mut states = app.world_mut().resource_mut::<TileStates>();
        states.set_owner(tile, Some(2)).unwrap();
        states.set_visibility(tile.all_neighbors()[0], FogState::Explored).unwrap();
    }
    app.update();
    let after = image(&app);
    let states = app.world().resource::<TileStates>();
    assert_eq!(after, minimap.paint(|t| look(states, t)), "the repaint equals a full paint");
    let mut near: Vec<u32> = minimap.pixels_of(tile).to_vec();
    for n in tile.all_neighbors() {
        near.extend_from_slice(minimap.pixels_of(n));
    }
    let changed: Vec<usize> =
        (0..after.len() / 4).filter(|&i| after[i * 4..i * 4 + 4] != before[i * 4..i * 4 + 4]).collect();
    assert!(!changed.is_empty());
    for i in &changed {
        assert!(near.contains(&(*i as u32)), "pixel {i} changed, away from the written tiles");
    }
    // Every pixel of the owned tile took its owner's tint or border.
    for &i in minimap.pixels_of(tile) {
        assert!(changed.contains(&(i as usize)), "pixel {i} of the owned tile did not change");
    }
    // The neighbor made explored is dimmed everywhere.
    for &i in minimap.pixels_of(tile.all_neighbors()[0]) {
        assert!(changed.contains(&(i as usize)));
    }
}

#[test]
fn a_press_on_the_minimap_sends_the_camera_to_that_tile() {
    let mut app = app(config());
    run_until(&mut app, "the minimap's picture", built);
    let map = app.world().resource::<HexMap>().clone();
    let minimap = app.world().resource::<MinimapPicture>().minimap().unwrap().clone();
    let [w, h] = minimap.size();
    for tile in [Hex::new(3, 2), Hex::new(20, -4), Hex::new(29, -10)] {
        assert!(map.contains(tile));
        let i = minimap.pixels_of(tile)[minimap.pixels_of(tile).len() / 2];
        let (px, py) = (i % w, i / w);
        let at = Vec2::new((px as f32 + 0.5) / w as f32 - 0.5, (py as f32 + 0.5) / h as f32 - 0.5);
        app.world_mut().resource_mut::<OnMinimap>().0 = Some(at);
        app.world_mut().resource_mut::<Navigations>().0.clear();
        app.update();
        for action in [PointerAction::Press(PointerButton::Primary), PointerAction::Release(PointerButton::Primary)] {
            app.world_mut().write_message(PointerInput::new(POINTER, location(), action));
            app.update();
        }
        let went = app.world().resource::<Navigations>().0.clone();
        assert_eq!(went.len(), 1, "one navigation for {tile:?}: {went:?}");
        assert_eq!(went[0].tile, tile);
        let world = Vec3::new(went[0].world.x as f32, 0.0, went[0].world.y as f32);
        assert_eq!(map.tile_at(world), Some(tile), "the world position is on the tile");
    }
    // Off the node: nothing.
    app.world_mut().resource_mut::<OnMinimap>().0 = None;
    app.world_mut().resource_mut::<Navigations>().0.clear();
    for action in [PointerAction::Press(PointerButton::Primary), PointerAction::Release(PointerButton::Primary)] {
        app.world_mut().write_message(PointerInput::new(POINTER, location(), action));
        app.update();
    }
    assert!(app.world().resource::<Navigations>().0.is_empty());
}

fn location() -> Location {
    Location { target: NormalizedRenderTarget::None { width: 640, height: 480 }, position: Vec2::new(600.0, 440.0) }
}

fn map_tiles(config: &MapConfig) -> Vec<Hex> {
    hex_terrain::Terrain::new(config.clone()).unwrap().tiles().collect()
}

/// `HexMinimapSettings` inserted before the plugin is added is kept (the plugin uses
/// `init_resource`, like every plugin of the crate).
#[test]
fn minimap_settings_inserted_first_are_kept() {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, AssetPlugin::default(), TransformPlugin, PickingPlugin, InteractionPlugin));
    app.init_asset::<Image>();
    let mine = HexMinimapSettings { size: UVec2::new(99, 77), explored_brightness: 0.25, ..default() };
    app.insert_resource(mine.clone());
    app.add_plugins(HexTerrainPlugins::new(config()).build().disable::<HexTerrainMaterialPlugin>());
    app.add_plugins(HexMinimapPlugin);
    app.update();
    assert_eq!(app.world().resource::<HexMinimapSettings>(), &mine);
}

/// The globe's minimap (`HexGlobeMinimapPlugin`): the image is the core's equirectangular
/// picture (every pixel its tile's terrain color, off the outline), the orbit camera's view is
/// outlined on the circle of its horizon around the spot under it, and a press on a pixel turns
/// the camera to look down on that pixel's tile, saying so with `GlobeMinimapNavigate`.
#[test]
fn the_globes_minimap_shows_the_globe_outlines_the_view_and_flies_the_camera() {
    use bevy_hex_terrain::hex_terrain::GlobeTile;
    use bevy_hex_terrain::hex_terrain::minimap::GlobeMinimap;
    use bevy_hex_terrain::{
        GlobeCamera, GlobeMinimapNavigate, GlobeMinimapPicture, HexGlobe, HexGlobeMinimap, HexGlobeMinimapPlugin,
        globe_horizon,
    };
    #[derive(Resource, Default)]
    struct Went(Vec<GlobeMinimapNavigate>);
    let config = MapConfig::from_ron("(seed: 3, size: Globe(frequency: 8), climate: (enabled: true))").unwrap();
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, AssetPlugin::default(), TransformPlugin, PickingPlugin, InteractionPlugin));
    app.init_asset::<Image>();
    app.add_plugins((HexGlobePlugin::from_config(config), HexGlobeMinimapPlugin));
    app.insert_resource(HexMinimapSettings { size: UVec2::new(200, 100), ..default() });
    app.init_resource::<OnMinimap>().init_resource::<Went>();
    app.add_systems(
        PreUpdate,
        (|on: Res<OnMinimap>, nodes: Query<Entity, With<HexGlobeMinimap>>, mut hits: MessageWriter<PointerHits>| {
            let (Some(at), Ok(node)) = (on.0, nodes.single()) else { return };
            let hit = HitData::new(node, 0.0, Some(at.extend(0.0)), None);
            hits.write(PointerHits::new(POINTER, vec![(node, hit)], 10.0));
        })
        .in_set(PickingSystems::Backend),
    );
    app.add_systems(Last, |mut read: MessageReader<GlobeMinimapNavigate>, mut all: ResMut<Went>| {
        all.0.extend(read.read().copied());
    });
    app.world_mut().spawn(POINTER);
    let camera = app.world_mut().spawn(GlobeCamera { altitude: 30.0, ..GlobeCamera::above(0.4, 0.3) }).id();
    run_until(&mut app, "the globe's minimap", |app| {
        let picture = app.world().resource::<GlobeMinimapPicture>();
        picture.minimap().is_some() && !picture.outline().is_empty()
    });
    let globe = app.world().resource::<HexGlobe>().globe().unwrap().clone();
    let picture = app.world().resource::<GlobeMinimapPicture>();
    let shown: GlobeMinimap = picture.minimap().unwrap().clone();
    let [w, h] = shown.size();
    assert_eq!([w, h], [200, 100]);
    let handle = picture.image().clone();
    let outline: Vec<u32> = picture.outline().to_vec();
    let data = app.world().resource::<Assets<Image>>().get(&handle).unwrap().data.clone().unwrap();
    assert_eq!(data.len(), (w * h * 4) as usize);
    // Pixels off the outline: the terrain color of the tile under the pixel's center.
    for i in (0..w * h).step_by(13).filter(|i| !outline.contains(i)) {
        let direction = shown.direction_at(f64::from(i % w) + 0.5, f64::from(i / w) + 0.5);
        let tile = globe.tile_at(direction).unwrap();
        let [r, g, b] = globe.ruleset().terrain(globe.tile_info(tile).unwrap().terrain.terrain).look.color;
        assert_eq!(&data[i as usize * 4..i as usize * 4 + 4], &[r, g, b, 255], "pixel {i}");
    }
    // The outline: white, on the circle of the camera's horizon around the direction it lies in.
    let place = app.world().get::<GlobalTransform>(camera).unwrap().translation();
    let angle = globe_horizon(globe.radius() as f32, globe.config().terrain.max_elevation, place.length());
    let d = place.normalize().as_dvec3();
    for &i in &outline {
        assert_eq!(&data[i as usize * 4..i as usize * 4 + 4], &[255, 255, 255, 255]);
        let p = shown.direction_at(f64::from(i % w) + 0.5, f64::from(i / w) + 0.5);
        let off = (p[0] * d.x + p[1] * d.y + p[2] * d.z).clamp(-1.0, 1.0).acos() - f64::from(angle);
        assert!(off.abs() <= 2.0 * std::f64::consts::PI / f64::from(w), "{off}");
    }
    // A press on a pixel: the camera turns over that pixel's tile.
    for (px, py) in [(20u32, 50u32), (150, 30), (100, 80)] {
        let at = Vec2::new((px as f32 + 0.5) / w as f32 - 0.5, (py as f32 + 0.5) / h as f32 - 0.5);
        app.world_mut().resource_mut::<OnMinimap>().0 = Some(at);
        app.world_mut().resource_mut::<Went>().0.clear();
        app.update();
        for action in [PointerAction::Press(PointerButton::Primary), PointerAction::Release(PointerButton::Primary)] {
            app.world_mut().write_message(PointerInput::new(POINTER, location(), action));
            app.update();
        }
        let went = app.world().resource::<Went>().0.clone();
        assert_eq!(went.len(), 1, "{went:?}");
        assert_eq!(Some(went[0].tile), shown.tile_at_pixel(px, py));
        let looks_along = app.world().get::<GlobeCamera>(camera).unwrap().orientation * Vec3::Z;
        let under = globe.tile_at(looks_along.as_dvec3().to_array()).unwrap();
        let near = under == went[0].tile || globe.grid().neighbors(went[0].tile).unwrap().as_slice().contains(&under);
        assert!(near, "the camera over {under:?}, the press on {:?}", went[0].tile);
    }
    // Tile states: an owner's tiles and the fog of war, painted as the states say once written.
    let grid = globe.grid();
    let home = grid.tile_at([0.0, 0.6, 0.8]).unwrap();
    let owned: Vec<GlobeTile> = grid.within(home, 2).into_iter().map(|(t, _)| t).collect();
    let seen: Vec<GlobeTile> = grid.within(home, 4).into_iter().map(|(t, _)| t).collect();
    app.insert_resource(HexTileStateStyle { fog_of_war: true, ..default() });
    {
        let mut states = app.world_mut().resource_mut::<GlobeTileStates>();
        for &t in &seen {
            states.set_visibility(t, FogState::Explored).unwrap();
        }
        for &t in &owned {
            states.set_owner(t, Some(1)).unwrap();
            states.set_visibility(t, FogState::Visible).unwrap();
        }
    }
    for _ in 0..3 {
        app.update();
    }
    let picture = app.world().resource::<GlobeMinimapPicture>();
    let outline: Vec<u32> = picture.outline().to_vec();
    let data = app.world().resource::<Assets<Image>>().get(picture.image()).unwrap().data.clone().unwrap();
    let style = app.world().resource::<HexMinimapSettings>().style();
    let mut counted = [0; 3];
    for i in (0..w * h).filter(|i| !outline.contains(i)) {
        let tile = shown.tile_at_pixel(i % w, i / w).unwrap();
        let pixel = &data[i as usize * 4..i as usize * 4 + 3];
        if !seen.contains(&tile) {
            assert_eq!(pixel, &style.unexplored[..3], "pixel {i} of unexplored tile {tile:?}");
            counted[0] += 1;
        } else if owned.contains(&tile) {
            // Visible and owned: its terrain's color tinted toward the owner's, or on its border.
            let [r, g, b] = globe.ruleset().terrain(globe.tile_info(tile).unwrap().terrain.terrain).look.color;
            assert_ne!(pixel, &[r, g, b], "pixel {i} of owned tile {tile:?} not tinted");
            counted[1] += 1;
        } else {
            // Explored: dimmer than its terrain's color.
            let [r, g, b] = globe.ruleset().terrain(globe.tile_info(tile).unwrap().terrain.terrain).look.color;
            let sum = |p: &[u8]| p.iter().map(|&c| u32::from(c)).sum::<u32>();
            assert!(
                sum(pixel) < sum(&[r, g, b]),
                "pixel {i} of explored tile {tile:?}: {pixel:?} against {:?}",
                [r, g, b]
            );
            counted[2] += 1;
        }
    }
    assert!(counted.iter().all(|&c| c > 10), "{counted:?}");
    // Later writes repaint only what they change: a highlight (the hovered tile) no pixel; an
    // owner lost on one tile its pixels and those beside them, and the picture is then what a
    // full paint of the states gives.
    let counts = |app: &App| {
        let p = app.world().resource::<GlobeMinimapPicture>();
        (p.repainted_pixels(), p.full_paints())
    };
    let (repainted, full) = counts(&app);
    app.world_mut().resource_mut::<GlobeTileStates>().set_highlight(home, Highlight::Hovered, true).unwrap();
    app.update();
    assert_eq!(counts(&app), (repainted, full), "a highlight repaints no pixel");
    let lost = owned[owned.len() - 1];
    app.world_mut().resource_mut::<GlobeTileStates>().set_owner(lost, None).unwrap();
    app.update();
    let (after, full_after) = counts(&app);
    assert_eq!(full_after, full, "one write is not a full paint");
    let near = shown.pixels_of(lost).len() as u64 * 5;
    assert!(after > repainted && after - repainted <= near, "{} pixels repainted for one tile", after - repainted);
    let picture = app.world().resource::<GlobeMinimapPicture>();
    let outline: Vec<u32> = picture.outline().to_vec();
    let data = app.world().resource::<Assets<Image>>().get(picture.image()).unwrap().data.clone().unwrap();
    let states = app.world().resource::<GlobeTileStates>();
    let whole = shown.paint(|t| TileLook { fog: states.visibility(t), owner: states.owner(t) });
    for i in (0..(w * h) as usize).filter(|&i| !outline.contains(&(i as u32))) {
        assert_eq!(&data[i * 4..i * 4 + 4], &whole[i * 4..i * 4 + 4], "pixel {i}");
    }
    // An edited globe of the same size (mountains round the home tile): recolored in place, no
    // picture built, and the picture is then a fresh picture of the edited globe, painted.
    let edits: Vec<hex_terrain::TileEdit> = seen
        .iter()
        .take(7)
        .map(|t| hex_terrain::TileEdit { kind: Some(TileKind::Mountain), ..hex_terrain::TileEdit::at((t.0 as i32, 0)) })
        .collect();
    let edited = hex_terrain::MapConfig { edits, ..globe.config().clone() };
    app.world_mut().resource_mut::<HexGlobe>().apply(edited.clone()).unwrap();
    app.update();
    app.update();
    let picture = app.world().resource::<GlobeMinimapPicture>();
    assert_eq!((picture.recolors(), picture.full_paints()), (1, full), "an edit is recolored, not built again");
    let outline: Vec<u32> = picture.outline().to_vec();
    let data = app.world().resource::<Assets<Image>>().get(picture.image()).unwrap().data.clone().unwrap();
    let states = app.world().resource::<GlobeTileStates>();
    let looks = |t: GlobeTile| TileLook { fog: states.visibility(t), owner: states.owner(t) };
    let fresh = GlobeMinimap::new(&hex_terrain::GlobeTerrain::new(edited).unwrap(), w, shown.style().clone()).unwrap();
    let whole = fresh.paint(looks);
    let before = shown.paint(looks);
    let mut differ = 0;
    for i in (0..(w * h) as usize).filter(|&i| !outline.contains(&(i as u32))) {
        assert_eq!(&data[i * 4..i * 4 + 4], &whole[i * 4..i * 4 + 4], "pixel {i} after the edit");
        differ += usize::from(whole[i * 4..i * 4 + 4] != before[i * 4..i * 4 + 4]);
    }
    assert!(differ > 0, "the edit changed no pixel");
}
