//! Every shipped map config parses, validates, round-trips through RON and generates.

use std::path::{Path, PathBuf};

use hex_terrain::{ClimateConfig, MapConfig, MapSize, Terrain, TileKind};
#[path = "common/biome.rs"]
mod biome;

fn maps_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/maps")
}

fn ron_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            ron_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "ron") {
            out.push(path);
        }
    }
}

#[test]
fn every_asset_loads_round_trips_and_generates() {
    let mut files = Vec::new();
    ron_files(&maps_dir(), &mut files);
    files.sort();
    assert!(files.len() >= 16 + 6 + 6 + 4, "thesis maps, Civ6 presets, map types and demo maps: {files:?}");
    for path in files {
        // The Bevy plugin's loader claims `*.map.ron` only: every shipped map must be loadable.
        assert!(path.to_string_lossy().ends_with(".map.ron"), "{} is not a .map.ron", path.display());
        let config = MapConfig::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert_eq!(MapConfig::from_ron(&config.to_ron()).unwrap(), config, "{}", path.display());
        if config.size.globe().is_some() {
            let globe = hex_terrain::GlobeTerrain::new(config).unwrap();
            let chunk = globe.generate(globe.chunks()[1]);
            assert!(!chunk.tiles.is_empty(), "{}", path.display());
            assert!(chunk.buffers.positions.iter().flatten().all(|v| v.is_finite()));
            let sea = globe.sea_share();
            assert!((0.4..=0.8).contains(&sea), "{}: {sea} of the tiles are sea", path.display());
            if let Some(report) = globe.map_type_report() {
                assert!(report.met(), "{}: {report}", path.display());
            }
            continue;
        }
        let terrain = Terrain::new(config.clone()).unwrap();
        let chunk = terrain.generate_rect(hex_terrain::TileRect::new([0, 0], [8, 8]));
        assert_eq!(chunk.tiles.len(), 64, "{}", path.display());
        assert!(chunk.buffers.positions.iter().flatten().all(|v| v.is_finite()));
    }
}

#[test]
fn thesis_maps_are_the_sixteen_of_section_7() {
    let load = |i: u32| MapConfig::load(maps_dir().join(format!("thesis/map{i:02}.map.ron"))).unwrap();
    let map0 = load(0);
    assert_eq!(map0, MapConfig { name: "Map0".into(), ..MapConfig::default() });
    assert_eq!(load(2).size, MapSize::Bounded { x: 40, z: 20 });
    assert_eq!(load(5).seed, 2401);
    assert_eq!(load(7).noise.scale, 5.0);
    assert_eq!(load(13).size, MapSize::Bounded { x: 200, z: 100 });
    assert_eq!(load(15).terrain.max_elevation, 100.0);
    // Map14/15 only scale heights: same tile types as Map0 (thesis 7.3.4).
    let kinds = |c: MapConfig| {
        let t = Terrain::new(c).unwrap();
        t.tiles().map(|h| t.tile_kind(h).unwrap()).collect::<Vec<TileKind>>()
    };
    assert_eq!(kinds(load(14)), kinds(map0.clone()));
    assert_eq!(kinds(load(15)), kinds(map0));
}

/// Biome counts (in `Biome::ALL` order), river tiles and lakes of each preset with a climate:
/// a change to climate, rivers or lakes changes these and must update the table in the same
/// commit. The continent is unbounded (climate only): its counts are of the 48x32 tiles at the
/// origin.
const PRESETS: [(&str, [usize; 13], usize, usize); 17] = include!("presets_golden.in");

#[test]
fn presets_keep_their_biomes_rivers_and_lakes() {
    let (mut rows, mut changed) = (Vec::new(), false);
    for (file, biomes, rivers, lakes) in PRESETS {
        let config = MapConfig::load(maps_dir().join(file)).unwrap();
        assert!(config.climate.enabled, "{file} has no climate");
        let t = Terrain::new(config).unwrap();
        let tiles: Vec<_> = match t.bounds() {
            Some(_) => t.tiles().collect(),
            None => hex_terrain::TileRect::new([0, 0], [48, 32]).iter().map(|oc| t.tile_from_offset(oc)).collect(),
        };
        let counts = hex_terrain::Biome::ALL.map(|b| tiles.iter().filter(|&&h| biome::at(&t, h).unwrap() == b).count());
        let got = (counts, t.rivers().len(), t.hydrology().map_or(0, |h| h.lake_count()));
        changed |= got != (biomes, rivers, lakes);
        rows.push(format!("    (\"{file}\", {:?}, {}, {}),", got.0, got.1, got.2));
    }
    assert!(!changed, "presets changed; if intended, presets_golden.in becomes:\n[\n{}\n]", rows.join("\n"));
}

