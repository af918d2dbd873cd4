//! The promises at the edges, property-based over random valid configs: a wrapped chunk's
//! origin, rays at the top of the relief, the f32 bound on positions for any chunk size and
//! ring count, queries past the world's edge, and wrapping maps far east and west.

use hex_terrain::config::MAX_WORLD_TILE;
use hex_terrain::hexx::Hex;
use hex_terrain::{
    Brush, ChunkCoord, EditError, Editor, GenerateOptions, MapConfig, MapSize, NoiseConfig, Orientation, SetupConfig,
    Shape, Stroke, Terrain, Tool,
};
use proptest::prelude::*;
#[path = "common/biome.rs"]
mod biome;

prop_compose! {
    /// Any layout: 1-16 inner rings, chunks up to 128x8 (or 8x128), bounded or not, wrapping
    /// or not, both orientations.
    fn config()(
        seed in any::<u32>(),
        inner_rings in 1u32..=16,
        pointy in any::<bool>(),
        hex_size in 0.25f32..4.0,
        chunk in prop_oneof![(1u32..=128, 1u32..=8), (1u32..=8, 1u32..=128), (1u32..=24, 1u32..=24)],
        size in 0usize..3,
        columns in 2u32..12,
        rows in 1u32..6,
        offset in (-1000i32..1000, -1000i32..1000),
        max_elevation in 0.5f32..100.0,
    ) -> MapConfig {
        let mut c = MapConfig {
            seed,
            offset,
            noise: NoiseConfig { octaves: 3, ..NoiseConfig::default() },
            chunk_size: chunk,
            ..MapConfig::default()
        };
        c.terrain.inner_rings = inner_rings;
        c.terrain.max_elevation = max_elevation;
        c.layout.orientation = if pointy { Orientation::Pointy } else { Orientation::Flat };
        c.layout.hex_size = hex_size;
        match size {
            0 => c.size = MapSize::Unbounded,
            1 => c.size = MapSize::Bounded { x: 2 * columns, z: rows },
            _ => {
                c.size = MapSize::Bounded { x: 2 * columns.max(2), z: rows };
                c.wrap = true;
            }
        }
        c
    }
}

/// Tiles that are not in any world: near `i32`'s ends, and just past `MAX_WORLD_TILE`.
fn hostile_tiles(t: &Terrain) -> Vec<Hex> {
    let m = MAX_WORLD_TILE;
    let mut tiles = vec![
        Hex::new(1 << 30, -(1 << 30)),
        Hex::new(i32::MAX, 0),
        Hex::new(i32::MIN, i32::MAX),
        Hex::new(i32::MAX, i32::MAX),
        Hex::new(i32::MIN, i32::MIN),
        Hex::new(0, i32::MIN),
    ];
    tiles.extend([[m, 0], [-m - 1, 0], [0, m], [0, -m - 1], [m, m]].map(|oc| t.tile_from_offset(oc)));
    tiles
}

