//! Map types: every report's numbers against the same numbers computed here another way from
//! the public tile queries (sea and mountains counted, landmasses and seas by union-find, the
//! strait by comparing every pair of continental tiles, the edge from the offsets), and every
//! type meeting its targets on the Civilization sizes, wrapping or not, at every water level.

use hex_terrain::hexx::Hex;
use hex_terrain::{
    CONTINENT_MIN_SHARE, CONTINENT_MIN_TILES, LoadError, MAX_TRIES, MapConfig, MapSize, MapType, MapTypeConfig,
    MapTypeReport, MapTypeTarget, NoiseConfig, Terrain, TileKind, WaterLevel,
};
use proptest::prelude::*;

#[path = "common/sets.rs"]
mod sets;
use sets::Sets;

/// Civilization VI's map sizes (columns, rows): Duel to Huge.
const CIV6_SIZES: [(&str, u32, u32); 6] =
    [("Duel", 44, 26), ("Tiny", 60, 38), ("Small", 74, 46), ("Standard", 84, 54), ("Large", 96, 60), ("Huge", 106, 66)];

fn config(kind: MapType, water: WaterLevel, (x, z): (u32, u32), wrap: bool, seed: u32, scale: f64) -> MapConfig {
    MapConfig {
        seed,
        size: MapSize::Bounded { x, z },
        wrap,
        noise: NoiseConfig { octaves: 8, persistence: 0.5, lacunarity: 2.0, scale },
        map_type: Some(MapTypeConfig { kind, water, ..MapTypeConfig::default() }),
        ..MapConfig::default()
    }
}

/// The targets' numbers, computed from the tile queries.
struct Recount {
    sea_share: f64,
    mountain_share: f64,
    landmasses: usize,
    continents: usize,
    largest_share: f64,
    second_share: f64,
    strait: f64,
    largest_sea_share: f64,
    largest_sea_edge_tiles: usize,
    /// The fewest rows a continent spans, over the map's rows (0 without a continent).
    continent_height: f64,
    /// The most mountains in a row along a hex axis.
    straight_ridge: usize,
    /// Mountains with 5 or 6 mountain neighbors, over the mountains.
    blob_share: f64,
}

