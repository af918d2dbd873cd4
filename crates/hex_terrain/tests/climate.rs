//! Biomes, rivers and lakes: properties over random configs (rivers never rise and end in the
//! sea, a lake or the map edge; no cycles; lakes are enclosed and below their spill height;
//! carving only lowers; biomes are a function of position) and every new field's validation.
//! Chunked = whole, seams and the type ranges with climate and rivers on are in
//! `invariants.rs`, whose random configs turn them on.

use std::collections::HashSet;

use hex_terrain::hexx::Hex;
use hex_terrain::{
    Biome, ChunkCoord, GenerateOptions, HeightImage, MapConfig, MapSize, NoiseConfig, Shape, Terrain, TileKind,
};
use proptest::prelude::*;
#[path = "common/biome.rs"]
mod biome;

prop_compose! {
    fn wet_config()(
        seed in any::<u32>(),
        size in (6u32..40, 6u32..30),
        scale in 10.0f64..200.0,
        octaves in 1u32..8,
        persistence in 0.2f64..0.7,
        sea in 0.1f32..0.45,
        shape in prop_oneof![
            Just(Shape::None),
            (0.5f32..4.0, 0.3f32..3.0).prop_map(|(a, b)| Shape::Island { a, b }),
            (0.5f32..4.0, 0.3f32..3.0).prop_map(|(a, b)| Shape::Mediterranean { a, b }),
            (0.0f32..0.4, 0.6f32..1.0).prop_map(|(min, max)| Shape::Inland { min, max }),
        ],
        threshold in 1.0f32..15.0,
        min_lake_depth in prop_oneof![Just(0.0f32), 0.0f32..0.05],
        climate in any::<bool>(),
        rings in 1u32..4,
    ) -> MapConfig {
        let mut c = MapConfig {
            seed,
            size: MapSize::Bounded { x: size.0, z: size.1 },
            noise: NoiseConfig { octaves, persistence, lacunarity: 2.0, scale },
            shape,
            ..MapConfig::default()
        };
        c.terrain.sea_threshold = sea;
        c.terrain.inner_rings = rings;
        c.climate.enabled = climate;
        c.rivers.enabled = true;
        c.rivers.threshold = threshold;
        c.rivers.min_lake_depth = min_lake_depth;
        c
    }
}