/// Positions past every world (and not finite).
const HOSTILE: [f64; 8] = [1e9, -1e9, 1e10, 1e15, -1e300, f64::MAX, f64::INFINITY, f64::NAN];

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// Every vertex of a chunk, brought into the world frame in f64, lies within the stated
    /// bound of its exact position, and the vertices two neighboring chunks share within the
    /// sum of their bounds: for any ring count and chunk size, next to the origin and at the
    /// last chunk of the world.
    #[test]
    fn positions_keep_the_stated_bound(config in config()) {
        let t = Terrain::new(config).unwrap();
        let g = t.geometry();
        let (w, h) = t.chunk_size();
        let last = ChunkCoord::new(MAX_WORLD_TILE / w as i32 - 1, -(MAX_WORLD_TILE / h as i32));
        let chunks: Vec<ChunkCoord> = if t.bounds().is_some() {
            t.chunks().into_iter().take(2).collect()
        } else {
            vec![ChunkCoord::new(0, 0), ChunkCoord::new(1, 0), last]
        };
        let bound = g.chunk_position_error();
        let mut seen = std::collections::HashMap::new();
        for chunk in chunks {
            let Some(rect) = t.chunk_rect(chunk) else { continue };
            let m = t.generate(rect, GenerateOptions::DIAGNOSTICS);
            let error = g.position_error(rect);
            prop_assert!(error <= bound);
            let lattice = &m.diagnostics.as_ref().unwrap().lattice;
            for (pos, &p) in m.buffers.positions.iter().zip(lattice) {
                let (x, z) = (m.origin[0] + f64::from(pos[0]), m.origin[2] + f64::from(pos[2]));
                let [ex, ez] = t.lattice().world(p);
                prop_assert!((x - ex).hypot(z - ez) <= error, "vertex {:?} of {:?}: {} off, bound {}", p, chunk, (x - ex).hypot(z - ez), error);
                if let Some((sx, sz, serror)) = seen.insert(p, (x, z, error)) {
                    let gap: f64 = (x - sx).hypot(z - sz);
                    prop_assert!(gap <= error + serror, "shared vertex {:?}: {} apart", p, gap);
                }
            }
        }
    }

    /// A wrapped copy of a chunk is the map's chunk's mesh with its origin where the copy
    /// goes: `generate_chunk(..).origin` is `chunk_origin`, a whole number of map widths east.
    #[test]
    fn wrapped_chunks_report_their_own_origin(config in config(), k in -1000i32..1000) {
        let mut config = config;
        if !config.wrap {
            config.size = MapSize::Bounded { x: 8, z: 3 };
            config.wrap = true;
        }
        let t = Terrain::new(config).unwrap();
        let wrap = *t.wrap().unwrap();
        for chunk in t.chunks() {
            let copy = ChunkCoord::new(chunk.x + k * wrap.chunk_columns(), chunk.z);
            let (a, b) = (t.generate_chunk(chunk).unwrap(), t.generate_chunk(copy).unwrap());
            prop_assert_eq!(&a.buffers, &b.buffers);
            prop_assert_eq!(Some(b.origin), t.chunk_origin(copy));
            prop_assert_eq!(b.origin[0], a.origin[0] + wrap.width * f64::from(k));
            prop_assert_eq!(Some(a.origin), t.chunk_origin(chunk));
        }
    }

    /// Every tile query about a tile past the world answers `None` (or "nothing there"), and
    /// every position query past it too: no panic (the tests run with overflow checks), no
    /// made-up tile.
    #[test]
    fn nothing_past_the_world(config in config()) {
        let t = Terrain::new(config).unwrap();
        for tile in hostile_tiles(&t) {
            prop_assert!(!t.in_world(tile), "{:?}", tile);
            prop_assert_eq!(t.tile_info(tile), None);
            prop_assert_eq!(t.tile_center(tile), None);
            prop_assert_eq!(t.tile_kind(tile), None);
            prop_assert_eq!(t.map_tile_kind(tile), None);
            prop_assert_eq!(biome::at(&t, tile), None);
            prop_assert_eq!(t.tile_climate(tile), None);
            prop_assert_eq!(t.neighbors(tile), None);
            prop_assert_eq!(t.distance(tile, Hex::ZERO), None);
            prop_assert_eq!(t.river(tile), None);
            prop_assert_eq!(t.lake(tile), None);
            prop_assert_eq!(t.water_level(tile), None);
            prop_assert_eq!(t.river_flow(tile), None);
            prop_assert!(!t.tile_is_wet(tile));
            prop_assert!(!t.contains(tile));
            prop_assert_eq!(t.wrap_tile(tile), None);
            prop_assert_eq!(t.chunk_of(tile), None);
            prop_assert_eq!(t.tile_near(tile, Hex::ZERO), tile);
        }
        // Lattice points past the world (2^30 steps are more than 2^24 tiles of 17 steps).
        for p in [Hex::new(i32::MAX, 0), Hex::new(i32::MIN, i32::MAX), Hex::new(1 << 30, -(1 << 30)), Hex::new(0, 1 << 30)] {
            prop_assert!(!t.geometry().point_in_world(p));
            prop_assert!(t.vertex(p).is_none() && t.vertex_elevation(p).is_none() && t.point_color(p).is_none());
            prop_assert_eq!(t.water_cover(Hex::ZERO, p), None);
            prop_assert_eq!(t.raw_height(p), None);
            prop_assert_eq!(t.source_height(p), None);
            prop_assert_eq!(t.noise_position(p), None);
        }
        let z_in_map = if t.bounds().is_some() { 0.5 } else { 1e9 };
        for x in HOSTILE {
            for (x, z) in [(x, z_in_map), (0.0, x), (x, x)] {
                let wraps = t.wrap().is_some() && x.is_finite() && z == z_in_map;
                prop_assert_eq!(t.tile_at(x, z).is_some(), wraps, "tile_at({}, {})", x, z);
                prop_assert_eq!(t.unwrapped_tile_at(x, z), None, "unwrapped_tile_at({}, {})", x, z);
                prop_assert_eq!(t.surface_height(x, z).is_some(), wraps);
                prop_assert_eq!(t.raycast([x, 200.0, z], [0.0, -1.0, 0.0], f64::MAX).is_some(), wraps);
                // Aimed far out from inside: a hit, if any, is on a tile of the world.
                let hit = t.raycast([0.0, 200.0, 0.0], [x, -1.0, z], f64::MAX);
                prop_assert!(hit.is_none_or(|h| t.in_world(h.tile) && h.point.iter().all(|v| v.is_finite())));
            }
        }
    }

    /// A ray straight down from above hits the surface everywhere, also where the surface is at
    /// the maximum elevation (a gradient map's top row), at the height the surface query gives.
    #[test]
    fn rays_from_above_hit_the_top_of_the_relief(config in config(), pointy in any::<bool>(), max_elevation in 0.5f32..100.0) {
        let mut config = config;
        config.size = MapSize::Bounded { x: 1 + config.chunk_size.0 % 6, z: 3 + config.chunk_size.1 % 4 };
        config.wrap = false;
        config.shape = Shape::Gradient;
        config.terrain.max_elevation = max_elevation;
        config.layout.orientation = if pointy { Orientation::Pointy } else { Orientation::Flat };
        let t = Terrain::new(config).unwrap();
        let tiles: Vec<Hex> = t.tiles().collect();
        for tile in tiles {
            let center = t.tile_center(tile).unwrap();
            for (dx, dz) in [(0.0, 0.0), (0.21, 0.13), (-0.3, 0.05), (0.05, -0.33)] {
                let s = f64::from(t.config().layout.hex_size);
                let (x, z) = (center[0] + dx * s, center[2] + dz * s);
                let y = t.surface_height(x, z).unwrap();
                let hit = t.raycast([x, f64::from(max_elevation) * 3.0 + 1.0, z], [0.0, -1.0, 0.0], f64::MAX);
                let hit = hit.ok_or_else(|| TestCaseError::fail(format!("ray down at ({x}, {z}) missed the surface at {y}")))?;
                prop_assert!((hit.point[1] - y).abs() <= 1e-6 * f64::from(max_elevation).max(1.0), "{:?} vs {}", hit, y);
            }
        }
    }

    /// A ray's hit is the first point of the ray on the surface: on it, and no point of the ray
    /// before it is under the surface, even for shallow rays grazing peaks and ridges (the march
    /// once stepped over tips thinner than its sample spacing). Checked against a dense sampling
    /// of the ray, on mountainous maps, at strategy-camera and shallower angles.
    #[test]
    fn rays_hit_the_first_surface_point(config in config(), mountains in any::<bool>(), rays in prop::collection::vec((0.0f64..1.0, 0.0f64..1.0, 0.05f64..1.2, 0.0f64..std::f64::consts::TAU), 8)) {
        let mut config = config;
        config.size = MapSize::Bounded { x: 12, z: 10 };
        config.wrap = false;
        config.terrain.max_elevation = config.terrain.max_elevation.min(8.0 * config.layout.hex_size);
        if mountains {
            config.relief = hex_terrain::ReliefConfig::MOUNTAINS;
        }
        let t = Terrain::new(config).unwrap();
        let far = t.tile_center(t.tile_from_offset([11, 9])).unwrap();
        let top = f64::from(t.config().terrain.max_elevation);
        for (fx, fz, pitch, yaw) in rays {
            // Aimed at a point of the map from above the relief, `pitch` radians down.
            let target = [far[0] * fx, 0.0, far[2] * fz];
            let d = [pitch.cos() * yaw.cos(), -pitch.sin(), pitch.cos() * yaw.sin()];
            let back = (top + 1.0) / pitch.sin();
            let o = [target[0] - d[0] * back, top + 1.0, target[2] - d[2] * back];
            let Some(hit) = t.raycast(o, d, f64::MAX) else { continue };
            let y = t.surface_height(hit.point[0], hit.point[2]).unwrap();
            prop_assert!((hit.point[1] - y).abs() <= 1e-6 * top.max(1.0), "{hit:?} is not on the surface at {y}");
            let samples = 4000;
            for k in 0..samples {
                let s = hit.distance * f64::from(k) / f64::from(samples);
                let p = [o[0] + d[0] * s, o[1] + d[1] * s, o[2] + d[2] * s];
                if let Some(h) = t.surface_height(p[0], p[2]) {
                    prop_assert!(p[1] >= h - 1e-6 * top.max(1.0), "the ray is under the surface at {s} ({} < {h}), before its hit at {}", p[1], hit.distance);
                }
            }
        }
    }

    /// On a wrapping map every finite position answers with the map's own tile, however far
    /// east or west: the tile, the surface height and a ray down equal those one period's worth
    /// of positions away, next to the map.
    #[test]
    fn wrapping_maps_wrap_at_any_distance(config in config(), east in prop_oneof![Just(1e10), Just(-1e10), Just(3.7e15), Just(-1e300), Just(f64::MAX), 1e6f64..1e12], zf in 0.0f64..1.0) {
        let mut config = config;
        if !config.wrap {
            config.size = MapSize::Bounded { x: 4, z: 1 };
            config.wrap = true;
        }
        let t = Terrain::new(config).unwrap();
        let width = t.wrap().unwrap().width;
        let rows = t.bounds().unwrap().max[1];
        // A z inside the map's rows.
        let bottom = t.tile_center(t.tile_from_offset([1, rows - 1])).unwrap()[2];
        let z = zf * bottom;
        let near = east % width;
        let tile = t.tile_at(east, z).ok_or_else(|| TestCaseError::fail(format!("no tile at {east}")))?;
        prop_assert!(t.contains(tile) && t.bounds().unwrap().contains(t.offset_of(tile)), "{:?} is not a tile of the map", tile);
        prop_assert_eq!(Some(tile), t.tile_at(near, z));
        prop_assert_eq!(t.surface_height(east, z), t.surface_height(near, z));
        let top = f64::from(t.config().terrain.max_elevation) + 5.0;
        let (far_hit, near_hit) = (
            t.raycast([east, top, z], [0.0, -1.0, 0.0], f64::MAX).unwrap(),
            t.raycast([near, top, z], [0.0, -1.0, 0.0], f64::MAX).unwrap(),
        );
        prop_assert_eq!(far_hit.tile, near_hit.tile);
        prop_assert_eq!(far_hit.point[1], near_hit.point[1]);
        prop_assert_eq!(far_hit.point[0], near_hit.point[0] + (east - near));
    }
}

