//! Map types on a globe, measured here on the globe's tiles with a flood fill of this test's
//! own: the sea share is the type's within the tolerance, Pangaea's largest landmass holds most
//! of the land, Continents has two or three continents, an Archipelago many small islands, an
//! Inland Sea one sea holding most of the sea; over several seeds and sizes, the report agrees.

use hex_terrain::{
    CONTINENT_MIN_SHARE, CONTINENT_MIN_TILES, GlobeTerrain, GlobeTile, MapConfig, MapSize, MapType, MapTypeConfig,
    SEA_SHARE_TOLERANCE, TileKind,
};

fn globe(frequency: u32, seed: u32, kind: MapType) -> GlobeTerrain {
    let mut config = MapConfig { seed, size: MapSize::Globe { frequency }, ..Default::default() };
    config.noise.octaves = 8;
    config.noise.persistence = 0.5;
    config.noise.scale = 120.0;
    config.terrain.sea_threshold = 0.5;
    config.terrain.mountain_threshold = 0.62;
    config.terrain.interpolation_tolerance = 0.01;
    config.map_type = Some(MapTypeConfig { kind, ..Default::default() });
    GlobeTerrain::new(config).unwrap()
}

/// The sizes of the groups of tiles `member` keeps, joined through neighbors, largest first.
fn groups(g: &GlobeTerrain, member: impl Fn(GlobeTile) -> bool) -> Vec<usize> {
    let mut seen = vec![false; g.grid().tile_count() as usize];
    let mut sizes = Vec::new();
    for start in g.grid().tiles().filter(|&t| member(t)) {
        if std::mem::replace(&mut seen[start.0 as usize], true) {
            continue;
        }
        let (mut stack, mut size) = (vec![start], 0);
        while let Some(t) = stack.pop() {
            size += 1;
            for &m in &g.grid().neighbors(t).unwrap() {
                if member(m) && !std::mem::replace(&mut seen[m.0 as usize], true) {
                    stack.push(m);
                }
            }
        }
        sizes.push(size);
    }
    sizes.sort_unstable_by(|a, b| b.cmp(a));
    sizes
}

#[test]
fn every_map_type_meets_its_numbers_on_the_globe() {
    for kind in MapType::ALL {
        for (f, seed) in [(11, 1), (11, 2), (16, 3), (21, 4), (21, 5)] {
            let g = globe(f, seed, kind);
            let report = g.map_type_report().expect("a map type");
            assert!(report.met(), "{kind:?}, f = {f}, seed {seed}: {:?}", report.missed().collect::<Vec<_>>());
            let n = g.grid().tile_count() as usize;
            let sea = |t: GlobeTile| g.tile_kind(t) == Some(TileKind::Sea);
            let sea_tiles = g.grid().tiles().filter(|&t| sea(t)).count();
            let share = sea_tiles as f64 / n as f64;
            let level = MapTypeConfig { kind, ..Default::default() }.sea_share();
            assert!((share - level).abs() <= SEA_SHARE_TOLERANCE + 1e-9, "{kind:?}, f = {f}: sea {share}");
            let land = groups(&g, |t| !sea(t));
            let land_tiles = n - sea_tiles;
            let largest = land[0] as f64 / land_tiles as f64;
            let continent =
                |s: usize| s >= CONTINENT_MIN_TILES as usize && s as f64 / land_tiles as f64 >= CONTINENT_MIN_SHARE;
            let continents = land.iter().filter(|&&s| continent(s)).count();
            match kind {
                MapType::Pangaea => assert!(largest >= 0.8, "f = {f}, seed {seed}: {largest}"),
                MapType::Continents => assert!((2..=3).contains(&continents), "f = {f}, seed {seed}: {land:?}"),
                MapType::SmallContinents => assert!((4..=8).contains(&continents) && largest <= 0.4, "{land:?}"),
                MapType::Archipelago => assert!(land.len() >= 10 && largest <= 0.15, "f = {f}, seed {seed}: {land:?}"),
                MapType::Fractal => {}
                MapType::InlandSea => {
                    let seas = groups(&g, sea);
                    assert!(seas[0] as f64 >= 0.8 * sea_tiles as f64, "f = {f}, seed {seed}: {seas:?}");
                    assert!(largest >= 0.9, "f = {f}, seed {seed}: {largest}");
                }
            }
        }
    }
}

