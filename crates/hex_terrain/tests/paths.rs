//! Paths, reach and turns over random maps (bounded, wrapping, unbounded, edited) and random
//! movement models, against what is computed here another way: a textbook Dijkstra over the
//! tiles' costs from the config's movement model, and a simulation of the turn rule.

use std::cmp::Reverse;
use std::collections::{BTreeMap, BinaryHeap};

use hex_terrain::hexx::Hex;
use hex_terrain::{
    Biome, MapConfig, MapSize, MovementConfig, NoiseConfig, Path, RiverModel, Terrain, TileEdit, TileKind,
};
use proptest::prelude::*;

#[path = "common/biome.rs"]
mod biome;
mod common;

prop_compose! {
    fn movement()(
        costs in prop::collection::btree_map(0usize..13, 0u32..5, 0..5),
        river in 0u32..4,
        embark in prop::option::of(1u32..5),
    ) -> MovementConfig {
        let costs = costs.into_iter().map(|(b, c)| (Biome::ALL[b], c)).collect();
        MovementConfig { costs, river, embark }
    }
}

prop_compose! {
    fn config()(
        seed in any::<u32>(),
        (x, z) in (6u32..28, 6u32..20),
        size in 0u8..5,
        scale in 4.0f64..20.0,
        climate in any::<bool>(),
        rivers in any::<bool>(),
        on_edges in any::<bool>(),
        wrap in any::<bool>(),
        movement in movement(),
        edits in prop::collection::btree_map((0i32..6, 0i32..6), 0usize..3, 0..6),
    ) -> MapConfig {
        let unbounded = size == 0;
        let mut c = MapConfig {
            seed,
            size: if unbounded { MapSize::Unbounded } else { MapSize::Bounded { x, z } },
            noise: NoiseConfig { scale, ..NoiseConfig::default() },
            chunk_size: (8, 8),
            movement,
            ..MapConfig::default()
        };
        c.climate.enabled = climate;
        c.rivers.enabled = rivers && !unbounded;
        c.rivers.threshold = 4.0;
        if on_edges {
            c.rivers.model = RiverModel::Edges;
        }
        if !unbounded {
            c.edits = edits
                .into_iter()
                .map(|((col, row), k)| TileEdit { kind: Some(TileKind::ALL[k]), ..TileEdit::at((col, row)) })
                .collect();
        }
        common::wrapping(c, wrap && !unbounded)
    }
}

/// The cost of entering a tile, from its biome and river and the config's model.
fn enter(t: &Terrain, tile: Hex) -> Option<u32> {
    let info = t.tile_info(tile)?;
    t.config().movement.enter(biome::of(t, &info), info.river_flow > 0.0)
}

/// The cost of the step from `from` to its neighbor `to`: entering `to`, and the model's river
/// cost when `from`'s river edges hold one toward `to` (its edge's far tile, brought onto the map).
fn step(t: &Terrain, from: Hex, to: Hex) -> Option<u32> {
    let across = t.river_edges(from).iter().any(|r| t.wrap_tile(r.edge.destination()) == Some(to));
    Some(enter(t, to)? + if across { t.config().movement.river } else { 0 })
}

/// Dijkstra from `from` over the map's tiles (hexx's neighbors brought onto the map), within
/// `radius` tiles of `from` on an unbounded world, never entering `blocked` tiles.
fn dijkstra(t: &Terrain, from: Hex, radius: u32, blocked: &[Hex]) -> BTreeMap<(i32, i32), u32> {
    let mut dist = BTreeMap::from([((from.x, from.y), 0)]);
    let mut heap = BinaryHeap::from([Reverse((0u32, from.x, from.y))]);
    while let Some(Reverse((d, x, y))) = heap.pop() {
        if dist[&(x, y)] < d {
            continue;
        }
        for n in Hex::new(x, y).all_neighbors() {
            let Some(n) = t.wrap_tile(n) else { continue };
            if t.bounds().is_none() && from.unsigned_distance_to(n) > radius {
                continue;
            }
            let Some(c) = step(t, Hex::new(x, y), n).filter(|_| !blocked.contains(&n)) else { continue };
            if dist.get(&(n.x, n.y)).is_none_or(|&e| d + c < e) {
                dist.insert((n.x, n.y), d + c);
                heap.push(Reverse((d + c, n.x, n.y)));
            }
        }
    }
    dist
}

/// A path is connected, passable, and costs what its steps cost.
fn check_path(t: &Terrain, path: &Path, from: Hex, to: Hex) -> Result<(), TestCaseError> {
    prop_assert_eq!(path.tiles.first(), Some(&from));
    prop_assert_eq!(path.tiles.last(), Some(&to));
    let mut cost = 0;
    for pair in path.tiles.windows(2) {
        prop_assert_eq!(t.distance(pair[0], pair[1]), Some(1), "{:?} is not a step", pair);
        cost += step(t, pair[0], pair[1]).expect("a passable step");
    }
    prop_assert_eq!(cost, path.cost);
    Ok(())
}

