//! `MapStats` over random bounded maps (wrapping or not, with and without climate, rivers,
//! shapes and a setup), against the same numbers computed here another way from the public tile
//! queries: landmasses and ranges by union-find, the coast counted from the sea's side, the
//! narrowest strait by comparing every pair of tiles, rivers by walking down from each source.

use std::collections::HashMap;

use hex_terrain::hexx::Hex;
use hex_terrain::{
    Biome, CONTINENT_MIN_SHARE, CONTINENT_MIN_TILES, LandmassKind, MapConfig, MapSize, MapStats, MapType,
    MapTypeConfig, NoiseConfig, RiverModel, SetupConfig, Shape, Terrain, TileKind, WaterLevel,
};
use proptest::prelude::*;

mod common;
#[path = "common/sets.rs"]
mod sets;
use sets::Sets;
#[path = "common/biome.rs"]
mod biome;

prop_compose! {
    fn config()(
        seed in any::<u32>(),
        (x, z) in (6u32..40, 6u32..30),
        scale in 4.0f64..30.0,
        sea in 0.2f32..0.6,
        shape in 0u8..4,
        climate in any::<bool>(),
        rivers in any::<bool>(),
        on_edges in any::<bool>(),
        setup in any::<bool>(),
        wrap in any::<bool>(),
        map_type in prop::option::weighted(0.3, (0usize..6, 0usize..3, any::<bool>())),
        // Bearings off the bisectors of the hex directions (no tie for the upwind neighbor).
        winds in prop::option::of(prop::collection::vec((0u32..12, 3u32..28), 1..4)),
        relief_sources in prop::option::of(2.0f32..20.0),
    ) -> MapConfig {
        let mut c = MapConfig {
            seed,
            size: MapSize::Bounded { x, z },
            noise: NoiseConfig { scale, ..NoiseConfig::default() },
            shape: [Shape::None, Shape::None, Shape::Island { a: 3.0, b: 5.0 }, Shape::Mediterranean { a: 3.0, b: 5.0 }][shape as usize].clone(),
            chunk_size: (8, 8),
            ..MapConfig::default()
        };
        c.terrain.sea_threshold = sea;
        c.terrain.mountain_threshold = (sea + 0.25).min(0.9);
        c.climate.enabled = climate;
        c.rivers.enabled = rivers;
        if on_edges {
            c.rivers.model = RiverModel::Edges;
            if let Some(tiles_per_edge) = relief_sources {
                c.rivers.sources = hex_terrain::RiverSources::Relief { tiles_per_edge };
            }
        }
        if let Some(bands) = winds {
            let bearings = bands.iter().map(|&(k, off)| (k * 30 + off) as f32).collect();
            c.climate.winds = Some(hex_terrain::WindConfig { pattern: hex_terrain::WindPattern::Bands(bearings), ..Default::default() });
        }
        if setup {
            c.setup = Some(SetupConfig { players: 2, min_distance: 2, ..SetupConfig::default() });
        }
        if let Some((kind, water, ranges)) = map_type {
            c.size = MapSize::Bounded { x: x.max(8), z: z.max(8) };
            c.shape = Shape::None;
            c.map_type = Some(MapTypeConfig { kind: MapType::ALL[kind], water: WaterLevel::ALL[water], ranges, ..MapTypeConfig::default() });
        }
        common::wrapping(c, wrap)
    }
}

/// The sizes of the groups of `member` tiles joined across neighbors (a tile's neighbors from
/// hexx, brought onto the map with `wrap_tile`), by each tile's group root.
fn groups(t: &Terrain, tiles: &[Hex], member: impl Fn(Hex) -> bool) -> (Sets, HashMap<usize, u32>) {
    let index: HashMap<Hex, usize> = tiles.iter().enumerate().map(|(i, &h)| (h, i)).collect();
    let mut sets = Sets::new(tiles.len());
    for (i, &tile) in tiles.iter().enumerate() {
        if !member(tile) {
            continue;
        }
        for n in tile.all_neighbors() {
            if let Some(n) = t.wrap_tile(n).filter(|&n| member(n)) {
                sets.join(i, index[&n]);
            }
        }
    }
    let mut sizes = HashMap::new();
    for (i, &tile) in tiles.iter().enumerate() {
        if member(tile) {
            *sizes.entry(sets.find(i)).or_insert(0) += 1;
        }
    }
    (sets, sizes)
}

