//! Headless `App` tests of entities on tiles: an [`OnTile`] entity stands on what its chunk's
//! mesh draws at its tile's center, through an edit under it and a level-of-detail change; it is
//! drawn at the copy of its tile nearest the agent on a wrapping map; it hides under the fog the
//! tile states show; a [`TileWalk`] walks it along a path and ends with [`WalkEnded`].

use bevy::prelude::*;
use bevy_hex_terrain::hex_terrain::Detail;
use bevy_hex_terrain::prelude::*;

mod common;

use common::*;

/// The height of the chunk mesh vertex nearest a world position (`x`, `z`), in the world, and
/// the chunk's level: what is drawn there.
fn drawn_height(app: &mut App, at: Vec3) -> Option<(f32, Detail)> {
    let chunks: Vec<(Detail, Vec3, Handle<Mesh>)> = app
        .world_mut()
        .query::<(&HexChunk, &Transform, &Mesh3d)>()
        .iter(app.world())
        .map(|(c, t, m)| (c.detail, t.translation, m.0.clone()))
        .collect();
    let meshes = app.world().resource::<Assets<Mesh>>();
    let mut best: Option<(f32, f32, Detail)> = None;
    for (detail, origin, handle) in chunks {
        let mesh = meshes.get(&handle)?;
        for p in mesh.attribute(Mesh::ATTRIBUTE_POSITION)?.as_float3()? {
            let world = origin + Vec3::from_array(*p);
            let d = (world.xz() - at.xz()).length();
            if best.is_none_or(|(b, ..)| d < b) {
                best = Some((d, world.y, detail));
            }
        }
    }
    best.filter(|(d, ..)| *d < 1e-3).map(|(_, y, detail)| (y, detail))
}

fn bounded(x: u32, z: u32) -> MapConfig {
    MapConfig { seed: 11, size: MapSize::Bounded { x, z }, chunk_size: (8, 8), ..default() }
}

fn translation(app: &App, e: Entity) -> Vec3 {
    app.world().get::<Transform>(e).unwrap().translation
}

#[test]
fn a_unit_stands_on_its_tile_through_an_edit_and_a_level_change() {
    let settings = HexStreamingSettings { coarse_distance: Some(12.0), ..settings(3) };
    let mut app = app_with(bounded(40, 24).into(), settings, None);
    keep::<HexMapEdited>(&mut app);
    let agent = spawn_agent(&mut app, Vec3::new(6.0, 0.0, 6.0));
    run_until(&mut app, "the terrain", ready);
    let tile = app.world().resource::<HexMap>().tile_from_offset([4, 4]);
    let lift = 0.5;
    let unit = app.world_mut().spawn(OnTile { lift, ..OnTile::new(tile) }).id();
    app.update();
    let at = translation(&app, unit);
    let (y, detail) = drawn_height(&mut app, at).expect("a vertex under the unit");
    assert_eq!(detail, Detail::Full);
    assert!((at.y - lift - y).abs() < 1e-4, "unit at {} over a surface at {y}", at.y);

    // Raise the ground under it: it stands on the new surface.
    app.world_mut().write_message(HexMapEdit::Stroke(Stroke { tool: Tool::Raise(0.3), brush: Brush::Range(1), tile }));
    run_until(&mut app, "the edit", |app| seen::<HexMapEdited>(app).len() == 1 && ready(app));
    app.update();
    let raised = translation(&app, unit);
    let (y, _) = drawn_height(&mut app, raised).unwrap();
    assert!(raised.y > at.y + 0.1, "the unit stayed at {} after a raise from {}", raised.y, at.y);
    assert!((raised.y - lift - y).abs() < 1e-4, "unit at {} over a surface at {y}", raised.y);

    // The agent goes far east: the unit's chunk is drawn coarse, and the unit stands on it.
    app.world_mut().entity_mut(agent).insert(Transform::from_translation(Vec3::new(6.0 + 36.0, 0.0, 6.0)));
    run_until(&mut app, "the unit's chunk coarse", |app| {
        ready(app) && drawn_height(app, raised).is_some_and(|(_, d)| d == Detail::Coarse)
    });
    let far = translation(&app, unit);
    let (y, _) = drawn_height(&mut app, far).unwrap();
    assert_eq!(far, raised, "a level change does not move the unit");
    assert!((far.y - lift - y).abs() < 1e-4, "unit at {} over a coarse surface at {y}", far.y);
}

#[test]
fn on_a_wrapping_map_a_unit_is_drawn_at_the_copy_nearest_the_agent() {
    let mut config = bounded(24, 12);
    config.wrap = true;
    let mut app = app(config, 2);
    let map_width = {
        let map = app.world().resource::<HexMap>();
        map.terrain().wrap().map(|w| w.width as f32)
    };
    let agent = spawn_agent(&mut app, Vec3::new(2.0, 0.0, 6.0));
    run_until(&mut app, "the terrain", ready);
    let width = map_width.or_else(|| app.world().resource::<HexMap>().terrain().wrap().map(|w| w.width as f32));
    let width = width.expect("a wrapping map");
    // A tile near the east edge, the agent near the west one: the copy west of the map shows.
    let tile = app.world().resource::<HexMap>().tile_from_offset([22, 5]);
    let center = app.world().resource::<HexMap>().tile_center(tile).unwrap();
    let unit = app.world_mut().spawn(OnTile::new(tile)).id();
    app.update();
    let at = translation(&app, unit);
    assert!((at.x - (center.x - width)).abs() < 1e-3, "drawn at {at}, the tile's center is {center}");
    // The agent goes east past the seam: the unit follows to its copy there (the frame after:
    // the agent's global transform moves at the end of its frame).
    app.world_mut().entity_mut(agent).insert(Transform::from_translation(Vec3::new(width - 2.0, 0.0, 6.0)));
    app.update();
    app.update();
    let at = translation(&app, unit);
    assert!((at.x - center.x).abs() < 1e-3, "drawn at {at}, the tile's center is {center}");
}