/// The turn rule, simulated: enter with any points left (this turn's as given, a bonus above the
/// full points too), paying the cost or all that is left; the turn of each tile, the points left
/// there, and the turns.
fn simulate(t: &Terrain, path: &Path, points: u32, left: u32) -> (Vec<u32>, Vec<u32>, u32) {
    let (mut turn, mut have, mut turns, mut lefts) = (0, left, vec![0], vec![left]);
    for pair in path.tiles.windows(2) {
        if have == 0 {
            turn += 1;
            have = points;
        }
        have = have.saturating_sub(step(t, pair[0], pair[1]).unwrap());
        turns.push(turn);
        lefts.push(have);
    }
    let count = if path.tiles.len() > 1 { turn + 1 } else { 0 };
    (turns, lefts, count)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn paths_and_reach_equal_dijkstra_and_turns_follow_the_rule(
        config in config(),
        picks in prop::collection::vec((0i32..40, 0i32..30), 2..6),
        budget in prop_oneof![0u32..12, Just(u32::MAX), u32::MAX - 8..=u32::MAX],
        (points, left) in (prop_oneof![1u32..6, Just(u32::MAX)], prop_oneof![0u32..10, Just(u32::MAX)]),
    ) {
        let t = Terrain::new(config).unwrap();
        let tile = |(c, r): (i32, i32)| t.tile_from_offset([c, r]);
        let from = tile(picks[0]);
        if !t.contains(from) {
            prop_assert!(t.path(from, from).is_none() && t.reachable(from, budget).is_empty());
            return Ok(());
        }
        let from = t.wrap_tile(from).unwrap();
        // The rules' table (bounded maps) answers as the surface does, tile by tile.
        for tile in t.tiles() {
            prop_assert_eq!(t.move_cost(tile), enter(&t, tile), "{:?}", tile);
            // A step's cost adds the river on the edge it crosses, the same both ways.
            for nb in tile.all_neighbors().into_iter().filter_map(|n| t.wrap_tile(n)).filter(|&n| t.contains(n)) {
                prop_assert_eq!(t.step_cost(tile, nb), step(&t, tile, nb), "{:?} -> {:?}", tile, nb);
                prop_assert_eq!(t.crosses_river(tile, nb), t.crosses_river(nb, tile));
            }
        }
        let radius = 40;
        let dist = dijkstra(&t, from, radius, &[]);
        for &pick in &picks[1..] {
            let to = tile(pick);
            let path = t.path(from, to);
            let Some(own) = t.wrap_tile(to) else {
                prop_assert!(path.is_none(), "off the map");
                continue;
            };
            match (&path, dist.get(&(own.x, own.y))) {
                (Some(path), expected) => {
                    check_path(&t, path, from, own)?;
                    if t.bounds().is_some() {
                        prop_assert_eq!(Some(&path.cost), expected, "A* equals Dijkstra");
                    } else {
                        // Unbounded: Dijkstra searched a disc, which holds paths at least as dear.
                        prop_assert!(expected.is_none_or(|&e| path.cost <= e));
                    }
                    // The same path again, and on another thread from a terrain compiled there.
                    let again = t.path(from, to);
                    prop_assert_eq!(again.as_ref(), Some(path), "the same path again");
                    let config = t.config().clone();
                    let there = std::thread::spawn(move || Terrain::new(config).unwrap().path(from, to));
                    let there = there.join().unwrap();
                    prop_assert_eq!(there.as_ref(), Some(path), "the same path on another thread");
                    let turns = t.turns(path, points, left).unwrap();
                    let (each, lefts, count) = simulate(&t, path, points, left);
                    prop_assert_eq!(&turns.turn, &each);
                    prop_assert_eq!(&turns.left, &lefts);
                    prop_assert_eq!(turns.count, count);
                    prop_assert_eq!(turns.ends.len() as u32, count);
                    prop_assert_eq!(turns.ends.last().copied(), (path.tiles.len() > 1).then_some(own));
                }
                (None, expected) => {
                    if t.bounds().is_some() {
                        prop_assert!(expected.is_none() || own == from, "Dijkstra reached {:?}", own);
                    }
                }
            }
        }
        // The reach: the Dijkstra ball of the budget (whole on a bounded map).
        if t.bounds().is_some() {
            let reach: BTreeMap<(i32, i32), u32> = t.reachable(from, budget).into_iter().map(|(h, c)| ((h.x, h.y), c)).collect();
            let ball: BTreeMap<(i32, i32), u32> = dist.iter().filter(|&(_, &d)| d <= budget).map(|(&k, &d)| (k, d)).collect();
            prop_assert_eq!(reach, ball);
            let order = t.reachable(from, budget);
            prop_assert!(order.windows(2).all(|w| w[0].1 <= w[1].1), "in order of cost");
            prop_assert_eq!(order.first().copied(), Some((from, 0)));
            // Around taken tiles: the picks but the start are taken.
            let taken: Vec<Hex> = picks[1..].iter().filter_map(|&p| t.wrap_tile(tile(p))).filter(|&h| h != from).collect();
            let around = dijkstra(&t, from, radius, &taken);
            let blocked = |h: Hex| taken.contains(&h);
            let reach: BTreeMap<(i32, i32), u32> =
                t.reachable_avoiding(from, budget, blocked).into_iter().map(|(h, c)| ((h.x, h.y), c)).collect();
            let ball: BTreeMap<(i32, i32), u32> = around.iter().filter(|&(_, &d)| d <= budget).map(|(&k, &d)| (k, d)).collect();
            prop_assert_eq!(reach, ball);
            for &goal in t.tiles().collect::<Vec<_>>().iter().step_by(7) {
                let path = t.path_avoiding(from, goal, blocked);
                prop_assert_eq!(path.as_ref().map(|p| p.cost), if goal == from { Some(0) } else { around.get(&(goal.x, goal.y)).copied() });
                if let Some(path) = path {
                    check_path(&t, &path, from, goal)?;
                    prop_assert!(path.tiles.iter().all(|h| !taken.contains(h)), "a taken tile on the path");
                }
            }
        }
    }
}

