//! Rivers on the edges between tiles (`rivers.model: Edges`) over random bounded maps, wrapping
//! or not: every river edge lies between two land tiles of the map and is the same seen from
//! either side, a step crosses exactly the river edges, every course runs downstream (its level
//! never rises, its flow grows) to the sea, a lake or the map's edge without a loop, and every
//! river rises at least `sea_distance` tiles from the sea (distances counted here, by a
//! breadth-first search of the test's own).

use std::collections::{HashSet, VecDeque};

use hex_terrain::hexx::{GridEdge, GridVertex, Hex};
use hex_terrain::{
    Biome, MapConfig, MapSize, MapType, MapTypeConfig, NoiseConfig, Orientation, RIVER_MIN_LANDMASS, RiverEdge,
    RiverEdit, RiverModel, RiverSources, Terrain, TileEdit, TileKind, WaterLevel,
};
use proptest::prelude::*;

#[path = "common/biome.rs"]
mod biome;
mod common;

prop_compose! {
    fn config()(
        seed in any::<u32>(),
        (x, z) in (4u32..40, 1u32..30),
        scale in 6.0f64..30.0,
        sea in 0.15f32..0.45,
        climate in any::<bool>(),
        pointy in any::<bool>(),
        wrap in any::<bool>(),
        threshold in 1.0f32..10.0,
        sea_distance in 0u32..4,
        lakes in any::<bool>(),
        relief in prop::option::of(2.0f32..30.0),
        map_type in prop::option::weighted(0.3, 0usize..6),
    ) -> MapConfig {
        let mut c = MapConfig {
            seed,
            size: MapSize::Bounded { x, z },
            noise: NoiseConfig { scale, ..NoiseConfig::default() },
            chunk_size: (8, 8),
            ..MapConfig::default()
        };
        c.terrain.sea_threshold = sea;
        c.climate.enabled = climate;
        c.layout.orientation = if pointy { Orientation::Pointy } else { Orientation::Flat };
        c.rivers.enabled = true;
        c.rivers.model = RiverModel::Edges;
        c.rivers.threshold = threshold;
        c.rivers.sea_distance = sea_distance;
        c.rivers.lakes = lakes;
        if let Some(tiles_per_edge) = relief {
            c.rivers.sources = RiverSources::Relief { tiles_per_edge };
        }
        if let Some(kind) = map_type {
            c.size = MapSize::Bounded { x: x.max(8), z: z.max(8) };
            c.map_type = Some(MapTypeConfig { kind: MapType::ALL[kind], ranges: true, ..MapTypeConfig::default() });
        }
        common::wrapping(c, wrap)
    }
}

/// A tile brought onto the map, if it is on it.
fn on_map(t: &Terrain, tile: Hex) -> Option<Hex> {
    t.wrap_tile(tile).filter(|&h| t.contains(h))
}

/// Whether a tile holds water: sea or lake.
fn wet(t: &Terrain, tile: Hex) -> bool {
    t.tile_kind(tile) == Some(TileKind::Sea) || t.lake(tile).is_some()
}

/// A corner as the tiles it joins, brought onto the map (so the names of a corner from either
/// side of a wrapping map's seam compare equal).
fn corner(t: &Terrain, v: GridVertex) -> Vec<Option<Hex>> {
    let mut tiles: Vec<Option<Hex>> = v.coordinates().into_iter().map(|c| t.wrap_tile(c)).collect();
    tiles.sort_by_key(|h| h.map(|h| (h.x, h.y)));
    tiles
}

/// An edge as the two tiles it lies between, brought onto the map.
fn side(t: &Terrain, e: GridEdge) -> Vec<Option<Hex>> {
    let mut tiles = vec![t.wrap_tile(e.origin), t.wrap_tile(e.destination())];
    tiles.sort_by_key(|h| h.map(|h| (h.x, h.y)));
    tiles
}

/// The river edge `edge` names, looked up from its origin's side.
fn river_on(t: &Terrain, edge: GridEdge) -> Option<RiverEdge> {
    let origin = on_map(t, edge.origin)?;
    t.river_edges(origin).into_iter().find(|r| r.edge.direction == edge.direction)
}