fn check(t: &Terrain) -> Result<(), TestCaseError> {
    let stats = MapStats::measure(t).expect("a bounded map");
    let tiles: Vec<Hex> = t.tiles().collect();
    let info = |h: Hex| t.tile_info(h).unwrap();
    let water = |h: Hex| info(h).kind == TileKind::Sea || info(h).lake.is_some();
    let land = |h: Hex| !water(h);
    let count = |f: &dyn Fn(Hex) -> bool| tiles.iter().filter(|&&h| f(h)).count() as u32;

    prop_assert_eq!(stats.tiles, tiles.len() as u32);
    prop_assert_eq!(stats.sea_tiles, count(&|h| info(h).kind == TileKind::Sea));
    prop_assert_eq!(stats.lake_tiles, count(&|h| info(h).kind != TileKind::Sea && info(h).lake.is_some()));
    prop_assert_eq!(stats.land_tiles, count(&land));
    prop_assert_eq!(stats.sea_tiles + stats.lake_tiles + stats.land_tiles, stats.tiles);
    let mountain = |h: Hex| land(h) && info(h).kind == TileKind::Mountain;
    prop_assert_eq!(stats.mountain_tiles, count(&mountain));

    // Landmasses: the sizes, largest first, and each one's kind by the rule.
    let (mut sets, sizes) = groups(t, &tiles, land);
    let mut expected: Vec<u32> = sizes.values().copied().collect();
    expected.sort_unstable_by(|a, b| b.cmp(a));
    prop_assert_eq!(stats.landmasses.iter().map(|m| m.tiles).collect::<Vec<_>>(), expected);
    for mass in &stats.landmasses {
        let continent = f64::from(mass.tiles) / f64::from(stats.land_tiles) >= CONTINENT_MIN_SHARE
            && mass.tiles >= CONTINENT_MIN_TILES;
        prop_assert_eq!(mass.kind == LandmassKind::Continent, continent);
        // Its first tile is the landmass' first in row order.
        let root = sets.find(tiles.iter().position(|&h| h == mass.first).unwrap());
        let first = tiles.iter().enumerate().find(|&(i, &h)| land(h) && sets.find(i) == root).map(|(_, &h)| h);
        prop_assert_eq!(Some(mass.first), first);
    }

    // The coast, counted from the sea's side.
    let coast: u32 = tiles
        .iter()
        .filter(|&&h| info(h).kind == TileKind::Sea)
        .map(|&h| h.all_neighbors().iter().filter_map(|&n| t.wrap_tile(n)).filter(|&n| land(n)).count() as u32)
        .sum();
    prop_assert_eq!(stats.coast_edges, coast);
    prop_assert_eq!(stats.landmasses.iter().map(|m| m.coast_edges).sum::<u32>(), coast);
    prop_assert_eq!(stats.landmasses.iter().map(|m| m.mountains).sum::<u32>(), stats.mountain_tiles);

    // The narrowest strait: every pair of tiles of two different continents.
    let continent_of = |sets: &mut Sets, i: usize| {
        let root = sets.find(i);
        (land(tiles[i])
            && sizes[&root] >= CONTINENT_MIN_TILES
            && f64::from(sizes[&root]) / f64::from(stats.land_tiles) >= CONTINENT_MIN_SHARE)
            .then_some(root)
    };
    let continental: Vec<(usize, usize)> =
        (0..tiles.len()).filter_map(|i| continent_of(&mut sets, i).map(|root| (i, root))).collect();
    let mut narrowest: Option<u32> = None;
    for (k, &(a, ra)) in continental.iter().enumerate() {
        for &(b, rb) in &continental[k + 1..] {
            if ra != rb {
                let d = t.distance(tiles[a], tiles[b]).unwrap() - 1;
                narrowest = Some(narrowest.map_or(d, |n| n.min(d)));
            }
        }
    }
    prop_assert_eq!(stats.narrowest_strait, narrowest);
    prop_assert_eq!(stats.continents().count() >= 2, narrowest.is_some());

    // Mountain ranges: groups of three or more.
    let (mut range_sets, ranges) = groups(t, &tiles, mountain);
    prop_assert_eq!(stats.range_tiles, ranges.values().filter(|&&s| s >= 3).sum::<u32>());
    // Their shape: mountain neighbors counted from each mountain, and the farthest two tiles of
    // one range (every pair of mountains compared).
    let neighbors: u32 = tiles
        .iter()
        .filter(|&&h| mountain(h))
        .map(|&h| h.all_neighbors().iter().filter_map(|&n| t.wrap_tile(n)).filter(|&n| mountain(n)).count() as u32)
        .sum();
    prop_assert_eq!(stats.mountain_adjacencies, neighbors);
    let peaks: Vec<(usize, usize)> =
        (0..tiles.len()).filter(|&i| mountain(tiles[i])).map(|i| (i, range_sets.find(i))).collect();
    let mut longest = 0;
    for &(a, ra) in &peaks {
        for &(b, rb) in &peaks {
            if ra == rb && ranges[&ra] >= 3 {
                longest = longest.max(t.distance(tiles[a], tiles[b]).unwrap() + 1);
            }
        }
    }
    prop_assert_eq!(stats.longest_range, longest);

    // Biomes.
    for biome in Biome::ALL {
        let n = count(&|h| biome::of(t, &info(h)) == biome);
        prop_assert_eq!(stats.biomes.iter().find(|b| b.0 == biome).map_or(0, |b| b.1), n);
    }

    // Shapes: straight runs of mountains walked along all six directions from every mountain;
    // mountains in blobs; land in the polar rows; each landmass' rows and columns.
    let mut ridge = 0;
    for &h in tiles.iter().filter(|&&h| mountain(h)) {
        for d in Hex::ZERO.all_neighbors() {
            let mut walked = std::collections::HashSet::from([h]);
            let mut at = h;
            while let Some(next) = t.wrap_tile(at + d).filter(|&n| t.contains(n) && mountain(n) && !walked.contains(&n))
            {
                walked.insert(next);
                at = next;
            }
            ridge = ridge.max(walked.len() as u32);
        }
    }
    prop_assert_eq!(stats.straight_ridge, ridge);
    let mountain_around =
        |h: Hex| h.all_neighbors().iter().filter_map(|&n| t.wrap_tile(n)).filter(|&n| mountain(n)).count();
    prop_assert_eq!(stats.blob_mountains, count(&|h| mountain(h) && mountain_around(h) >= 5));
    let rect = t.bounds().unwrap();
    let (width, height) = (rect.max[0] - rect.min[0], rect.max[1] - rect.min[1]);
    let band = (height + 9) / 10;
    let row = |h: Hex| t.offset_of(h)[1] - rect.min[1];
    prop_assert_eq!(stats.polar_land_tiles, count(&|h| land(h) && (row(h) < band || row(h) >= height - band)));
    let mut centers = Vec::new();
    for mass in &stats.landmasses {
        let root = sets.find(tiles.iter().position(|&h| h == mass.first).unwrap());
        let members: Vec<Hex> =
            (0..tiles.len()).filter(|&i| land(tiles[i]) && sets.find(i) == root).map(|i| tiles[i]).collect();
        let rows: std::collections::BTreeSet<i32> = members.iter().map(|&h| row(h)).collect();
        prop_assert_eq!(mass.rows, (rows.last().unwrap() - rows.first().unwrap() + 1) as u32);
        let columns: std::collections::BTreeSet<i32> =
            members.iter().map(|&h| t.offset_of(h)[0] - rect.min[0]).collect();
        // The fewest columns of an arc that holds them all: every start and length tried.
        let span = if t.wrap().is_some() {
            (1..=width)
                .find(|&len| (0..width).any(|start| columns.iter().all(|&c| (c - start).rem_euclid(width) < len)))
                .unwrap()
        } else {
            columns.last().unwrap() - columns.first().unwrap() + 1
        };
        prop_assert_eq!(mass.columns, span as u32);
        // Its center: the mean row, and the mean column (round a wrapping map: the direction of
        // the sum of its columns' bearings).
        let n = members.len() as f64;
        let mean_row = members.iter().map(|&h| f64::from(row(h))).sum::<f64>() / n;
        let cols = members.iter().map(|&h| f64::from(t.offset_of(h)[0] - rect.min[0]));
        let mean_col = if t.wrap().is_some() {
            let turn = std::f64::consts::TAU / f64::from(width);
            let (c, s) = cols.fold((0.0, 0.0), |(c, s), col| (c + (col * turn).cos(), s + (col * turn).sin()));
            if c.hypot(s) < 1e-6 * n { 0.0 } else { (s.atan2(c) / turn).rem_euclid(f64::from(width)) }
        } else {
            cols.sum::<f64>() / n
        };
        prop_assert!((mass.center[1] - mean_row).abs() < 1e-6, "{:?} row {mean_row}", mass.center);
        let apart = (mass.center[0] - mean_col).abs();
        let apart = if t.wrap().is_some() { apart.min(f64::from(width) - apart) } else { apart };
        prop_assert!(apart < 1e-6, "{:?} column {mean_col}", mass.center);
        prop_assert!((0.0..f64::from(width)).contains(&mass.center[0]), "{:?}", mass.center);
        centers.push((mass.kind, [mean_col, mean_row]));
        // Its tiles on a river: carrying one, or with a river on an edge.
        let on_river = |h: Hex| t.river(h).is_some() || !t.river_edges(h).is_empty();
        prop_assert_eq!(mass.river_tiles, members.iter().filter(|&&h| on_river(h)).count() as u32);
    }
    // Continents in line: every pair's centers within 1.5 tiles of the same row or column
    // (round a wrapping map the nearer way). The centers above agree with the map's to 1e-6, so a
    // pair that far from 1.5 apart (exactly 1.5 columns, say, which the mean round a wrapping map
    // gives as 1.4999999999999982) may count either way: the share lies between the two counts.
    let continents: Vec<[f64; 2]> =
        centers.iter().filter(|(k, _)| *k == LandmassKind::Continent).map(|&(_, c)| c).collect();
    let (mut pairs, mut surely, mut maybe) = (0, 0, 0);
    for (k, a) in continents.iter().enumerate() {
        for b in &continents[k + 1..] {
            let dx = (a[0] - b[0]).abs();
            let dx = if t.wrap().is_some() { dx.min(f64::from(width) - dx) } else { dx };
            let nearer = dx.min((a[1] - b[1]).abs());
            pairs += 1;
            surely += usize::from(nearer < 1.5 - 1e-6);
            maybe += usize::from(nearer < 1.5 + 1e-6);
        }
    }
    let share = |n: usize| if pairs == 0 { 0.0 } else { n as f64 / f64::from(pairs) };
    let (least, most) = (share(surely), share(maybe));
    let in_line = stats.continents_in_line();
    prop_assert!(least - 1e-9 <= in_line && in_line <= most + 1e-9, "{in_line} not in {least}..={most}");
    prop_assert_eq!(
        stats.landmasses_without_river(20),
        stats.landmasses.iter().filter(|m| m.tiles >= 20 && m.river_tiles == 0).count()
    );
    prop_assert_eq!(stats.rain_shadow, rain_shadow(t));

    // Rivers on edges: walked down from every edge.
    if t.config().rivers.model == RiverModel::Edges {
        prop_assert_eq!(stats.rivers, edge_rivers(t));
        prop_assert!(t.rivers().is_empty());
    }
    // Rivers through tile centers: walked down from every source.
    let rivers = t.rivers();
    let is_river = |h: Hex| rivers.iter().any(|r| r.hex == h);
    let mut longest = 0;
    let mut lengths = Vec::new();
    for source in rivers.iter().filter(|r| r.upstream.is_empty()) {
        let mut length = 1;
        let mut at = source.clone();
        while let Some(next) = at.downstream.filter(|&d| is_river(d)) {
            length += 1;
            at = t.river(next).unwrap();
        }
        longest = longest.max(length);
        lengths.push(length);
    }
    if t.config().rivers.model == RiverModel::Edges {
        prop_assert_eq!(stats.lakes, t.hydrology().map_or(0, |h| h.lake_count() as u32));
        return Ok(());
    }
    prop_assert_eq!(stats.rivers.edges, 0);
    prop_assert_eq!(stats.rivers.tiles, rivers.len() as u32);
    prop_assert_eq!(stats.rivers.longest, longest);
    prop_assert_eq!(stats.rivers.sources, lengths.len() as u32);
    prop_assert_eq!(stats.rivers.median, median(lengths));
    let near = rivers.iter().filter(|r| r.upstream.is_empty() && near_relief(t, r.hex)).count() as u32;
    prop_assert_eq!(stats.rivers.sources_near_relief, near);
    prop_assert_eq!(stats.rivers.mouths_at_edge, rivers.iter().filter(|r| r.downstream.is_none()).count() as u32);
    prop_assert_eq!(
        stats.rivers.systems,
        rivers.iter().filter(|r| r.downstream.is_none_or(|d| !is_river(d))).count() as u32
    );
    prop_assert_eq!(stats.lakes, t.hydrology().map_or(0, |h| h.lake_count() as u32));

    // With a setup, each start's landmass.
    if let Some(setup) = t.setup() {
        let starts: Vec<u32> =
            setup.starts().iter().map(|s| sizes[&sets.find(tiles.iter().position(|h| h == s).unwrap())]).collect();
        prop_assert_eq!(&stats.start_landmass_tiles, &starts);
    }
    Ok(())
}

