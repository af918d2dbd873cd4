//! The game setup on a globe over random globes and setups, checked by computations written
//! here over the globe's tile graph (pentagons included): every start keeps its rules and its
//! distance (a breadth-first search), the report's values are the values of the starts' rings
//! and reach recomputed with a textbook Dijkstra, its path costs are the globe's paths, the
//! spread is the spread of those values, resources and wonders lie only on allowed tiles with
//! their spacing, every start lies in its region's box of longitudes and latitudes, and the
//! setup is the same however the globe is built. Then bad input.

use std::cmp::Reverse;
use std::collections::{BTreeSet, BinaryHeap};

use hex_terrain::{
    Biome, GlobeTerrain, GlobeTile, MapConfig, MapSize, Place, SetupConfig, StartOn, TileEdit, TileKind, Yields,
};
use proptest::prelude::*;

/// A globe with a climate and a setup.
fn globe(frequency: u32, seed: u32, setup: SetupConfig) -> Result<GlobeTerrain, hex_terrain::ConfigError> {
    let mut config = MapConfig { seed, size: MapSize::Globe { frequency }, ..Default::default() };
    config.noise.scale = 60.0;
    config.terrain.sea_threshold = 0.45;
    config.terrain.mountain_threshold = 0.6;
    config.terrain.inner_rings = 1;
    config.climate.enabled = true;
    config.setup = Some(setup);
    GlobeTerrain::new(config)
}

fn biome(g: &GlobeTerrain, t: GlobeTile) -> Biome {
    g.ruleset().biome(g.tile_info(t).unwrap().terrain.terrain).expect("a biome")
}

fn neighbors(g: &GlobeTerrain, t: GlobeTile) -> Vec<GlobeTile> {
    g.grid().neighbors(t).unwrap().as_slice().to_vec()
}

/// Steps from `from` to every tile, by a breadth-first search.
fn steps(g: &GlobeTerrain, from: GlobeTile) -> Vec<u32> {
    let mut d = vec![u32::MAX; g.grid().tile_count() as usize];
    d[from.0 as usize] = 0;
    let mut queue = std::collections::VecDeque::from([from]);
    while let Some(t) = queue.pop_front() {
        for n in neighbors(g, t) {
            if d[n.0 as usize] == u32::MAX {
                d[n.0 as usize] = d[t.0 as usize] + 1;
                queue.push_back(n);
            }
        }
    }
    d
}

/// The tiles within `radius` steps of `tile`.
fn ring(g: &GlobeTerrain, tile: GlobeTile, radius: u32) -> Vec<GlobeTile> {
    let d = steps(g, tile);
    g.grid().tiles().filter(|t| d[t.0 as usize] <= radius).collect()
}

/// Whether a land tile has a sea neighbor (a globe has no lakes).
fn next_to_sea(g: &GlobeTerrain, t: GlobeTile) -> bool {
    neighbors(g, t).into_iter().any(|n| g.tile_kind(n) == Some(TileKind::Sea))
}

/// A tile's yields from its biome, kind and coast by the setup's table, with what the setup
/// put on it.
fn yields(g: &GlobeTerrain, cfg: &SetupConfig, t: GlobeTile) -> Yields {
    let kind = g.tile_kind(t).unwrap();
    let mut y = cfg.yields.biome(biome(g, t));
    if let Some(k) = cfg.yields.kinds.get(&kind) {
        y += *k;
    }
    if kind != TileKind::Sea && next_to_sea(g, t) {
        y += cfg.yields.coast;
    }
    let on = g.tile_setup(t).unwrap();
    if let Some(r) = on.resource {
        y += cfg.resources[r.rule as usize].yields;
    }
    if let Some(w) = on.wonder {
        y += cfg.wonders.list[w.rule as usize].yields;
    }
    y
}

fn allowed(g: &GlobeTerrain, t: GlobeTile, on: &[Place]) -> bool {
    on.iter().any(|p| match p {
        Place::Biome(b) => biome(g, t) == *b,
        Place::Kind(k) => g.tile_kind(t) == Some(*k),
        Place::Terrain(id) => g.ruleset().terrain(g.tile_info(t).unwrap().terrain.terrain).id == *id,
        Place::Feature(id) => g.tile_info(t).unwrap().terrain.feature.is_some_and(|f| g.ruleset().feature(f).id == *id),
    })
}

/// Path costs from `from`: entering a tile costs the movement model's cost of its biome.
fn dijkstra(g: &GlobeTerrain, from: GlobeTile) -> Vec<Option<u32>> {
    let mut dist = vec![None; g.grid().tile_count() as usize];
    dist[from.0 as usize] = Some(0);
    let mut heap = BinaryHeap::from([Reverse((0, from.0))]);
    while let Some(Reverse((d, t))) = heap.pop() {
        if dist[t as usize].is_some_and(|e| e < d) {
            continue;
        }
        for n in neighbors(g, GlobeTile(t)) {
            let Some(enter) = g.config().movement.enter(biome(g, n), false) else { continue };
            if dist[n.0 as usize].is_none_or(|e| d + enter < e) {
                dist[n.0 as usize] = Some(d + enter);
                heap.push(Reverse((d + enter, n.0)));
            }
        }
    }
    dist
}