/// Each tile's distance to the nearest sea tile, in steps over the map.
fn sea_distance_of(t: &Terrain) -> std::collections::HashMap<Hex, u32> {
    let mut far = std::collections::HashMap::new();
    let mut queue = VecDeque::new();
    for tile in t.tiles() {
        if t.tile_kind(tile) == Some(TileKind::Sea) {
            far.insert(tile, 0);
            queue.push_back(tile);
        }
    }
    while let Some(tile) = queue.pop_front() {
        let d = far[&tile];
        for nb in tile.all_neighbors().into_iter().filter_map(|n| on_map(t, n)) {
            far.entry(nb).or_insert_with(|| {
                queue.push_back(nb);
                d + 1
            });
        }
    }
    far
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn edge_rivers_run_downstream_between_land_tiles_to_the_sea_a_lake_or_the_edge(config in config()) {
        let threshold = config.rivers.threshold;
        let min_sea = config.rivers.sea_distance;
        let relief = matches!(config.rivers.sources, RiverSources::Relief { .. });
        let t = Terrain::new(config.clone()).unwrap();
        // No river runs through a tile center on such a map.
        prop_assert!(t.rivers().is_empty());
        let far = sea_distance_of(&t);
        let mut all = Vec::new();
        for tile in t.tiles() {
            prop_assert_eq!(t.river_flow(tile), Some(0.0));
            let edges = t.river_edges(tile);
            for (d, nb) in tile.all_neighbors().into_iter().enumerate() {
                let Some(nb) = on_map(&t, nb) else {
                    prop_assert!(edges.iter().all(|r| r.edge.direction.index() as usize != d), "a river on the map's edge");
                    continue;
                };
                let river = edges.iter().find(|r| r.edge.direction.index() as usize == d);
                prop_assert_eq!(t.crosses_river(tile, nb), river.is_some(), "{:?} -> {:?}", tile, nb);
                let Some(r) = river else { continue };
                prop_assert_eq!(r.edge.origin, tile);
                prop_assert!(!wet(&t, tile) && !wet(&t, nb), "a river edge beside water at {:?} -> {:?}", tile, nb);
                // Rivers rising where the flow reaches the threshold carry it at least.
                prop_assert!(relief || r.flow >= threshold, "flow {} below the threshold", r.flow);
                let [p, q] = r.edge.vertices();
                prop_assert!(r.downstream == p || r.downstream == q);
                // The same river seen from the other side.
                let back = t.river_edges(nb).into_iter().find(|b| on_map(&t, b.edge.destination()) == Some(tile));
                prop_assert!(back.is_some(), "{:?} has no river toward {:?}", nb, tile);
                let back = back.unwrap();
                prop_assert_eq!(back.flow.to_bits(), r.flow.to_bits());
                prop_assert_eq!(back.level.to_bits(), r.level.to_bits());
                prop_assert_eq!(corner(&t, back.downstream), corner(&t, r.downstream));
                // The channel: the point halfway between the two centers (when the lattice has
                // one) lies on the edge, covered by water in full as either tile reads it.
                let lattice = t.lattice();
                let (a, b) = (lattice.tile_center(tile), lattice.tile_center(r.edge.destination()));
                let d = b - a;
                if d.x % 2 == 0 && d.y % 2 == 0 {
                    let mid = a + Hex::new(d.x / 2, d.y / 2);
                    prop_assert_eq!(t.water_cover(tile, mid), Some(1.0));
                    prop_assert_eq!(t.water_cover(nb, t.lattice().tile_center(nb) + (mid - b)), Some(1.0));
                }
                prop_assert!(t.tile_is_wet(tile) && t.tile_is_wet(nb));
                all.push(*r);
            }
        }
        // Every course: connected, downstream, no loop, ending at water or the map's edge.
        for r in &all {
            let course = t.river_course(r.edge);
            prop_assert!(!course.is_empty() && course.len() <= all.len() / 2, "course of {} edges", course.len());
            prop_assert_eq!(side(&t, course[0]), side(&t, r.edge));
            let mut seen = HashSet::new();
            let mut last: Option<RiverEdge> = None;
            for &edge in &course {
                let here = river_on(&t, edge);
                prop_assert!(here.is_some(), "{:?} on the course carries no river", edge);
                let here = here.unwrap();
                let key = (on_map(&t, edge.origin), edge.direction);
                prop_assert!(seen.insert(key), "the course loops at {:?}", edge);
                if let Some(before) = last {
                    let [p, q] = edge.vertices();
                    let at = corner(&t, before.downstream);
                    prop_assert!(corner(&t, p) == at || corner(&t, q) == at, "a gap before {:?}", edge);
                    prop_assert!(here.level <= before.level, "the river rises: {} after {}", here.level, before.level);
                    prop_assert!(here.flow > before.flow, "the flow shrinks: {} after {}", here.flow, before.flow);
                }
                last = Some(here);
            }
            let mouth: GridVertex = last.unwrap().downstream;
            let ends = mouth.coordinates().into_iter().any(|c| on_map(&t, c).is_none_or(|c| wet(&t, c)));
            prop_assert!(ends, "a river ends at {:?}, away from water and the map's edge", mouth);
            // Rivers rising in the hills run to the sea or a lake, never off the map.
            let in_water = mouth.coordinates().into_iter().any(|c| on_map(&t, c).is_some_and(|c| wet(&t, c)));
            prop_assert!(!relief || in_water, "a river from the hills ends at the map's edge at {:?}", mouth);
        }
        // Sources: an edge no river flows into rises at least `sea_distance` from the sea.
        for r in &all {
            let [p, q] = r.edge.vertices();
            let source = if r.downstream == q { p } else { q };
            let fed = all.iter().any(|o| corner(&t, o.downstream) == corner(&t, source) && side(&t, o.edge) != side(&t, r.edge));
            if !fed {
                let tiles: Vec<Hex> = source.coordinates().into_iter().filter_map(|c| on_map(&t, c)).collect();
                let nearest = tiles.iter().map(|c| far.get(c).copied().unwrap_or(u32::MAX)).min();
                if !relief {
                    prop_assert!(nearest.is_some_and(|d| d >= min_sea), "a source {} from the sea", nearest.unwrap_or(0));
                    continue;
                }
                // Civilization V's passes: the first at `sea_distance` from the sea, the ones
                // filling a landmass' share at half of it, and only on landmasses that big.
                prop_assert!(nearest.is_some_and(|d| d >= min_sea.div_ceil(2)), "a source {} from the sea", nearest.unwrap_or(0));
                let size = landmass_of(&t, tiles[0]);
                prop_assert!(
                    nearest.is_some_and(|d| d >= min_sea) || size >= RIVER_MIN_LANDMASS as usize,
                    "a source {} from the sea on a landmass of {} tiles", nearest.unwrap_or(0), size
                );
                // The first pass rises among hills and mountains; the others only on landmasses
                // given a share.
                let near_relief = tiles.iter().any(|&h| relief_tile(&t, h));
                prop_assert!(near_relief || size >= RIVER_MIN_LANDMASS as usize, "a source off the hills on {} tiles", size);
            }
        }
        // The same network on another thread.
        let there = std::thread::spawn(move || Terrain::new(config).unwrap()).join().unwrap();
        for tile in t.tiles() {
            prop_assert_eq!(t.river_edges(tile), there.river_edges(tile));
        }
    }
}