fn recount(t: &Terrain) -> Recount {
    let tiles: Vec<Hex> = t.tiles().collect();
    let n = tiles.len();
    let at = |h: Hex| tiles.iter().position(|&x| x == h).unwrap();
    let kinds: Vec<TileKind> = tiles.iter().map(|&h| t.tile_kind(h).unwrap()).collect();
    let sea: Vec<bool> = kinds.iter().map(|&k| k == TileKind::Sea).collect();
    let land = sea.iter().filter(|&&s| !s).count();
    let mountains = kinds.iter().filter(|&&k| k == TileKind::Mountain).count();
    let groups = |member: &dyn Fn(usize) -> bool| {
        let mut sets = Sets::new(n);
        for (i, &h) in tiles.iter().enumerate() {
            for nb in t.neighbors(h).unwrap().into_iter().flatten() {
                let j = at(nb);
                if member(i) && member(j) {
                    sets.join(i, j);
                }
            }
        }
        let roots: Vec<Option<usize>> = (0..n).map(|i| member(i).then(|| sets.find(i))).collect();
        let mut sizes = std::collections::HashMap::<usize, usize>::new();
        for r in roots.iter().flatten() {
            *sizes.entry(*r).or_default() += 1;
        }
        (roots, sizes)
    };
    let (mass, mass_sizes) = groups(&|i| !sea[i]);
    let mut sizes: Vec<usize> = mass_sizes.values().copied().collect();
    sizes.sort_unstable_by(|a, b| b.cmp(a));
    let share = |a: usize, b: usize| a as f64 / b.max(1) as f64;
    let continent = |size: usize| size >= CONTINENT_MIN_TILES as usize && share(size, land) >= CONTINENT_MIN_SHARE;
    let continental: Vec<usize> = (0..n).filter(|&i| mass[i].is_some_and(|r| continent(mass_sizes[&r]))).collect();
    let mut strait = f64::INFINITY;
    for (k, &a) in continental.iter().enumerate() {
        for &b in &continental[k + 1..] {
            if mass[a] != mass[b] {
                strait = strait.min(f64::from(t.distance(tiles[a], tiles[b]).unwrap() - 1));
            }
        }
    }
    let (seas, sea_sizes) = groups(&|i| sea[i]);
    let biggest = sea_sizes.iter().max_by_key(|&(&root, &size)| (size, std::cmp::Reverse(root))).map(|(&r, _)| r);
    let rect = t.bounds().unwrap();
    let on_edge = |h: Hex| {
        let [col, row] = t.offset_of(h);
        row == rect.min[1]
            || row == rect.max[1] - 1
            || (t.wrap().is_none() && (col == rect.min[0] || col == rect.max[0] - 1))
    };
    // Each continent's rows, from its tiles' offsets.
    let mut spans = std::collections::HashMap::<usize, (i32, i32)>::new();
    for i in 0..n {
        if let Some(r) = mass[i].filter(|r| continent(mass_sizes[r])) {
            let row = t.offset_of(tiles[i])[1];
            let s = spans.entry(r).or_insert((row, row));
            *s = (s.0.min(row), s.1.max(row));
        }
    }
    let rows = f64::from(rect.max[1] - rect.min[1]);
    let continent_height = spans.values().map(|&(a, b)| f64::from(b - a + 1) / rows).fold(f64::INFINITY, f64::min);
    // Mountains in a row: from every mountain, the run along each axis counted by stepping both
    // ways (at most once round a wrapping map).
    let mountain = |h: Hex| t.tile_kind(h) == Some(TileKind::Mountain);
    let step = |h: Hex, d: Hex| t.wrap_tile(h + d).filter(|&x| t.contains(x));
    let mut straight_ridge = 0;
    for &h in tiles.iter().filter(|&&h| mountain(h)) {
        for axis in [Hex::new(1, 0), Hex::new(0, 1), Hex::new(1, -1)] {
            let mut run = 1;
            for d in [axis, -axis] {
                let mut at = h;
                while let Some(next) = step(at, d).filter(|&x| mountain(x) && x != h) {
                    run += 1;
                    at = next;
                }
                if step(at, d) == Some(h) {
                    break; // all round: counted once
                }
            }
            straight_ridge = straight_ridge.max(run);
        }
    }
    let blobs = tiles
        .iter()
        .filter(|&&h| mountain(h))
        .filter(|&&h| t.neighbors(h).unwrap().into_iter().flatten().filter(|&nb| mountain(nb)).count() >= 5)
        .count();
    Recount {
        continent_height: if continent_height.is_finite() { continent_height } else { 0.0 },
        straight_ridge,
        blob_share: share(blobs, mountains),
        sea_share: share(n - land, n),
        mountain_share: share(mountains, land),
        landmasses: sizes.len(),
        continents: sizes.iter().filter(|&&s| continent(s)).count(),
        largest_share: share(sizes.first().copied().unwrap_or(0), land),
        // The second of the continents (islands are not continents): none with fewer than two.
        second_share: share(sizes.iter().copied().filter(|&s| continent(s)).nth(1).unwrap_or(0), land),
        strait,
        largest_sea_share: share(biggest.map_or(0, |r| sea_sizes[&r]), n - land),
        largest_sea_edge_tiles: (0..n)
            .filter(|&i| biggest.is_some() && seas[i] == biggest && on_edge(tiles[i]))
            .count(),
    }
}

/// Every number of the report equals the recount; a missed target is named in the report.
fn check_report(t: &Terrain) -> Result<MapTypeReport, TestCaseError> {
    let report = t.map_type().expect("a map type's report").clone();
    let r = recount(t);
    prop_assert!((1..=MAX_TRIES).contains(&report.tries));
    for check in &report.checks {
        let expected = match check.target {
            MapTypeTarget::SeaShare => r.sea_share,
            MapTypeTarget::MountainShare => r.mountain_share,
            MapTypeTarget::Continents => r.continents as f64,
            MapTypeTarget::SecondContinentShare => r.second_share,
            MapTypeTarget::LargestLandmassShare => r.largest_share,
            MapTypeTarget::Landmasses => r.landmasses as f64,
            MapTypeTarget::NarrowestStrait => r.strait,
            MapTypeTarget::LargestSeaShare => r.largest_sea_share,
            MapTypeTarget::LargestSeaEdgeTiles => r.largest_sea_edge_tiles as f64,
            MapTypeTarget::ContinentHeight => r.continent_height,
            MapTypeTarget::StraightRidge => r.straight_ridge as f64,
            MapTypeTarget::MountainBlobShare => r.blob_share,
        };
        prop_assert_eq!(check.measured, expected, "{:?} of {}", check.target, report);
        let line = check.to_string();
        prop_assert!(line.starts_with(check.target.name()));
        prop_assert_eq!(check.met(), !line.contains("MISSED"), "{}", line);
    }
    let wanted: &[MapTypeTarget] = match report.kind {
        MapType::Pangaea => &[MapTypeTarget::LargestLandmassShare],
        MapType::Continents => &[
            MapTypeTarget::Continents,
            MapTypeTarget::SecondContinentShare,
            MapTypeTarget::NarrowestStrait,
            MapTypeTarget::ContinentHeight,
        ],
        MapType::SmallContinents => {
            &[MapTypeTarget::Continents, MapTypeTarget::LargestLandmassShare, MapTypeTarget::NarrowestStrait]
        }
        MapType::Archipelago => &[MapTypeTarget::Landmasses, MapTypeTarget::LargestLandmassShare],
        MapType::Fractal => &[],
        MapType::InlandSea => {
            &[MapTypeTarget::LargestSeaShare, MapTypeTarget::LargestSeaEdgeTiles, MapTypeTarget::LargestLandmassShare]
        }
    };
    let ranges: &[MapTypeTarget] = if t.config().map_type.unwrap().ranges {
        &[MapTypeTarget::StraightRidge, MapTypeTarget::MountainBlobShare]
    } else {
        &[]
    };
    for target in [MapTypeTarget::SeaShare, MapTypeTarget::MountainShare].iter().chain(wanted).chain(ranges) {
        prop_assert!(report.check(*target).is_some(), "{:?} missing from {}", target, report);
    }
    prop_assert_eq!(report.checks.len(), 2 + wanted.len() + ranges.len());
    Ok(report)
}