/// Whether a tile lies within 2 steps of relief (a mountain or a hill): the tile, its neighbors
/// and theirs.
fn near_relief(t: &Terrain, h: Hex) -> bool {
    let relief = |h: Hex| {
        let i = t.tile_info(h).unwrap();
        (i.kind == TileKind::Mountain && i.lake.is_none()) || biome::of(t, &i) == Biome::Hills
    };
    let around = |h: Hex| t.neighbors(h).unwrap().into_iter().flatten();
    relief(h) || around(h).any(|n| relief(n) || around(n).any(relief))
}

/// The lower median of some lengths; 0 without any.
fn median(mut v: Vec<u32>) -> u32 {
    v.sort_unstable();
    if v.is_empty() { 0 } else { v[(v.len() - 1) / 2] }
}

/// Rivers on edges, counted from `river_edges` alone: each edge once (named by the two tiles it
/// lies between), its corners by the tiles they join; a system ends at an edge whose downstream
/// corner no river edge leaves; a river's length is the edges walked down from it to there.
fn edge_rivers(t: &Terrain) -> hex_terrain::RiverStats {
    let on_map = |h: Hex| t.wrap_tile(h).unwrap_or(h);
    let corner = |v: hex_terrain::hexx::GridVertex| {
        let mut tiles = v.coordinates().map(on_map);
        tiles.sort_by_key(|h| (h.x, h.y));
        tiles
    };
    let mut seen = std::collections::HashSet::new();
    let mut down: HashMap<[Hex; 3], [Hex; 3]> = HashMap::new();
    // Each corner's tiles on the map, by its name.
    let mut corner_tiles: HashMap<[Hex; 3], Vec<Hex>> = HashMap::new();
    let mut tiles = 0;
    for tile in t.tiles() {
        let edges = t.river_edges(tile);
        tiles += u32::from(!edges.is_empty());
        for r in edges {
            let mut side = [on_map(r.edge.origin), on_map(r.edge.destination())];
            side.sort_by_key(|h| (h.x, h.y));
            if !seen.insert(side) {
                continue;
            }
            let [p, q] = r.edge.vertices();
            let upstream = if corner(r.downstream) == corner(q) { p } else { q };
            let on = upstream.coordinates().into_iter().filter_map(|c| t.wrap_tile(c).filter(|&c| t.contains(c)));
            corner_tiles.insert(corner(upstream), on.collect());
            assert!(down.insert(corner(upstream), corner(r.downstream)).is_none(), "one edge leaves a corner");
        }
    }
    let mut longest = 0;
    let mut lengths = Vec::new();
    let mut near = 0;
    let fed: std::collections::HashSet<&[Hex; 3]> = down.values().collect();
    for &start in down.keys() {
        let (mut at, mut length) = (start, 0);
        while let Some(&next) = down.get(&at) {
            length += 1;
            at = next;
            assert!(length <= down.len(), "a river loops");
        }
        longest = longest.max(length as u32);
        if !fed.contains(&start) {
            lengths.push(length as u32);
            near += u32::from(corner_tiles[&start].iter().any(|&h| near_relief(t, h)));
        }
    }
    // A mouth at the map's edge: a corner past the map touching no sea or lake.
    let wet = |h: Hex| t.tile_kind(h) == Some(TileKind::Sea) || t.lake(h).is_some();
    let at_edge = |c: &[Hex; 3]| {
        let on: Vec<Hex> = c.iter().filter_map(|&h| t.wrap_tile(h).filter(|&h| t.contains(h))).collect();
        on.len() < 3 && !on.iter().any(|&h| wet(h))
    };
    let mouths: std::collections::HashSet<&[Hex; 3]> = down.values().filter(|to| !down.contains_key(*to)).collect();
    hex_terrain::RiverStats {
        mouths_at_edge: mouths.iter().filter(|c| at_edge(c)).count() as u32,
        systems: down.values().filter(|to| !down.contains_key(*to)).count() as u32,
        tiles,
        edges: down.len() as u32,
        longest,
        sources: lengths.len() as u32,
        median: median(lengths),
        sources_near_relief: near,
    }
}