/// The cases the issue reported, by name: a one-column gradient map whose top surface rounds
/// above the maximum elevation, and a wrapping map asked ten billion units east.
#[test]
fn the_reported_cases_hold() {
    let mut c = MapConfig { size: MapSize::Bounded { x: 1, z: 3 }, shape: Shape::Gradient, ..MapConfig::default() };
    c.layout.orientation = Orientation::Pointy;
    let t = Terrain::new(c).unwrap();
    for tile in t.tiles().collect::<Vec<_>>() {
        let [x, _, z] = t.tile_center(tile).unwrap();
        assert!(t.raycast([x, 50.0, z], [0.0, -1.0, 0.0], f64::MAX).is_some(), "{tile:?}");
    }
    let t =
        Terrain::new(MapConfig { size: MapSize::Bounded { x: 4, z: 1 }, wrap: true, ..MapConfig::default() }).unwrap();
    let tile = t.tile_at(1e10, 0.0).unwrap();
    assert!(t.bounds().unwrap().contains(t.offset_of(tile)), "{tile:?}");
    let unbounded = Terrain::new(MapConfig { size: MapSize::Unbounded, ..MapConfig::default() }).unwrap();
    assert_eq!(unbounded.tile_info(Hex::new(1 << 30, -(1 << 30))), None);
    assert_eq!(unbounded.surface_height(1e9, 1e9), None);
    // An error about a tile at `i32`'s end prints (hexx's `Debug` of a `Hex` overflows there).
    assert_eq!(format!("{:?}", EditError::OffMap(Hex::new(i32::MIN, 0))), format!("OffMap([{}, 0])", i32::MIN));
}