fn kind() -> impl Strategy<Value = MapType> {
    prop::sample::select(MapType::ALL.to_vec())
}

fn water() -> impl Strategy<Value = WaterLevel> {
    prop::sample::select(WaterLevel::ALL.to_vec())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// Over random types, water levels, sizes, wrap, noise and mountain shares: every number of
    /// the report is the recount's, every missed target is named, the tries stay bounded.
    #[test]
    fn reports_equal_a_recount(
        kind in kind(),
        water in water(),
        (x, z) in (8u32..60, 8u32..40),
        wrap in any::<bool>(),
        seed in any::<u32>(),
        (octaves, persistence, scale) in (3u32..10, 0.25f64..0.6, 8.0f64..90.0),
        mountains in 0.0f32..0.3,
        ranges in any::<bool>(),
    ) {
        let mut c = config(kind, water, (x + x % 2, z), wrap, seed, scale);
        c.noise.octaves = octaves;
        c.noise.persistence = persistence;
        c.map_type = Some(MapTypeConfig { kind, water, mountains, ranges });
        check_report(&Terrain::new(c).unwrap())?;
    }
}

/// The case that was found: on a map too small for two continents (8x8, Continents) the report
/// named the second landmass' share the second continent's, and met the target. Over the first
/// seeds, each with fewer than two continents and an island beside the largest landmass reports
/// no second continent and misses the target.
#[test]
fn the_second_continent_is_a_continent() {
    let mut cases = 0;
    for seed in 0..64 {
        let c = MapConfig::from_ron(&format!(
            "(seed: {seed}, size: Bounded(x: 8, z: 8), chunk_size: (8, 16), \
             map_type: Some((kind: Continents, water: Normal, mountains: 0.08, ranges: false)))"
        ))
        .unwrap();
        let t = Terrain::new(c).unwrap();
        let (report, r) = (t.map_type().unwrap(), recount(&t));
        if r.continents < 2 && r.landmasses >= 2 {
            cases += 1;
            let second = report.check(MapTypeTarget::SecondContinentShare).unwrap();
            assert_eq!(second.measured, 0.0, "seed {seed}: {report}");
            assert!(!second.met(), "seed {seed}: {report}");
        }
    }
    assert!(cases > 0, "no seed gave an island beside fewer than two continents");
}