#[test]
fn a_globe_map_type_is_refused_by_field_where_it_cannot_be() {
    let mut small = MapConfig { size: MapSize::Globe { frequency: 3 }, ..Default::default() };
    small.map_type = Some(MapTypeConfig::default());
    assert_eq!(GlobeTerrain::new(small).unwrap_err().field, "size.Globe.frequency");
    let mut ranges = MapConfig { size: MapSize::Globe { frequency: 8 }, ..Default::default() };
    ranges.map_type = Some(MapTypeConfig { ranges: true, ..Default::default() });
    assert_eq!(GlobeTerrain::new(ranges).unwrap_err().field, "map_type.ranges");
}

#[test]
fn globe_stats_count_what_a_flood_fill_finds() {
    use hex_terrain::{GlobeStats, POLAR_LATITUDE};
    for (kind, seed) in [(MapType::Continents, 1), (MapType::Archipelago, 2), (MapType::Pangaea, 3)] {
        let g = globe(11, seed, kind);
        let stats = GlobeStats::measure(&g);
        let n = g.grid().tile_count() as usize;
        let sea = |t: GlobeTile| g.tile_kind(t) == Some(TileKind::Sea);
        let land = groups(&g, |t| !sea(t));
        assert_eq!(stats.landmasses.iter().map(|m| m.tiles as usize).collect::<Vec<_>>(), land, "{kind:?}");
        let land_tiles: usize = land.iter().sum();
        assert_eq!((stats.land_tiles as usize, stats.sea_tiles as usize), (land_tiles, n - land_tiles));
        let (mut coast, mut pairs, mut polar) = (0, 0, 0);
        for t in g.grid().tiles().filter(|&t| !sea(t)) {
            let around = g.grid().neighbors(t).unwrap();
            coast += around.as_slice().iter().filter(|&&m| sea(m)).count();
            if g.tile_kind(t) == Some(TileKind::Mountain) {
                pairs += around.as_slice().iter().filter(|&&m| g.tile_kind(m) == Some(TileKind::Mountain)).count();
            }
            polar += usize::from(g.grid().center(t).unwrap()[1].asin().to_degrees().abs() >= POLAR_LATITUDE);
        }
        assert_eq!(stats.coast_edges as usize, coast);
        assert_eq!(stats.mountain_adjacencies as usize, pairs);
        assert_eq!(stats.polar_land_tiles as usize, polar);
        // The strait: from every continent's tiles, the fewest steps to another continent's.
        let continent_of = |t: GlobeTile| {
            stats.continents().position(|c| {
                let mut seen = vec![false; n];
                let mut stack = vec![c.first];
                seen[c.first.0 as usize] = true;
                while let Some(u) = stack.pop() {
                    if u == t {
                        return true;
                    }
                    for &m in &g.grid().neighbors(u).unwrap() {
                        if !sea(m) && !std::mem::replace(&mut seen[m.0 as usize], true) {
                            stack.push(m);
                        }
                    }
                }
                false
            })
        };
        let labels: Vec<Option<usize>> =
            g.grid().tiles().map(|t| if sea(t) { None } else { continent_of(t) }).collect();
        let mut strait: Option<u32> = None;
        for t in g.grid().tiles().filter(|t| labels[t.0 as usize].is_some()) {
            let mine = labels[t.0 as usize];
            for (u, steps) in g.grid().within(t, u32::MAX) {
                if labels[u.0 as usize].is_some() && labels[u.0 as usize] != mine {
                    strait = Some(strait.map_or(steps - 1, |s| s.min(steps - 1)));
                }
            }
        }
        if stats.continents().count() >= 2 {
            assert_eq!(stats.narrowest_strait, strait, "{kind:?}");
        } else {
            assert_eq!(stats.narrowest_strait, None);
        }
        assert!(!stats.to_string().is_empty());
    }
}