#[test]
fn the_world_preset_has_every_biome_rivers_and_lakes() {
    let config = MapConfig::load(maps_dir().join("world.map.ron")).unwrap();
    let t = Terrain::new(config.clone()).unwrap();
    let present: std::collections::HashSet<_> = t.tiles().map(|h| biome::at(&t, h).unwrap()).collect();
    for b in hex_terrain::Biome::ALL {
        assert!(present.contains(&b), "no {b:?} in the world preset");
    }
    // Lakes only in deep basins, as few as a Civilization map has (at most 6 per 1,000 land tiles).
    let lakes = t.hydrology().unwrap().lake_count();
    let land_tiles = t.tiles().filter(|&h| t.tile_kind(h).unwrap() != TileKind::Sea).count();
    assert!((1..=land_tiles * 6 / 1000).contains(&lakes), "{lakes} lakes on {land_tiles} land tiles");
    // Its rivers run on tile edges, Civilization's way, and reach at least 15 % of the land.
    let land: Vec<_> = t.tiles().filter(|&h| t.tile_kind(h).unwrap() != TileKind::Sea && t.lake(h).is_none()).collect();
    let on_river = land.iter().filter(|&&h| !t.river_edges(h).is_empty()).count();
    assert!(on_river * 100 >= land.len() * 15, "{on_river} of {} land tiles on a river", land.len());
    // With rivers through tile centers, they rise on wet ground: their sources are wetter than
    // land, on average; and, with the moisture fBm's climate (where the rain is the same high
    // and low), on high ground too. With winds the highlands inland lie in a rain shadow, so
    // sources are where the rain falls, not where the land is highest.
    // The Island preset (a noise island, no map type) under the World's winds shows it.
    let mut centers = MapConfig::load(maps_dir().join("island.map.ron")).unwrap();
    centers.climate = ClimateConfig { winds: config.climate.winds.clone(), lapse_rate: 0.55, ..centers.climate };
    centers.rivers = hex_terrain::RiverConfig { enabled: true, threshold: 5.0, ..Default::default() };
    // As it was before it had winds: no winds, rivers from 8 units of rain.
    let mut without_winds =
        MapConfig { climate: ClimateConfig { winds: None, ..centers.climate.clone() }, ..centers.clone() };
    without_winds.rivers.threshold = 8.0;
    for (t, higher) in [(Terrain::new(centers).unwrap(), false), (Terrain::new(without_winds).unwrap(), true)] {
        let rivers = t.rivers();
        let sources: Vec<_> = rivers.iter().filter(|r| r.upstream.is_empty()).collect();
        assert!(sources.len() >= 10, "{} sources", sources.len());
        let mean = |tiles: &mut dyn Iterator<Item = hex_terrain::hexx::Hex>| {
            let (mut h, mut m, mut n) = (0.0, 0.0, 0.0);
            for tile in tiles {
                h += t.raw_height(t.lattice().tile_center(tile)).unwrap();
                m += t.tile_climate(tile).unwrap().moisture;
                n += 1.0;
            }
            (h / n, m / n)
        };
        let land = mean(&mut t.tiles().filter(|&h| t.tile_kind(h).unwrap() != TileKind::Sea && t.lake(h).is_none()));
        let at_sources = mean(&mut sources.iter().map(|r| r.hex));
        let along = mean(&mut rivers.iter().map(|r| r.hex));
        assert!(!higher || at_sources.0 > along.0 + 0.01, "sources {at_sources:?}, river tiles {along:?}");
        assert!(at_sources.1 > land.1 + 0.05, "sources {at_sources:?}, land {land:?}");
    }
}
