//! The rules (paths, movement range, sight, every player's fog) on Civ6 Huge (106x66, climate
//! and rivers, units may embark so the sea can be crossed) beside hexx 0.25's `a_star`,
//! `field_of_movement` and `range_fov` given the same costs, in one process, each the median of
//! many runs, with the ratio ours / hexx (below 1: ours is faster).
//!
//! hexx knows nothing of the terrain: it is given what a game would give it, a `HashMap` from
//! each tile of the map to its cost (or whether it blocks sight), built once outside the timing.
//! The maps here do not wrap, so both solve the same problem (hexx does not wrap); ours on the
//! wrapping map is printed beside. The sight rules differ (ours sees over lower tiles and farther
//! from hills and mountains; hexx's `range_fov` only stops at blocking tiles): the field of view
//! compares the work, not the answer. Our rules' table (each tile's cost and sight height) is
//! made on the first rules query of a map; its time is printed first and left out of the rest.
//!
//! `cargo bench -p hex_terrain_bench --bench rules`

use std::collections::{HashMap, HashSet};
use std::hint::black_box;
use std::time::{Duration, Instant};

use hex_terrain::hexx::Hex;
use hex_terrain::{FogOfWar, MapConfig, Terrain, TileKind};
use hex_terrain_bench::{median, ms};
use hexx::algorithms::{a_star, field_of_movement, range_fov};

/// Players and units a player for the fog's turn (Civilization VI's Huge map has 12 players).
const PLAYERS: u32 = 12;
const UNITS: usize = 20;
/// Civilization's sight radius of a land unit.
const SIGHT: u32 = 2;

/// The median time of `runs` calls of `f`.
fn time<T>(runs: usize, mut f: impl FnMut() -> T) -> Duration {
    let mut times = Vec::with_capacity(runs);
    for _ in 0..runs {
        let start = Instant::now();
        black_box(f());
        times.push(start.elapsed());
    }
    median(times)
}

/// A timing in microseconds, right-aligned for a table.
fn us(d: Duration) -> String {
    format!("{:9.1} µs", d.as_secs_f64() * 1e6)
}

fn row(what: &str, ours: Duration, hexx: Duration) {
    let ratio = ours.as_secs_f64() / hexx.as_secs_f64();
    println!("  {what:<34} ours {}  hexx {}  ratio {ratio:5.2}", us(ours), us(hexx));
}