/// The land tiles (neither sea nor lake) joined to `tile` through their neighbors, counted by a
/// flood fill.
fn landmass_of(t: &Terrain, tile: Hex) -> usize {
    let mut seen = HashSet::from([tile]);
    let mut queue = VecDeque::from([tile]);
    while let Some(at) = queue.pop_front() {
        for nb in at.all_neighbors().into_iter().filter_map(|n| on_map(t, n)) {
            if !wet(t, nb) && seen.insert(nb) {
                queue.push_back(nb);
            }
        }
    }
    seen.len()
}

/// Whether a tile is hills or a mountain (not under a lake).
fn relief_tile(t: &Terrain, tile: Hex) -> bool {
    let info = t.tile_info(tile).unwrap();
    biome::of(t, &info) == Biome::Hills || (info.kind == TileKind::Mountain && info.lake.is_none())
}

/// Every river edge of the map, each once (named from the first of its two tiles visited).
fn all_river_edges(t: &Terrain) -> Vec<RiverEdge> {
    let mut seen = HashSet::new();
    t.tiles().flat_map(|tile| t.river_edges(tile)).filter(|r| seen.insert(side(t, r.edge))).collect()
}

/// Whether a corner drains: its three tiles lie on the map and are land without a lake (a
/// corner touching water or the map's edge is an outlet).
fn drains(t: &Terrain, v: GridVertex) -> bool {
    v.coordinates().into_iter().all(|c| on_map(t, c).is_some_and(|c| !wet(t, c)))
}