/// The promise: every type meets its targets on every Civilization VI size, wrapping or not, at
/// every water level, with the presets' noise. Over these 216 maps (seeds fixed), at most one in
/// twenty may miss (the smallest sizes, where a few continents or twenty islands barely fit);
/// `hexterrain survey` measures the rate over hundreds of seeds.
#[test]
fn every_type_meets_its_targets_on_every_civ_size() {
    let mut missed = Vec::new();
    let mut maps = 0;
    for (k, kind) in MapType::ALL.into_iter().enumerate() {
        for &(name, x, z) in &CIV6_SIZES {
            for wrap in [false, true] {
                for water in WaterLevel::ALL {
                    let seed = 7919 * maps + k as u32;
                    let mut c = config(kind, water, (x, z), wrap, seed, 60.0);
                    c.map_type.as_mut().unwrap().ranges = maps % 2 == 1;
                    maps += 1;
                    let t = Terrain::new(c).unwrap();
                    let report = t.map_type().unwrap();
                    if !report.met() {
                        missed.push(format!("{name} wrap {wrap} {water:?} seed {seed}: {report}"));
                    }
                }
            }
        }
    }
    assert_eq!(maps, 216);
    println!("{} of {maps} maps missed a target:\n{}", missed.len(), missed.join("\n"));
    assert!(missed.len() * 20 <= maps as usize, "{} of {maps} maps missed:\n{}", missed.len(), missed.join("\n"));
    // Every type keeps its promise on the Standard size and larger.
    assert!(!missed.iter().any(|m| ["Standard", "Large", "Huge"].iter().any(|s| m.starts_with(s))), "{missed:?}");
}

/// Mountain ranges: the same share of mountains in chains along the plates' meeting lines, so a
/// mountain has fewer mountain neighbors, more mountains are links of a chain (one or two
/// mountain neighbors, counted here from the tiles) and fewer lie in blobs, on every type, on
/// average over seeds.
#[test]
fn ranges_run_in_chains() {
    for kind in MapType::ALL {
        let (mut neighbors, mut chained, mut blobs) = ([0.0; 2], [0.0; 2], [0.0; 2]);
        for seed in 0..12 {
            for (r, ranges) in [false, true].into_iter().enumerate() {
                let mut c = config(kind, WaterLevel::Normal, (84, 54), true, seed, 60.0);
                c.map_type.as_mut().unwrap().ranges = ranges;
                let t = Terrain::new(c).unwrap();
                let stats = hex_terrain::MapStats::measure(&t).unwrap();
                neighbors[r] += stats.mountain_neighbors() / 12.0;
                let mountain = |h: Hex| t.tile_kind(h) == Some(TileKind::Mountain);
                let around: Vec<usize> = t
                    .tiles()
                    .filter(|&h| mountain(h))
                    .map(|h| t.neighbors(h).unwrap().into_iter().flatten().filter(|&nb| mountain(nb)).count())
                    .collect();
                let share = |f: &dyn Fn(usize) -> bool| {
                    around.iter().filter(|&&a| f(a)).count() as f64 / around.len().max(1) as f64 / 12.0
                };
                chained[r] += share(&|a| (1..=2).contains(&a));
                blobs[r] += share(&|a| a >= 5);
            }
        }
        println!(
            "{}: mountain neighbors {:.2} -> {:.2}, in chains {:.2} -> {:.2}, in blobs {:.3} -> {:.3}",
            kind.name(),
            neighbors[0],
            neighbors[1],
            chained[0],
            chained[1],
            blobs[0],
            blobs[1]
        );
        assert!(neighbors[1] < neighbors[0], "{kind:?}: {neighbors:?}");
        assert!(blobs[1] <= blobs[0], "{kind:?}: {blobs:?}");
        // An archipelago's islands are too small for long ranges: fewer neighbors is all.
        if kind != MapType::Archipelago {
            assert!(neighbors[1] < neighbors[0] - 0.2, "{kind:?}: {neighbors:?}");
            assert!(chained[1] > chained[0], "{kind:?}: {chained:?}");
        }
    }
}

/// A map type is compiled once from the config: the same report, tiles and statistics on one
/// thread as on many, and from a config read back from its RON.
#[test]
fn the_same_map_on_any_thread_and_after_a_round_trip() {
    for kind in MapType::ALL {
        let c = config(kind, WaterLevel::Normal, (44, 26), true, 11, 60.0);
        let kinds = |t: &Terrain| t.tiles().map(|h| t.tile_kind(h).unwrap()).collect::<Vec<_>>();
        let here = Terrain::new(c.clone()).unwrap();
        let single = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let there = single.install(|| Terrain::new(c.clone()).unwrap());
        let read = Terrain::new(MapConfig::from_ron(&c.to_ron()).unwrap()).unwrap();
        let stats = hex_terrain::MapStats::measure(&here);
        for other in [&there, &read] {
            assert_eq!(here.map_type(), other.map_type());
            assert_eq!(kinds(&here), kinds(other));
        }
        assert_eq!(stats, single.install(|| hex_terrain::MapStats::measure(&there)));
    }
}