fn spread(values: &[f32]) -> f32 {
    let max = values.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    let min = values.iter().copied().fold(f32::INFINITY, f32::min);
    if min <= 0.0 { if max <= 0.0 { 0.0 } else { f32::INFINITY } } else { max / min - 1.0 }
}

/// Whether a longitude (degrees) lies in `[west, east)`, the box running east from `west`.
fn in_longitudes(lon: f64, [west, east]: [f64; 2]) -> bool {
    // A longitude a hair west of `west` (-5e-15 against 0, say) wraps to a hair under 360: it is
    // on the box's western edge, not across the world.
    let east_of = (lon - west).rem_euclid(360.0);
    let east_of = if east_of >= 360.0 - 1e-9 { east_of - 360.0 } else { east_of };
    east_of >= -1e-9 && east_of <= east - west + 1e-9 || east - west >= 360.0 - 1e-9
}

/// Checks everything the setup promises on `g`.
fn check_setup(g: &GlobeTerrain) -> Result<(), TestCaseError> {
    let cfg = g.config().setup.clone().unwrap();
    let setup = g.setup().unwrap();
    let starts = setup.starts();
    let report = setup.report();
    prop_assert_eq!(starts.len(), cfg.players as usize);
    prop_assert_eq!(report.starts.len(), starts.len());
    let costs: Vec<Vec<Option<u32>>> = starts.iter().map(|&s| dijkstra(g, s)).collect();
    let mut values = Vec::new();
    for (p, &s) in starts.iter().enumerate() {
        // The start's rules.
        prop_assert_eq!(g.tile_setup(s).unwrap().start, Some(p as u32));
        prop_assert_eq!(g.tile_kind(s), Some(TileKind::Land), "start {} not on land", p);
        prop_assert!(!biome(g, s).is_water(), "start {p} on water");
        prop_assert!(g.move_cost(s).is_some(), "start {p} impassable");
        if cfg.start_on == StartOn::Coast {
            prop_assert!(next_to_sea(g, s), "start {p} not on the coast");
        }
        let d = steps(g, s);
        for &o in &starts[p + 1..] {
            prop_assert!(d[o.0 as usize] >= cfg.min_distance, "starts closer than {}", cfg.min_distance);
        }
        let on = g.tile_setup(s).unwrap();
        prop_assert!(on.resource.is_none() && on.wonder.is_none(), "something on start {p}");
        // Its region's box holds it.
        let row = &report.starts[p];
        prop_assert_eq!(row.tile, s);
        prop_assert_eq!(row.region, on.region);
        let region = &setup.regions()[on.region as usize];
        let info = g.tile_info(s).unwrap();
        prop_assert!(
            in_longitudes(info.longitude, region.longitudes),
            "start {p} at longitude {} outside {:?}",
            info.longitude,
            region.longitudes
        );
        prop_assert!(
            (region.latitudes[0] - 1e-9..=region.latitudes[1] + 1e-9).contains(&info.latitude),
            "start {p} at latitude {} outside {:?}",
            info.latitude,
            region.latitudes
        );
        prop_assert_eq!(row.coords, [info.longitude.round() as i32, info.latitude.round() as i32]);
        // Its value, reach and land, recomputed.
        let tiles = ring(g, s, cfg.rings);
        let mut sum = Yields::default();
        for &t in &tiles {
            sum += yields(g, &cfg, t);
        }
        for (got, want) in row.yields.values().iter().zip(sum.values()) {
            prop_assert!((got - want).abs() < 1e-3, "player {p} yields {:?}, recomputed {:?}", row.yields, sum);
        }
        let reach = (0..costs[p].len())
            .filter(|&t| {
                costs[p][t].is_some_and(|c| costs.iter().enumerate().all(|(q, o)| q == p || o[t].is_none_or(|e| c < e)))
            })
            .count() as u32;
        prop_assert_eq!(row.reach, reach, "player {} reach", p);
        prop_assert_eq!(row.land_area, costs[p].iter().flatten().count() as u32, "player {} land mass", p);
        let value = cfg.value.of(sum) + cfg.value.reach * reach as f32;
        prop_assert!((row.value - value).abs() <= 1e-3 * value.abs().max(1.0), "value {} vs {}", row.value, value);
        values.push(row.value);
        prop_assert_eq!(
            row.resources,
            tiles.iter().filter(|&&t| g.tile_setup(t).unwrap().resource.is_some()).count() as u32
        );
        // Path costs: the globe's paths, and the Dijkstra's.
        for (q, &o) in starts.iter().enumerate() {
            prop_assert_eq!(report.costs[p][q], costs[p][o.0 as usize], "cost {} to {}", p, q);
            prop_assert_eq!(report.costs[p][q], g.path(s, o).map(|path| path.cost), "path {} to {}", p, q);
        }
    }
    let s = spread(&values);
    prop_assert!(s == report.spread || (s - report.spread).abs() < 1e-5, "spread {} vs {}", report.spread, s);
    prop_assert_eq!(report.within_bound, report.spread <= cfg.fairness);
    // Resources: allowed tiles, spacing, one a tile, guarantees.
    let resources = setup.resources();
    prop_assert_eq!(report.resources as usize, resources.len());
    let mut seen = BTreeSet::new();
    for (k, r) in resources.iter().enumerate() {
        let rule = &cfg.resources[r.rule as usize];
        prop_assert!(allowed(g, r.tile, &rule.on), "{} on a tile it may not lie on", r.name);
        prop_assert!(seen.insert(r.tile), "two resources on one tile");
        prop_assert_eq!(g.tile_setup(r.tile).unwrap().resource, Some(r));
        let d = steps(g, r.tile);
        for o in &resources[k + 1..] {
            if o.rule == r.rule {
                prop_assert!(d[o.tile.0 as usize] >= rule.spacing, "{} closer than its spacing", r.name);
            }
        }
    }
    for (p, &s) in starts.iter().enumerate() {
        let tiles = ring(g, s, cfg.rings);
        for (i, rule) in cfg.resources.iter().enumerate() {
            let found = tiles
                .iter()
                .filter(|&&t| g.tile_setup(t).unwrap().resource.is_some_and(|r| r.rule == i as u32))
                .count();
            let reported = report.shortfalls.iter().any(|f| f.player == p as u32 && f.resource == rule.name);
            prop_assert!(found >= rule.per_player as usize || reported, "player {p} short of {}", rule.name);
        }
    }
    // Wonders.
    let wonders = setup.wonders();
    prop_assert!(wonders.len() <= cfg.wonders.count as usize);
    for (k, w) in wonders.iter().enumerate() {
        prop_assert!(allowed(g, w.tile, &cfg.wonders.list[w.rule as usize].on));
        prop_assert!(g.tile_setup(w.tile).unwrap().resource.is_none());
        let d = steps(g, w.tile);
        for &s in starts {
            prop_assert!(d[s.0 as usize] >= cfg.wonders.from_starts, "wonder near a start");
        }
        for o in &wonders[k + 1..] {
            prop_assert!(d[o.tile.0 as usize] >= cfg.wonders.spacing, "wonders too close");
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    #[test]
    fn a_globes_setup_keeps_its_promises(
        frequency in 4u32..=11,
        seed in any::<u32>(),
        players in 1u32..=6,
        rings in 1u32..=3,
        min_distance in 2u32..=6,
        coast in any::<bool>(),
        wonders in 0u32..=3,
    ) {
        let mut setup = SetupConfig { players, rings, min_distance, ..SetupConfig::default() };
        setup.start_on = if coast { StartOn::Coast } else { StartOn::Land };
        setup.wonders.count = wonders;
        match globe(frequency, seed, setup) {
            Ok(g) => {
                check_setup(&g)?;
                // The same setup however the globe is built.
                let again = g.with_setup(None).unwrap().with_setup(g.config().setup.clone()).unwrap();
                prop_assert_eq!(again.setup(), g.setup());
            }
            // Refused only by the fields that say the starts do not fit.
            Err(e) => prop_assert!(e.field == "setup.players" || e.field == "setup.min_distance", "{e}"),
        }
    }
}

#[test]
fn an_edited_globe_places_its_setup_on_the_edited_tiles() {
    let g = globe(9, 7, SetupConfig { players: 3, ..SetupConfig::default() }).unwrap();
    // Drown the first start: the edited globe's starts avoid it.
    let first = g.setup().unwrap().starts()[0];
    let edit = TileEdit { kind: Some(TileKind::Sea), ..TileEdit::at(first.at()) };
    let edited = g.with_edits(vec![edit]).unwrap();
    assert!(!edited.setup().unwrap().starts().contains(&first));
    let fresh = GlobeTerrain::new(edited.config().clone()).unwrap();
    assert_eq!(fresh.setup(), edited.setup());
    check_setup(&edited).unwrap();
}

#[test]
fn a_globe_refuses_a_setup_it_cannot_hold_by_the_field() {
    let area = hex_terrain::TileRect { min: [0, 0], max: [4, 4] };
    let e = globe(5, 1, SetupConfig { area: Some(area), ..SetupConfig::default() }).unwrap_err();
    assert_eq!(e.field, "setup.area");
    let e = globe(3, 1, SetupConfig { players: 60, min_distance: 2, ..SetupConfig::default() }).unwrap_err();
    assert_eq!(e.field, "setup.players");
    let e = globe(6, 1, SetupConfig { players: 8, min_distance: 30, ..SetupConfig::default() }).unwrap_err();
    assert_eq!(e.field, "setup.min_distance");
    assert!(e.allowed.contains("fits on this map"), "{e}");
}

#[test]
fn the_setups_resources_and_wonders_stand_on_their_tiles_in_every_chunk() {
    let mut setup = SetupConfig { players: 3, ..SetupConfig::default() };
    setup.wonders.count = 3;
    let g = globe(9, 11, setup).unwrap();
    let placed = g.setup().unwrap();
    let sea = g.radius() + f64::from(g.config().terrain.sea_threshold * g.config().terrain.max_elevation);
    // What the setup placed, off the starts: each a marker, once over all chunks, at both levels.
    let mut wanted: Vec<(GlobeTile, hex_terrain::PropKind, u8)> = placed
        .resources()
        .iter()
        .map(|r| (r.tile, hex_terrain::PropKind::Resource, r.class as u8))
        .filter(|(t, ..)| g.tile_setup(*t).unwrap().wonder.is_none())
        .chain(placed.wonders().iter().map(|w| (w.tile, hex_terrain::PropKind::Wonder, 0)))
        .collect();
    wanted.sort_by_key(|w| w.0);
    assert!(!wanted.is_empty());
    for coarse in [false, true] {
        let mut got = Vec::new();
        for chunk in g.chunks() {
            let full = g.generate(chunk);
            let mesh = if coarse { full.coarse() } else { full };
            for m in g.marker_props(&mesh) {
                let foot: Vec<f64> = (0..3).map(|k| mesh.origin[k] + f64::from(m.position[k])).collect();
                let r = foot.iter().map(|c| c * c).sum::<f64>().sqrt();
                let center = g.grid().center(m.tile).unwrap();
                // At its tile's center, upright.
                let dir: Vec<f64> = foot.iter().map(|c| c / r).collect();
                assert!((0..3).all(|k| (dir[k] - center[k]).abs() < 1e-5), "{:?} not at its center", m.tile);
                assert!((0..3).all(|k| (f64::from(m.up[k]) - center[k]).abs() < 1e-5));
                // On the surface as meshed, or on the sea over it: a ray from outside down to
                // the center meets the ground there.
                let outside: Vec<f64> = center.iter().map(|c| c * 2.0 * g.radius()).collect();
                let down = center.map(|c| -c);
                let hit = g.raycast([outside[0], outside[1], outside[2]], down, f64::MAX).unwrap();
                let ground = hit.point.iter().map(|c| c * c).sum::<f64>().sqrt();
                if !coarse {
                    assert_eq!(hit.tile, m.tile);
                    assert!((r - ground.max(sea)).abs() < 1e-3, "{:?}: foot at {r}, ground {ground}", m.tile);
                }
                got.push((m.tile, m.kind, m.variant));
            }
        }
        got.sort_by_key(|w| w.0);
        assert_eq!(got, wanted, "coarse: {coarse}");
    }
}

#[test]
fn an_edit_reports_every_tile_whose_setup_changed() {
    let mut config = MapConfig { seed: 21, size: MapSize::Globe { frequency: 8 }, ..Default::default() };
    config.noise.scale = 60.0;
    config.terrain.sea_threshold = 0.45;
    config.climate.enabled = true;
    config.setup = Some(SetupConfig { players: 2, min_distance: 3, ..SetupConfig::default() });
    let mut editor = hex_terrain::GlobeEditor::new(config).unwrap();
    let before = editor.globe().clone();
    let start = before.setup().unwrap().starts()[0];
    // Sink the first start and its neighbors: the setup moves, and resources with it.
    let stroke = hex_terrain::GlobeStroke {
        tool: hex_terrain::Tool::SetKind(TileKind::Sea),
        brush: hex_terrain::Brush::Range(1),
        tile: start,
    };
    let change = editor.apply(stroke).unwrap();
    let after = editor.globe();
    let placed = |g: &GlobeTerrain, t: GlobeTile| {
        let s = g.tile_setup(t).unwrap();
        (s.start, s.resource.cloned(), s.wonder.cloned())
    };
    let moved: Vec<GlobeTile> = before.grid().tiles().filter(|&t| placed(&before, t) != placed(after, t)).collect();
    assert!(!moved.is_empty(), "the setup did not move");
    for t in moved {
        assert!(change.tiles.contains(&t), "{t:?}'s setup changed, not reported");
        assert!(change.chunks.contains(&after.chunk_of(t).unwrap()), "{t:?}'s chunk not rebuilt");
    }
}
