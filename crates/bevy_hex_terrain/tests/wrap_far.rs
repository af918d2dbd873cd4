//! Headless `App` tests of wrapping maps and of agents far from the origin.

use std::collections::{HashMap, HashSet};

use bevy::math::DVec3;
use bevy::prelude::*;
use bevy_hex_terrain::hex_terrain::Terrain;
use bevy_hex_terrain::prelude::*;
use bevy_hex_terrain::{ChunkTask, HexWorldPosition};

mod common;

use common::*;

fn wrapping(x: u32, z: u32, chunk: (u32, u32)) -> MapConfig {
    MapConfig { size: MapSize::Bounded { x, z }, wrap: true, chunk_size: chunk, ..MapConfig::default() }
}

/// The chunks of the map being built, by the chunk of the map they stand for.
fn building(app: &mut App, terrain: &Terrain) -> Vec<ChunkCoord> {
    let mut q = app.world_mut().query::<(&HexChunk, &ChunkTask)>();
    q.iter(app.world()).map(|(c, _)| terrain.wrap_chunk(c.coord).0).collect()
}

/// An agent walks east across the seam three times: chunks appear at wrapped positions (the
/// map's chunk meshes placed again, one map width on), every chunk of the map is generated at
/// most once at a time, copies share the mesh of the chunk they stand for, and around the agent
/// every chunk is there: it never sees an edge.
#[test]
fn chunks_appear_at_wrapped_positions_as_an_agent_walks_east() {
    // 20 columns in chunks of 6: three chunks and a narrower fourth a period.
    let config = wrapping(20, 12, (6, 6));
    let terrain = Terrain::new(config.clone()).unwrap();
    let wrap = *terrain.wrap().unwrap();
    let mut app = app(config, 1);
    let agent = spawn_agent(&mut app, Vec3::new(0.0, 5.0, 8.0));
    let mut max_x = i32::MIN;
    for step in 0..160 {
        let x = step as f32 * wrap.width as f32 * 3.0 / 160.0;
        app.world_mut().entity_mut(agent).get_mut::<Transform>().unwrap().translation.x = x;
        run_until(&mut app, "the chunks around the agent", |app| {
            let live = building(app, &terrain);
            let distinct: HashSet<_> = live.iter().collect();
            assert_eq!(distinct.len(), live.len(), "a chunk of the map built twice at once: {live:?}");
            let here = terrain.chunk_of(terrain.unwrapped_tile_at(f64::from(x), 8.0).unwrap()).unwrap();
            let meshed = meshed_chunks(app);
            window(here, 1).iter().filter(|c| terrain.chunk_rect(**c).is_some()).all(|c| meshed.contains_key(c))
        });
        let meshed = meshed_chunks(&mut app);
        max_x = max_x.max(meshed.keys().map(|c| c.x).max().unwrap());
        // Copies show the mesh of the chunk they stand for, where that chunk would be one or more
        // map widths on.
        let mut by_map_chunk: HashMap<ChunkCoord, Handle<Mesh>> = HashMap::new();
        let mut q = app.world_mut().query::<(&HexChunk, &Mesh3d, &Transform)>();
        for (chunk, mesh, transform) in q.iter(app.world()) {
            let (canonical, k) = terrain.wrap_chunk(chunk.coord);
            let origin = terrain.chunk_origin(canonical).unwrap();
            let expected = origin[0] + f64::from(k) * wrap.width;
            assert!((chunk.origin.x - expected).abs() < 1e-6, "{:?} at {}", chunk.coord, chunk.origin.x);
            assert!((f64::from(transform.translation.x) - expected).abs() < 1e-2);
            if let Some(other) = by_map_chunk.insert(canonical, mesh.0.clone()) {
                assert_eq!(other, mesh.0, "two copies of {canonical:?} with different meshes");
            }
        }
    }
    assert!(max_x >= 3 * wrap.chunk_columns(), "the walk went three periods east (chunk {max_x})");
    // Each chunk of the map was generated about once however many times it was placed again.
    let stats = app.world().resource::<HexStreamingStats>();
    let map_chunks = terrain.chunks().len() as u64;
    assert!(stats.tasks_started() <= 3 * map_chunks, "{} tasks for {map_chunks} chunks", stats.tasks_started());
}