#[test]
fn refused_configs_name_their_field() {
    // The default size is 30x30.
    let typed = |ron: &str| MapConfig::from_ron(&format!("(map_type: Some((kind: Pangaea)), {ron})"));
    let field = |ron: &str| match typed(ron) {
        Err(LoadError::Invalid(error)) => error.field,
        other => panic!("{ron}: {other:?}"),
    };
    assert_eq!(field("size: Unbounded"), "map_type");
    assert_eq!(field("shape: Island(a: 2.0, b: 5.0)"), "shape");
    assert_eq!(field("source: Image(path: \"x.png\", sea_level: 0.3)"), "source");
    assert_eq!(field("size: Bounded(x: 7, z: 30)"), "size");
    assert!(Terrain::new(typed("size: Bounded(x: 8, z: 8)").unwrap()).is_ok());
    let mut mountains = typed("size: Bounded(x: 40, z: 30)").unwrap();
    mountains.map_type.as_mut().unwrap().mountains = 0.9;
    let error = Terrain::new(mountains).unwrap_err();
    assert_eq!((error.field.as_str(), error.value.as_str()), ("map_type.mountains", "0.9"));
    // An unknown type or field is a parse error naming line and column.
    let unknown = MapConfig::from_ron("(map_type: Some((kind: Pangea)))").unwrap_err().to_string();
    assert!(unknown.contains("Pangea") && unknown.contains("1:"), "{unknown}");
}

/// One map of each type pinned: the tiles' kinds hashed (FNV-1a) and the tries. A change is a
/// deliberate change to the generator: update the table and say why.
#[test]
fn one_map_of_each_type_is_pinned() {
    const GOLDEN: [(MapType, u64, u32); 6] = [
        (MapType::Pangaea, 0x0080_1230_3170_2785, 1),
        (MapType::Continents, 0xaa10_b194_7c10_8d1c, 1),
        (MapType::SmallContinents, 0x6eb7_7d37_914f_fd94, 6),
        (MapType::Archipelago, 0xaf52_8a8c_0d6e_a1f9, 1),
        (MapType::Fractal, 0x347c_2f05_1a84_91c1, 1),
        (MapType::InlandSea, 0x9e68_6e00_806d_600a, 1),
    ];
    let mut rows = Vec::new();
    for (kind, _, _) in GOLDEN {
        let t = Terrain::new(config(kind, WaterLevel::Normal, (84, 54), true, 2024, 60.0)).unwrap();
        let mut h: u64 = 0xcbf2_9ce4_8422_2325;
        for tile in t.tiles() {
            h ^= t.tile_kind(tile).unwrap() as u64;
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
        rows.push((kind, h, t.map_type().unwrap().tries));
    }
    assert_eq!(rows, GOLDEN, "if intended, GOLDEN becomes {rows:#x?}");
}

/// The type presets as a player gets them (winds, rivers on edges rising in the hills): over the
/// presets' own seed and the next 199, every survey target (`survey_targets`: ranges, poles,
/// lakes, rivers, shapes, deserts) is met, each figure read from `MapStats` (whose numbers
/// `tests/stats.rs` recomputes), as `hexterrain survey TYPE --seeds 200` prints them.
#[test]
fn the_type_presets_meet_their_survey_targets() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/maps/types");
    let mut missed = Vec::new();
    for name in ["pangaea", "continents", "small_continents", "archipelago", "fractal", "inland_sea"] {
        let text = std::fs::read_to_string(dir.join(format!("{name}.map.ron"))).unwrap();
        let preset = MapConfig::from_ron(&text).unwrap();
        let kind = preset.map_type.unwrap().kind;
        let size = preset.size.bounds().unwrap();
        let targets = hex_terrain::survey_targets(
            kind,
            preset.rivers.model == hex_terrain::RiverModel::Edges,
            preset.climate.winds.is_some(),
        );
        let stats: Vec<(u32, hex_terrain::MapStats)> = (0..200)
            .map(|k| {
                let seed = preset.seed + k;
                let t = Terrain::new(MapConfig { seed, ..preset.clone() }).unwrap();
                (seed, hex_terrain::MapStats::measure(&t).unwrap())
            })
            .collect();
        for target in &targets {
            let values: Vec<(u32, f64)> = stats.iter().map(|(seed, s)| (*seed, target.figure.of(s, size))).collect();
            let verdict = target.judge(&values);
            println!(
                "{name}: {} median {:.3} tail {:.3} met {}",
                target.figure.name(),
                verdict.median,
                verdict.tail,
                verdict.met
            );
            if !verdict.met {
                missed.push(format!("{name}: {:?} {verdict:?}", target.figure));
            }
        }
    }
    assert!(missed.is_empty(), "{missed:#?}");
}