fn on_edge(t: &Terrain, tile: Hex) -> bool {
    tile.all_neighbors().iter().any(|&nb| !t.contains(nb))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// Every river flows to a tile whose water level is not higher, with more water, and ends
    /// in the sea, a lake or off the map edge; following it never comes back to a tile.
    #[test]
    fn rivers_never_rise_never_cycle_and_end_in_sea_lake_or_edge(config in wet_config()) {
        let t = Terrain::new(config).unwrap();
        let tiles: Vec<Hex> = t.tiles().collect();
        for r in t.rivers() {
            prop_assert!(t.tile_kind(r.hex).unwrap() != TileKind::Sea && t.lake(r.hex).is_none());
            let mut seen = HashSet::new();
            let mut here = r.clone();
            loop {
                prop_assert!(seen.insert(here.hex), "river through {:?} comes back to {:?}", r.hex, here.hex);
                prop_assert!(seen.len() <= tiles.len());
                let Some(next) = here.downstream else {
                    prop_assert!(on_edge(&t, here.hex), "{:?} ends inland without an outlet", here.hex);
                    break;
                };
                prop_assert!(here.hex.unsigned_distance_to(next) == 1);
                let level = t.water_level(next).unwrap();
                prop_assert!(level <= here.level, "{:?} ({}) flows up to {:?} ({})", here.hex, here.level, next, level);
                if t.tile_kind(next).unwrap() == TileKind::Sea || t.lake(next).is_some() {
                    break;
                }
                let down = t.river(next);
                prop_assert!(down.is_some(), "{:?} flows into {:?}, which is neither river, lake nor sea", here.hex, next);
                let down = down.unwrap();
                prop_assert!(down.flow > here.flow, "flow does not grow from {:?} to {:?}", here.hex, next);
                prop_assert!(down.upstream.contains(&here.hex));
                here = down;
            }
        }
    }

    /// Every lake tile lies below its lake's spill height, is not on the map edge, and is
    /// enclosed: each neighbor is in the same lake or at least as high as the spill height less
    /// the minimum depth.
    #[test]
    fn lakes_are_enclosed_and_below_their_spill_height(config in wet_config()) {
        let min_depth = config.rivers.min_lake_depth;
        let t = Terrain::new(config).unwrap();
        let h = t.hydrology().unwrap();
        let mut lakes = HashSet::new();
        for tile in t.tiles() {
            let Some(lake) = t.lake(tile) else { continue };
            lakes.insert(lake);
            let spill = h.spill_height(lake).unwrap();
            let center = t.raw_height(t.lattice().tile_center(tile)).unwrap();
            prop_assert!(center + min_depth < spill, "lake tile {:?} at {} not below spill {}", tile, center, spill);
            prop_assert!(!on_edge(&t, tile));
            prop_assert_eq!(biome::at(&t, tile).unwrap(), Biome::Lake);
            for nb in tile.all_neighbors() {
                if t.lake(nb) == Some(lake) { continue; }
                prop_assert!(t.lake(nb).is_none(), "two lakes touch at {:?}", nb);
                let rim = t.raw_height(t.lattice().tile_center(nb)).unwrap();
                prop_assert!(rim >= spill - min_depth, "lake {} leaks through {:?} ({} < {})", lake, nb, rim, spill);
            }
        }
        prop_assert_eq!(lakes.len(), h.lake_count());
    }

    /// Carving only lowers: every vertex of the map with rivers is at or below the same vertex
    /// with `carve: 0`, strictly below on a river tile's center that lay above the bottom of its
    /// range, and dry vertices do not move.
    #[test]
    fn channels_are_lower_than_their_banks(config in wet_config()) {
        let t = Terrain::new(config.clone()).unwrap();
        let mut flat = config;
        flat.rivers.carve = 0.0;
        let f = Terrain::new(flat).unwrap();
        let max = t.config().terrain.max_elevation;
        let carved = t.generate(t.bounds().unwrap(), GenerateOptions::DIAGNOSTICS);
        let plain = f.generate(f.bounds().unwrap(), GenerateOptions::DIAGNOSTICS);
        let lattice = &carved.diagnostics.as_ref().unwrap().lattice;
        for (p, (a, b)) in lattice.iter().zip(carved.buffers.positions.iter().zip(&plain.buffers.positions)) {
            prop_assert!(a[1] <= b[1]);
            if t.vertex(*p).unwrap().water == 0.0 {
                prop_assert_eq!(a[1].to_bits(), b[1].to_bits());
            }
        }
        for r in t.rivers() {
            let p = t.lattice().tile_center(r.hex);
            let lo = t.thresholds().range(t.tile_kind(r.hex).unwrap()).0;
            let (c, b) = (t.vertex(p).unwrap().height, f.vertex(p).unwrap().height);
            if b > lo + 1e-6 {
                prop_assert!(c < b, "river tile {:?} center not carved: {} vs {}", r.hex, c * max, b * max);
            }
            prop_assert!(t.vertex(p).unwrap().water > 0.99);
        }
    }

    /// Biomes are a function of position: a chunk's tiles carry the biome the terrain gives the
    /// tile alone, on bounded and unbounded maps.
    #[test]
    fn biomes_are_a_function_of_position(config in wet_config(), unbounded in any::<bool>(), chunk in (-3i32..3, -3i32..3)) {
        let mut c = config;
        c.chunk_size = (5, 4);
        if unbounded {
            c.size = MapSize::Unbounded;
            c.shape = Shape::None;
            c.rivers.enabled = false;
            c.climate.enabled = true;
        }
        let t = Terrain::new(c).unwrap();
        let Some(m) = t.generate_chunk(ChunkCoord::new(chunk.0, chunk.1)) else { return Ok(()) };
        for info in &m.tiles {
            prop_assert_eq!(info, &t.tile_info(info.hex).unwrap());
        }
    }
}