/// Map queries wrap, and neighbors and distances cross the seam.
#[test]
fn map_queries_wrap() {
    let config = wrapping(44, 26, (16, 16));
    let mut app = app(config, 1);
    app.update();
    let map = app.world().resource::<HexMap>();
    let width = map.terrain().wrap().unwrap().width as f32;
    let west = map.terrain().tile_from_offset([0, 5]);
    let east = map.terrain().tile_from_offset([43, 5]);
    let center = map.tile_center(west).unwrap();
    assert_eq!(map.tile_at(center + Vec3::X * width).unwrap(), west);
    assert_eq!(map.tile_at(center - Vec3::X * 2.0 * width).unwrap(), west);
    assert!(map.neighbors(east).unwrap().contains(&Some(west)));
    assert_eq!(map.distance(east, west), Some(1));
    let ray = Ray3d::new(center + Vec3::new(width, 30.0, 0.0), Dir3::NEG_Y);
    assert_eq!(map.raycast(ray, 100.0).unwrap().tile, west, "a ray east of the seam hits the west side's tile");
    let near = map.wrap_near(center, center + Vec3::X * (width * 2.0 + 3.0));
    assert!((near.x - (center.x + 2.0 * width)).abs() < 1e-3);
}

/// An agent a million units out (its f64 position in `HexWorldPosition`): the chunks around it
/// load, with their origins out there and their mesh positions small.
#[test]
fn an_agent_a_million_units_out_streams_exact_chunks() {
    let mut app = app(MapConfig { size: MapSize::Unbounded, ..MapConfig::default() }, 1);
    let at = DVec3::new(1.0e6 + 0.3, 5.0, -1.0e6 - 0.7);
    app.world_mut().spawn((HexTerrainAgent::default(), Transform::default(), HexWorldPosition(at)));
    let terrain = app.world().resource::<HexMap>().terrain().clone();
    let here = terrain.chunk_of(terrain.tile_at(at.x, at.z).unwrap()).unwrap();
    run_until(&mut app, "the far chunks", |app| {
        let meshed = meshed_chunks(app);
        window(here, 1).iter().all(|c| meshed.contains_key(c))
    });
    assert!(chunk_coords(&mut app).iter().all(|c| c.distance(here) <= 3), "nothing streams around the origin");
    let mut q = app.world_mut().query::<(&HexChunk, &Mesh3d)>();
    let meshes = app.world().resource::<Assets<Mesh>>();
    for (chunk, mesh) in q.iter(app.world()) {
        assert!((chunk.origin.x - at.x).abs() < 200.0 && (chunk.origin.z - at.z).abs() < 200.0);
        let positions = meshes.get(&mesh.0).unwrap().attribute(Mesh::ATTRIBUTE_POSITION).unwrap().as_float3().unwrap();
        assert!(positions.iter().all(|p| p[0].abs() < 100.0 && p[2].abs() < 100.0), "positions relative to the chunk");
        // The core's mesh at the level the chunk is drawn at.
        let expected = terrain.generate_chunk_detail(chunk.coord, chunk.detail).unwrap();
        assert_eq!(positions, expected.buffers.positions.as_slice());
    }
    let tile = app.world().resource::<HexMap>().tile_at_f64(at).unwrap();
    let center = app.world().resource::<HexMap>().tile_center_f64(tile).unwrap();
    assert!((center.x - at.x).abs() < 1.0 && (center.z - at.z).abs() < 1.0, "{center} vs {at}");
}

/// With `big_space`, the queries take positions as a cell and an offset, a million units out.
#[cfg(feature = "big_space")]
#[test]
fn queries_in_grid_cells_are_exact_far_out() {
    use big_space::prelude::Grid;
    let map = HexMap::new(MapConfig { size: MapSize::Unbounded, ..MapConfig::default() }).unwrap();
    let grid = Grid::default();
    let at = DVec3::new(1.0e6 + 0.3, 2.0, -1.0e6 - 0.7);
    let tile = map.tile_at_f64(at).unwrap();
    let (cell, offset) = grid.translation_to_grid(at);
    assert_eq!(map.tile_at_cell(&grid, &cell, offset).unwrap(), tile);
    assert!(
        (map.surface_height_at_cell(&grid, &cell, offset).unwrap() - map.surface_height_f64(at).unwrap()).abs() < 1e-5
    );
    let hit = map.raycast_from_cell(&grid, &cell, offset + Vec3::Y * 30.0, Dir3::NEG_Y, 100.0).unwrap();
    assert_eq!(hit.tile, tile);
    let (center_cell, center_offset) = map.tile_center_in_grid(&grid, tile).unwrap();
    assert_eq!(map.tile_at_cell(&grid, &center_cell, center_offset).unwrap(), tile);
    assert!(center_offset.length() < grid.cell_edge_length());
}