/// The fog hides entities where something is drawn (the `render` feature).
#[cfg(feature = "render")]
#[test]
fn a_unit_hides_under_the_fog_and_a_city_shows_once_explored() {
    let mut app = app(bounded(16, 12), 2);
    spawn_agent(&mut app, Vec3::new(6.0, 0.0, 6.0));
    run_until(&mut app, "the terrain", ready);
    let tile = app.world().resource::<HexMap>().tile_from_offset([3, 3]);
    let unit = app.world_mut().spawn(OnTile::new(tile)).id();
    let city = app.world_mut().spawn(OnTile { shown_from: FogState::Explored, ..OnTile::new(tile) }).id();
    let marker = app.world_mut().spawn(OnTile { shown_from: FogState::Unexplored, ..OnTile::new(tile) }).id();
    let visibility = |app: &App, e: Entity| *app.world().get::<Visibility>(e).unwrap();
    for (fog, shown) in [
        (FogState::Unexplored, [false, false, true]),
        (FogState::Visible, [true, true, true]),
        (FogState::Explored, [false, true, true]),
    ] {
        app.world_mut().resource_mut::<TileStates>().set_visibility(tile, fog).unwrap();
        app.update();
        for (e, shown) in [unit, city, marker].into_iter().zip(shown) {
            let expected = if shown { Visibility::Inherited } else { Visibility::Hidden };
            assert_eq!(visibility(&app, e), expected, "{fog:?}");
        }
    }
}

/// The `WalkEnded`s observed.
#[derive(Resource, Default)]
struct Ended(Vec<WalkEnded>);

#[test]
fn a_walk_follows_its_path_on_the_surface_and_ends_on_the_last_tile() {
    let mut app = app(bounded(16, 12), 2);
    spawn_agent(&mut app, Vec3::new(6.0, 0.0, 6.0));
    run_until(&mut app, "the terrain", ready);
    app.init_resource::<Ended>();
    app.add_observer(|ended: On<WalkEnded>, mut seen: ResMut<Ended>| seen.0.push(*ended));
    let map = app.world().resource::<HexMap>();
    let start = map.tile_from_offset([2, 2]);
    let path: Vec<Hex> = (2..7).map(|col| map.tile_from_offset([col, 2])).collect();
    let goal = *path.last().unwrap();
    let goal_center = map.tile_center(goal).unwrap();
    let unit = app.world_mut().spawn((OnTile::new(start), TileWalk::new(path.clone(), 4.0))).id();
    let mut tiles = vec![start];
    run_until(&mut app, "the walk's end", |app| {
        let on = app.world().get::<OnTile>(unit).unwrap().tile;
        if tiles.last() != Some(&on) {
            tiles.push(on);
        }
        // Between tiles the unit stands on the surface.
        let at = app.world().get::<Transform>(unit).unwrap().translation;
        let ground = app.world().resource::<HexMap>().surface_height(at).unwrap();
        assert!((at.y - ground).abs() < 1e-3, "at {at}, the ground at {ground}");
        !app.world().resource::<Ended>().0.is_empty()
    });
    assert_eq!(tiles, path, "the unit reached each tile of its path in turn");
    assert_eq!(app.world().resource::<Ended>().0, vec![WalkEnded { entity: unit, tile: goal }]);
    assert!(app.world().get::<TileWalk>(unit).is_none(), "the walk is removed");
    app.update();
    assert!((translation(&app, unit) - goal_center).length() < 1e-4);
}

/// With `big_space`, an entity in the terrain's grid stands in the cell of its tile's exact
/// position, a million units out.
#[cfg(feature = "big_space")]
#[test]
fn in_a_big_space_grid_a_unit_stands_in_its_tiles_cell_far_out() {
    use bevy::math::DVec3;
    use big_space::prelude::{CellCoord, Grid};
    let mut app = app(MapConfig { size: MapSize::Unbounded, ..MapConfig::default() }, 1);
    let at = DVec3::new(1.0e6 + 0.3, 0.0, -1.0e6 - 0.7);
    app.world_mut().spawn((HexTerrainAgent::default(), Transform::default(), bevy_hex_terrain::HexWorldPosition(at)));
    let grid = app.world_mut().spawn((Grid::default(), bevy_hex_terrain::HexTerrainGrid)).id();
    let tile = app.world().resource::<HexMap>().tile_at_f64(at).unwrap();
    let unit = app.world_mut().spawn((OnTile::new(tile), CellCoord::default(), ChildOf(grid))).id();
    app.update();
    let center = app.world().resource::<HexMap>().tile_center_f64(tile).unwrap();
    let grid = app.world().get::<Grid>(grid).unwrap();
    let cell = app.world().get::<CellCoord>(unit).unwrap();
    let transform = app.world().get::<Transform>(unit).unwrap();
    assert_ne!(*cell, CellCoord::default());
    let stands = grid.grid_position_double(cell, transform);
    assert!((stands - center).length() < 1e-3, "stands at {stands}, the tile's center is {center}");
    assert!(transform.translation.length() < grid.cell_edge_length());
}