/// The rain shadow counted here: each row's wind from the config's bands (equal bands of
/// latitude from the equator to each pole, a band's bearing the direction the wind blows from,
/// clockwise from north, the southern half mirrored north to south; the rows' latitudes from
/// `climate.latitudes`), then from each land tile (not a mountain, not a lake) six steps, each to
/// the neighbor whose center lies most directly upwind, looking for a mountain.
fn rain_shadow(t: &Terrain) -> Option<hex_terrain::RainShadow> {
    let winds = t.config().climate.winds.as_ref().filter(|_| t.config().climate.enabled)?;
    let hex_terrain::WindPattern::Bands(bearings) = &winds.pattern else { return None };
    let rect = t.bounds()?;
    assert_eq!(t.config().climate.latitudes, (1.0, -1.0), "the rows' latitudes below are pole to pole");
    let rows = (rect.max[1] - rect.min[1]) as f32;
    let wind = |h: Hex| {
        // A row's latitude: its middle's distance from the map's middle, 1 at the outer edges
        // (in f32, as the climate computes it, so a row on a band's edge falls the same way).
        let v = ((t.offset_of(h)[1] - rect.min[1]) as f32 + 0.5) / rows - 0.5;
        let lat = f64::from(-2.0 * v);
        let band = ((f64::from(v.abs() * 2.0 * bearings.len() as f32)) as usize).min(bearings.len() - 1);
        let b = f64::from(bearings[band]).to_radians();
        // Blowing from the bearing: moving the other way (north is -z).
        let (x, z) = (-b.sin(), b.cos());
        if lat > 0.0 { (x, z) } else { (x, -z) }
    };
    let mountain = |h: Hex| t.tile_kind(h) == Some(TileKind::Mountain) && t.lake(h).is_none();
    let upwind = |h: Hex| {
        let lattice = t.lattice();
        let c = lattice.world(lattice.tile_center(h));
        let (wx, wz) = wind(h);
        let mut best: Option<(f64, Hex)> = None;
        for nb in h.all_neighbors() {
            let d = lattice.world(lattice.tile_center(nb));
            let (dx, dz) = (d[0] - c[0], d[1] - c[1]);
            let against = -(dx * wx + dz * wz) / dx.hypot(dz);
            if best.is_none_or(|(b, _)| against > b) {
                best = Some((against, nb));
            }
        }
        t.wrap_tile(best.unwrap().1).filter(|&h| t.contains(h))
    };
    let mut out = hex_terrain::RainShadow::default();
    for h in t.tiles() {
        let info = t.tile_info(h).unwrap();
        if info.kind != TileKind::Land || info.lake.is_some() {
            continue;
        }
        let mut at = h;
        let mut shadow = false;
        for _ in 0..hex_terrain::SHADOW_REACH {
            match upwind(at) {
                Some(n) if mountain(n) => {
                    shadow = true;
                    break;
                }
                Some(n) => at = n,
                None => break,
            }
        }
        out.land += 1;
        out.land_in_shadow += u32::from(shadow);
        if biome::of(t, &info) == Biome::Desert {
            out.deserts += 1;
            out.deserts_in_shadow += u32::from(shadow);
        }
    }
    Some(out)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn map_stats_equal_their_recomputation(config in config()) {
        // A setup that does not fit is another test's business.
        if let Ok(t) = Terrain::new(config) {
            check(&t)?;
        }
    }
}