#[test]
fn a_path_across_the_seam_of_a_wrapping_map() {
    // All land, one cost: the short way from the west edge to the east edge is one step.
    let config = MapConfig::from_ron(
        "(size: Bounded(x: 20, z: 10), wrap: true, terrain: (sea_threshold: 0.0001, mountain_threshold: 0.9999, interpolation_tolerance: 0.0))",
    )
    .unwrap();
    let t = Terrain::new(config).unwrap();
    let (west, east) = (t.tile_from_offset([0, 4]), t.tile_from_offset([19, 4]));
    let path = t.path(west, east).unwrap();
    assert_eq!(path.tiles.len(), 2, "{path:?}");
    assert_eq!(path.cost, t.move_cost(east).unwrap());
}

#[test]
fn turns_pay_what_is_left_when_a_tile_costs_more() {
    let config = MapConfig::from_ron(
        "(size: Bounded(x: 12, z: 6), terrain: (sea_threshold: 0.0001, mountain_threshold: 0.9999, interpolation_tolerance: 0.0), \
         movement: (costs: {Plains: 3, Grassland: 3, Desert: 3, Tundra: 3, Snow: 3, Hills: 3, Forest: 3, Rainforest: 3}))",
    )
    .unwrap();
    let t = Terrain::new(config).unwrap();
    let path = t.path(t.tile_from_offset([0, 2]), t.tile_from_offset([4, 2])).unwrap();
    assert!(path.tiles.iter().skip(1).all(|&h| t.move_cost(h) == Some(3)), "{path:?}");
    // Two points a turn: each step takes what is left, so every step is a turn of its own.
    let turns = t.turns(&path, 2, 2).unwrap();
    assert_eq!(turns.turn, (0..path.tiles.len() as u32).map(|i| i.saturating_sub(1)).collect::<Vec<_>>());
    assert_eq!(turns.count, path.tiles.len() as u32 - 1);
    assert_eq!(turns.left, vec![2, 0, 0, 0, 0]);
    assert!(t.turns(&path, 0, 0).is_none());
    // Seven points left this turn, more than the two of a full turn: a bonus, spent as it is.
    assert_eq!(path.tiles.len(), 5);
    let bonus = t.turns(&path, 2, 7).unwrap();
    assert_eq!(bonus.turn, vec![0, 0, 0, 0, 1]);
    assert_eq!(bonus.left, vec![7, 4, 1, 0, 0]);
    assert_eq!(bonus.ends, vec![path.tiles[3], path.tiles[4]]);
    // No points a turn: what is left this turn walks as far as it pays, then no more.
    assert!(t.turns(&path, 0, 7).is_none());
    let short = hex_terrain::Path { tiles: path.tiles[..3].to_vec(), cost: 6 };
    assert_eq!(t.turns(&short, 0, 7).unwrap().left, vec![7, 4, 1]);
}

/// Any budget, on an unbounded world too: the reach stops at `MAX_PATH_TILES` tiles, in order of
/// cost, without overflow (this runs in the overflow-checked build too), and a goal that cannot
/// be reached is searched for no longer.
#[test]
fn the_largest_budget_is_bounded_by_the_search() {
    let config = MapConfig::from_ron("(size: Unbounded, movement: (embark: Some(1)))").unwrap();
    let t = Terrain::new(config).unwrap();
    let from = (0..).map(|c| t.tile_from_offset([c, 0])).find(|&h| t.move_cost(h).is_some()).unwrap();
    let reach = t.reachable(from, u32::MAX);
    assert_eq!(reach.len(), hex_terrain::MAX_PATH_TILES);
    assert_eq!(reach[0], (from, 0));
    assert!(reach.windows(2).all(|w| w[0].1 <= w[1].1), "in order of cost");
    let far = t.tile_from_offset([1 << 20, 0]);
    if t.move_cost(far).is_some() {
        assert!(t.path(from, far).is_none(), "beyond the search");
    }
}