fn main() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/maps/civ6/huge.map.ron");
    let mut config = MapConfig::load(path).expect("the Huge preset");
    config.movement.embark = Some(2);
    let wrapping = Terrain::new(config.clone()).expect("a valid config");
    config.wrap = false;
    let terrain = Terrain::new(config).expect("a valid config");
    let start = Instant::now();
    let first = terrain.move_cost(terrain.tile_from_offset([0, 0]));
    println!("Civ6 Huge, rivers and climate, embarking: the rules' table made in {}", ms(start.elapsed()));
    black_box((first, wrapping.move_cost(Hex::ZERO)));

    // What a hexx user holds: each tile's cost and whether it blocks sight.
    let tiles: Vec<Hex> = terrain.tiles().collect();
    let costs: HashMap<Hex, u32> = tiles.iter().filter_map(|&t| Some((t, terrain.move_cost(t)?))).collect();
    let blocks: HashSet<Hex> =
        tiles.iter().copied().filter(|&t| terrain.tile_kind(t) == Some(TileKind::Mountain)).collect();

    // A path from corner to corner.
    let (a, b) = (terrain.tile_from_offset([0, 0]), terrain.tile_from_offset([105, 65]));
    let ours = terrain.path(a, b).expect("a path across the map");
    let theirs = a_star(a, b, |_, to| costs.get(&to).copied()).expect("a path across the map");
    let theirs_cost: u32 = theirs[1..].iter().map(|t| costs[t]).sum();
    assert_eq!(ours.cost, theirs_cost, "both find a cheapest path");
    println!("paths (cost {}, {} tiles):", ours.cost, ours.tiles.len());
    row(
        "corner to corner",
        time(21, || terrain.path(a, b)),
        time(21, || a_star(a, b, |_, to| costs.get(&to).copied())),
    );
    // The wrapping map's corner may be another tile (its edges blend into each other): the
    // enterable tile of the last row nearest it.
    let b = (0..106).rev().map(|c| wrapping.tile_from_offset([c, 65])).find(|&t| wrapping.move_cost(t).is_some());
    let b = b.expect("an enterable tile on the last row");
    let across = wrapping.path(a, b).expect("a path across the seam");
    let seam = time(21, || wrapping.path(a, b));
    println!("  {:<34} ours {}  (cost {}, across the seam)", "the same on the wrapping map", us(seam), across.cost);

    // The movement range of 4 points from the map's middle (hexx's cost is the extra cost of a
    // tile over 1).
    let middle = terrain.tile_from_offset([53, 33]);
    let reach: HashSet<Hex> = terrain.reachable(middle, 4).into_iter().map(|(t, _)| t).collect();
    let extra = |h: Hex| costs.get(&h).map(|c| c - 1);
    assert_eq!(reach, field_of_movement(middle, 4, extra), "both reach the same tiles");
    println!("movement range ({} tiles):", reach.len());
    row(
        "4 points from the middle",
        time(201, || terrain.reachable(middle, 4)),
        time(201, || field_of_movement(middle, 4, extra)),
    );

    // The field of view of radius 3 from a mountain (a mountain sees 2 farther by our rule).
    let mountain = tiles.iter().copied().filter(|t| blocks.contains(t)).min_by_key(|t| t.unsigned_distance_to(middle));
    let mountain = mountain.expect("a mountain");
    let reach = 3 + terrain.config().sight.mountain_bonus;
    println!(
        "field of view from a mountain (ours {} tiles, hexx {}):",
        terrain.field_of_view(mountain, 3).expect("a bounded map").len(),
        range_fov(mountain, reach, |h| h != mountain && blocks.contains(&h)).len()
    );
    row(
        &format!("radius 3 (reach {reach})"),
        time(501, || terrain.field_of_view(mountain, 3)),
        time(501, || range_fov(mountain, reach, |h| h != mountain && blocks.contains(&h))),
    );

    // A turn's fog: 12 players with 20 land units each, sight 2. hexx's: each unit's
    // `range_fov`, its tiles gathered into the player's visible set, and the set kept as explored.
    let land: Vec<Hex> = tiles.iter().copied().filter(|&t| terrain.tile_kind(t) == Some(TileKind::Land)).collect();
    let step = land.len() / (PLAYERS as usize * UNITS);
    let units: Vec<Vec<(Hex, u32)>> =
        (0..PLAYERS as usize).map(|p| (0..UNITS).map(|u| (land[(p * UNITS + u) * step], SIGHT)).collect()).collect();
    let mut fog = FogOfWar::new(&terrain, PLAYERS).expect("12 players");
    let ours = time(201, || {
        for (player, units) in units.iter().enumerate() {
            fog.update(&terrain, player as u32, units.iter().copied()).expect("the fog's own map");
        }
    });
    let mut explored: Vec<HashSet<Hex>> = vec![HashSet::new(); PLAYERS as usize];
    let theirs = time(201, || {
        for (player, units) in units.iter().enumerate() {
            let visible: HashSet<Hex> =
                units.iter().flat_map(|&(u, s)| range_fov(u, s, |h| blocks.contains(&h))).collect();
            explored[player].extend(visible.iter().copied());
        }
    });
    println!("a turn's fog, {PLAYERS} players x {UNITS} units, sight {SIGHT}:");
    row("every player's fog updated", ours, theirs);
    let visible: usize = (0..PLAYERS).map(|p| fog.visible(p).count()).sum();
    println!("  {visible} tiles visible in all; target: under 1 ms a turn");
}