/// Tiles inside and outside the world: near the map (and past its edges), anywhere an `i32`
/// reaches, and around the world's edge.
fn any_tile() -> impl Strategy<Value = ([i32; 2], Option<Hex>)> {
    let m = MAX_WORLD_TILE;
    prop_oneof![
        3 => (-6i32..40, -6i32..20).prop_map(|(c, r)| ([c, r], None)),
        1 => (any::<i32>(), any::<i32>()).prop_map(|(x, y)| ([0, 0], Some(Hex::new(x, y)))),
        1 => (m - 3..m + 3, -m - 3..-m + 3, any::<bool>()).prop_map(|(a, b, swap)| (if swap { [b, a] } else { [a, b] }, None)),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// The one rule of the queries (`hex_terrain::terrain`'s docs), over random tiles inside
    /// and outside the world: the terrain at a place answers `Some` exactly in the world, the
    /// map's questions exactly on the map (`contains`, itself checked against the bounds here),
    /// predicates `false` elsewhere, conversions answer everything; nothing panics (overflow
    /// checks on); strokes past the map or with too wide a brush are refused by name.
    #[test]
    fn every_query_follows_the_rule(
        config in config(),
        water in 0u8..3,
        setup in any::<bool>(),
        tiles in prop::collection::vec(any_tile(), 24),
    ) {
        let mut config = config;
        config.climate.enabled = water > 0;
        config.rivers.enabled = water > 1 && config.size.bounds().is_some();
        if setup && config.size.bounds().is_some() {
            config.setup = Some(SetupConfig { players: 1, min_distance: 1, rings: 1, ..SetupConfig::default() });
        }
        let t = match Terrain::new(config.clone()) {
            Ok(t) => t,
            // A map without a tile a start may stand on.
            Err(_) => { config.setup = None; Terrain::new(config).unwrap() }
        };
        let m = i64::from(MAX_WORLD_TILE);
        for (offset, raw) in tiles {
            let tile = raw.unwrap_or_else(|| t.tile_from_offset(offset));
            let world = t.in_world(tile);
            let on_map = t.contains(tile);
            // Membership, from the offset coordinate (a conversion: it answers any tile).
            if world {
                let [c, r] = t.offset_of(tile);
                prop_assert!((-m..m).contains(&i64::from(c)) && (-m..m).contains(&i64::from(r)));
                prop_assert_eq!(t.tile_from_offset([c, r]), tile);
                let expected = match (t.bounds(), t.wrap()) {
                    (None, _) => true,
                    (Some(b), Some(_)) => (b.min[1]..b.max[1]).contains(&r),
                    (Some(b), None) => b.contains([c, r]),
                };
                prop_assert_eq!(on_map, expected, "contains({:?}) at offset {:?}", tile, [c, r]);
            } else {
                prop_assert!(!on_map);
            }
            // The terrain at a place: exactly in the world.
            prop_assert_eq!(t.tile_kind(tile).is_some(), world);
            prop_assert_eq!(biome::at(&t, tile).is_some(), world);
            prop_assert_eq!(t.tile_center(tile).is_some(), world);
            prop_assert_eq!(t.tile_climate(tile).is_some(), world && t.climate().is_enabled());
            prop_assert_eq!(t.distance(tile, t.tile_from_offset([0, 0])).is_some(), world);
            let info = t.tile_info(tile);
            prop_assert_eq!(info.is_some(), world);
            if let Some(info) = info {
                prop_assert_eq!(info.in_map, on_map);
            }
            // The map: exactly on the map.
            prop_assert_eq!(t.wrap_tile(tile).is_some(), on_map);
            prop_assert_eq!(t.chunk_of(tile).is_some(), on_map);
            prop_assert_eq!(t.map_tile_kind(tile).is_some(), on_map);
            prop_assert_eq!(t.river_flow(tile).is_some(), on_map);
            prop_assert!(on_map || (t.river(tile).is_none() && t.lake(tile).is_none() && t.water_level(tile).is_none()));
            prop_assert!(on_map || (t.tile_setup(tile).is_none() && t.start(tile).is_none() && t.resource(tile).is_none()));
            prop_assert!(on_map || !t.tile_is_wet(tile));
            // The movement rule: the model's cost of the tile's biome and river, on the map.
            let rule = t.tile_info(tile).filter(|_| on_map).and_then(|i| t.config().movement.enter(biome::of(&t, &i), i.river_flow > 0.0));
            prop_assert_eq!(t.move_cost(tile), rule);
            let around = t.neighbors(tile);
            prop_assert_eq!(around.is_some(), on_map);
            if let (Some(around), Some(own), Some(info)) = (around, t.wrap_tile(tile), info) {
                prop_assert!(t.contains(own) && t.bounds().is_none_or(|b| b.contains(t.offset_of(own))));
                prop_assert_eq!(t.river_flow(tile), Some(info.river_flow));
                let chunk = t.chunk_of(tile).unwrap();
                prop_assert!(t.chunk_rect(chunk).is_some_and(|r| r.contains(t.offset_of(own))), "{:?} not in {:?}", tile, chunk);
                for (n, raw) in around.iter().zip(tile.all_neighbors()) {
                    prop_assert_eq!(n.is_some(), t.contains(raw), "neighbor {:?} of {:?}", raw, tile);
                    prop_assert_eq!(*n, t.wrap_tile(raw));
                }
                let center = t.lattice().tile_center(tile);
                prop_assert!(t.raw_height(center).is_some() && t.source_height(center).is_some());
                prop_assert!(t.vertex(center).is_some() && t.noise_position(center).is_some());
                prop_assert!(t.water_cover(tile, center).is_some_and(|c| (0.0..=1.0).contains(&c)));
            }
            // Conversions answer every tile.
            let _ = (t.wrap_point(tile), t.tile_near(tile, Hex::ZERO), t.tile_near(Hex::ZERO, tile));
            // A stroke off the map is refused by name, and its error prints.
            if !on_map {
                let mut editor = Editor::from_terrain(t.clone());
                let e = editor.apply(Stroke { tool: Tool::Raise(0.1), brush: Brush::Range(1), tile }).unwrap_err();
                prop_assert_eq!(&e, &EditError::OffMap(tile));
                let printed = format!("{e:?} {e}");
                prop_assert!(printed.contains("OffMap"));
            }
        }
        // A brush wider than the most is refused, not clamped.
        let tile = t.tile_from_offset([0, 0]);
        let mut editor = Editor::from_terrain(t);
        let stroke = Stroke { tool: Tool::Raise(0.1), brush: Brush::Range(hex_terrain::MAX_BRUSH_RADIUS + 1), tile };
        prop_assert_eq!(editor.apply(stroke), Err(EditError::Range { radius: hex_terrain::MAX_BRUSH_RADIUS + 1 }));
        prop_assert_eq!(editor.undo_len(), 0);
    }
}