/// Whether a river edge touches one of `tile`'s corners that drain.
fn river_at_a_corner(t: &Terrain, all: &[RiverEdge], tile: Hex) -> bool {
    let corners: Vec<_> = tile.all_vertices().into_iter().filter(|&v| drains(t, v)).map(|v| corner(t, v)).collect();
    all.iter().any(|r| r.edge.vertices().into_iter().any(|v| corners.contains(&corner(t, v))))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// A river set by hand rises at its tile wherever that lies from the sea: a tile with a corner
    /// that drains has a river edge at one of them, whatever flows in from upstream (a stream
    /// dropped for rising near the sea, too).
    #[test]
    fn a_source_set_by_hand_always_rises(
        config in config(),
        sea_distance in 1u32..6,
        picks in proptest::collection::vec(any::<u32>(), 1..24),
    ) {
        let mut config = config;
        config.rivers.sea_distance = sea_distance;
        let t = Terrain::new(config.clone()).unwrap();
        // Sources on land, most of them near the sea, where streams are dropped for rising too
        // near it.
        let far = sea_distance_of(&t);
        let land: Vec<Hex> = t.tiles().filter(|&h| !wet(&t, h)).collect();
        let near: Vec<Hex> = land.iter().copied().filter(|h| far.get(h).is_some_and(|&d| d < sea_distance)).collect();
        prop_assume!(!land.is_empty());
        let sources: Vec<Hex> = picks
            .iter()
            .map(|&p| if p % 4 != 0 && !near.is_empty() { near[p as usize / 4 % near.len()] } else { land[p as usize % land.len()] })
            .collect();
        let mut edited = config;
        for &tile in &sources {
            let [col, row] = t.offset_of(tile);
            if !edited.edits.iter().any(|e| e.at == (col, row)) {
                edited.edits.push(TileEdit { river: Some(RiverEdit::Source), ..TileEdit::at((col, row)) });
            }
        }
        let e = Terrain::new(edited).unwrap();
        let all = all_river_edges(&e);
        for &tile in &sources {
            if tile.all_vertices().into_iter().any(|v| drains(&e, v)) {
                prop_assert!(river_at_a_corner(&e, &all, tile), "no river rises at {:?}", e.offset_of(tile));
            }
        }
    }
}

/// The case that was found: a source set by hand where a stream dropped for rising within
/// `sea_distance` of the sea already flows into the tile's lowest corner.
#[test]
fn a_source_set_by_hand_rises_where_a_dropped_stream_flows_in() {
    let mut c = MapConfig {
        seed: 2_791_030_992,
        size: MapSize::Bounded { x: 40, z: 19 },
        map_type: Some(MapTypeConfig {
            kind: MapType::SmallContinents,
            water: WaterLevel::Low,
            mountains: 0.08,
            ranges: false,
        }),
        ..MapConfig::default()
    };
    c.layout.orientation = Orientation::Pointy;
    c.rivers.enabled = true;
    c.rivers.threshold = 1.395_399_6;
    c.rivers.min_lake_depth = 0.0;
    c.rivers.model = RiverModel::Edges;
    c.rivers.sea_distance = 4;
    c.edits.push(TileEdit { river: Some(RiverEdit::Source), ..TileEdit::at((22, 7)) });
    let t = Terrain::new(c).unwrap();
    let tile = t.tile_from_offset([22, 7]);
    assert!(tile.all_vertices().into_iter().any(|v| drains(&t, v)), "the tile has a corner that drains");
    assert!(river_at_a_corner(&t, &all_river_edges(&t), tile), "a river rises at the tile");
}

/// The World preset with edge rivers: how many river edges a land tile has, printed, and some.
#[test]
fn the_world_preset_has_edge_rivers() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../bevy_hex_terrain/assets/maps/world.map.ron");
    let mut config = MapConfig::load(path).unwrap();
    config.setup = None;
    assert_eq!(config.rivers.model, RiverModel::Edges, "the World preset's rivers run on edges");
    let t = Terrain::new(config).unwrap();
    let land = t.tiles().filter(|&h| !wet(&t, h)).count();
    let edges: usize = t.tiles().map(|h| t.river_edges(h).len()).sum::<usize>() / 2;
    println!(
        "World preset, edge rivers: {edges} river edges over {land} land tiles (one per {:.1})",
        land as f64 / edges as f64
    );
    assert!(edges > land / 40, "{edges} river edges over {land} land tiles");
}