#[test]
fn an_unbounded_world_has_no_stats() {
    let t = Terrain::new(MapConfig { size: MapSize::Unbounded, ..MapConfig::default() }).unwrap();
    assert!(MapStats::measure(&t).is_none());
}

#[test]
fn two_continents_across_a_strait() {
    // The World preset cut by a strait: two continents, and the strait is the fewest tiles
    // between them.
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/maps/strait.map.ron");
    let t = Terrain::new(MapConfig::from_ron(&std::fs::read_to_string(path).unwrap()).unwrap()).unwrap();
    let stats = MapStats::measure(&t).unwrap();
    assert!(stats.continents().count() >= 2, "{stats:?}");
    let strait = stats.narrowest_strait.unwrap();
    assert!((1..=4).contains(&strait), "the strait is three tiles wide: {strait}");
    check(&t).unwrap();
}

/// The maps whose rivers run on edges count them: the Jacksboro map and the World preset with
/// edge rivers have river systems, edges and tiles on a river, as walked from `river_edges`.
#[test]
fn edge_river_maps_count_their_rivers() {
    let maps = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../bevy_hex_terrain/assets/maps");
    let jacksboro = MapConfig::load(maps.join("jacksboro.map.ron")).unwrap();
    assert_eq!(jacksboro.rivers.model, RiverModel::Edges);
    let world = MapConfig::load(maps.join("world.map.ron")).unwrap();
    assert_eq!(world.rivers.model, RiverModel::Edges);
    for (name, mut config) in [("jacksboro", jacksboro), ("world", world)] {
        config.setup = None;
        let t = Terrain::new(config).unwrap();
        let stats = MapStats::measure(&t).unwrap();
        let r = stats.rivers;
        println!("{name}: {r:?}");
        assert!(r.systems > 0 && r.edges >= r.systems && r.tiles > r.edges / 2 && r.longest > 1, "{name}: {r:?}");
        assert_eq!(r, edge_rivers(&t), "{name}");
        assert!(stats.to_string().contains(&format!("{} systems on {} edges", r.systems, r.edges)), "{stats}");
    }
}