/// A heightmap with a valley running from a high west to a sea in the east, and a closed basin:
/// the rivers run down the valley and the basin holds a lake.
#[test]
fn a_heightmap_puts_rivers_in_its_valleys_and_lakes_in_its_basins() {
    let (w, h) = (96usize, 64usize);
    let mut data = vec![0.0_f32; w * h];
    for y in 0..h {
        for x in 0..w {
            let u = x as f32 / (w - 1) as f32;
            let v = y as f32 / (h - 1) as f32;
            // High in the west, sea in the east; a valley along v = 0.3.
            let mut z = 0.75 - 0.6 * u + 0.8 * (v - 0.3).abs();
            // A basin around (0.3, 0.75), ringed by a rim.
            let d = ((u - 0.3).powi(2) + (v - 0.75).powi(2)).sqrt();
            if d < 0.12 {
                z = 0.45 + d;
            } else if d < 0.2 {
                z = z.max(0.7);
            }
            data[y * w + x] = z.clamp(0.0, 1.0);
        }
    }
    let image = std::sync::Arc::new(HeightImage::from_samples(w, h, data).unwrap());
    let mut c =
        MapConfig::from_ron(r#"(size: Bounded(x: 48, z: 32), source: Image(path: "valley.png", sea_level: 0.2))"#)
            .unwrap();
    c.rivers.enabled = true;
    c.rivers.threshold = 30.0;
    let t = Terrain::with_sources(c, Some(image), None).unwrap();
    let rivers = t.rivers();
    assert!(rivers.len() >= 20, "{} river tiles", rivers.len());
    // The biggest river reaches the sea down the valley (around row 0.3 * 31).
    let mouth = rivers
        .iter()
        .filter(|r| r.downstream.is_some_and(|d| t.tile_kind(d).unwrap() == TileKind::Sea))
        .max_by(|a, b| a.flow.total_cmp(&b.flow))
        .expect("a river reaches the sea");
    let row = t.offset_of(mouth.hex)[1];
    assert!((6..=13).contains(&row), "the main river's mouth is at row {row}, off the valley");
    // Following it upstream along its biggest branch stays in the valley for most of the map.
    let mut here = mouth.clone();
    let mut in_valley = 0;
    while let Some(up) = here.upstream.iter().filter_map(|&u| t.river(u)).max_by(|a, b| a.flow.total_cmp(&b.flow)) {
        in_valley += usize::from((6..=13).contains(&t.offset_of(up.hex)[1]));
        here = up;
    }
    assert!(in_valley >= 20, "only {in_valley} tiles of the main river in the valley");
    let basin = t.tile_from_offset([14, 24]);
    assert!(t.lake(basin).is_some(), "the basin holds no lake");
}

#[test]
fn every_new_field_out_of_range_is_refused_by_name() {
    type Edit = fn(&mut MapConfig);
    let cases: [(&str, Edit); 16] = [
        ("climate.moisture.octaves", |c| c.climate.moisture.octaves = 0),
        ("climate.moisture.persistence", |c| c.climate.moisture.persistence = f64::NAN),
        ("climate.moisture.lacunarity", |c| c.climate.moisture.lacunarity = 0.5),
        ("climate.moisture.scale", |c| c.climate.moisture.scale = -1.0),
        ("climate.coast_moisture", |c| c.climate.coast_moisture = 1.5),
        ("climate.temperature_scale", |c| c.climate.temperature_scale = f64::INFINITY),
        ("climate.temperature_jitter", |c| c.climate.temperature_jitter = -0.1),
        ("climate.lapse_rate", |c| c.climate.lapse_rate = f32::NAN),
        ("climate.hills", |c| c.climate.hills = 2.0),
        ("climate.biomes[0].relief", |c| c.climate.biomes[0].relief = TileKind::Sea),
        ("climate.biomes[0].biome", |c| c.climate.biomes[0].biome = Biome::Lake),
        ("climate.biomes[2].moisture", |c| c.climate.biomes[2].moisture = (0.5, 0.2)),
        ("rivers.threshold", |c| c.rivers.threshold = 0.0),
        ("rivers.min_lake_depth", |c| c.rivers.min_lake_depth = f32::NAN),
        ("rivers.carve", |c| c.rivers.carve = 1.5),
        ("rivers.width", |c| c.rivers.width = 0.1),
    ];
    for (field, edit) in cases {
        let mut c = MapConfig::default();
        c.climate.enabled = true;
        c.rivers.enabled = true;
        edit(&mut c);
        let e = Terrain::new(c).expect_err(field);
        assert_eq!(e.field, field, "{e}");
        assert!(e.to_string().contains("allowed"), "{e}");
    }
    let e = MapConfig::from_ron("(size: Unbounded, rivers: (enabled: true))").unwrap_err();
    assert!(e.to_string().contains("rivers.enabled"), "{e}");
    let mut c = MapConfig::default();
    c.climate.biomes = vec![c.climate.biomes[0].clone(); hex_terrain::config::MAX_BIOME_RULES + 1];
    assert_eq!(Terrain::new(c).unwrap_err().field, "climate.biomes");
    let e = MapConfig::from_ron("(climate: (enabled: true, biomes: []))").unwrap_err();
    assert!(e.to_string().contains("climate.biomes"), "{e}");
}

#[test]
fn rivers_on_maps_too_large_for_one_network_are_refused_and_climate_still_works() {
    let e = MapConfig::from_ron("(size: Bounded(x: 1000, z: 500), rivers: (enabled: true))").unwrap_err();
    assert!(e.to_string().contains("rivers.enabled") && e.to_string().contains("500000 tiles"), "{e}");
    // A climate on such a map computes biomes per chunk, as on an unbounded map.
    let mut c = MapConfig::from_ron("(size: Bounded(x: 2000, z: 1000), climate: (enabled: true))").unwrap();
    c.chunk_size = (6, 5);
    let t = Terrain::new(c).unwrap();
    let m = t.generate_chunk(ChunkCoord::new(100, 80)).unwrap();
    for info in &m.tiles {
        assert_eq!(info, &t.tile_info(info.hex).unwrap());
    }
    assert!(!m.buffers.colors.is_empty());
}
