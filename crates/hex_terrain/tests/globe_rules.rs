//! The flat map's rules on a globe, checked by computations written here over the globe's tile
//! graph (pentagons included): path and reach costs against a Bellman-Ford relaxation, paths
//! walked step by step, sight against the rule written out (distances by a breadth-first
//! search, the great circle sampled here), the fog against the units' fields of view, the
//! climate against latitude and the biome table.

use std::collections::BTreeSet;

use hex_terrain::{
    Biome, FogState, GlobeFog, GlobeTerrain, GlobeTile, Landform, MapConfig, MapSize, SaveError, TileKind,
};
#[path = "common/vec3.rs"]
mod vec3;
use vec3::{V, dot, normalize, scale};

/// A globe with its climate on or off and units embarking or not.
fn globe(frequency: u32, seed: u32, climate: bool, embark: Option<u32>) -> GlobeTerrain {
    let mut config = MapConfig { seed, size: MapSize::Globe { frequency }, ..Default::default() };
    config.noise.scale = 60.0;
    config.terrain.sea_threshold = 0.47;
    config.terrain.mountain_threshold = 0.56;
    config.climate.enabled = climate;
    config.movement.embark = embark;
    GlobeTerrain::new(config).unwrap()
}

fn cases() -> Vec<GlobeTerrain> {
    vec![
        globe(3, 1, false, None),
        globe(5, 2, true, None),
        globe(6, 3, true, Some(3)),
        globe(8, 4, false, Some(1)),
        globe(9, 5, true, Some(2)),
    ]
}

/// A tile's biome, read from what the globe says the tile is.
fn biome(g: &GlobeTerrain, t: GlobeTile) -> Option<Biome> {
    g.tile_info(t).map(|i| g.ruleset().biome(i.terrain.terrain).expect("a biome"))
}

/// What entering a tile costs, from its biome by the movement model: `None` impassable.
fn enter(g: &GlobeTerrain, t: GlobeTile) -> Option<u32> {
    g.config().movement.enter(biome(g, t).unwrap(), false)
}

/// Every tile's cheapest cost from `from` (never re-entering `from`, never entering `blocked`),
/// by relaxing every edge until nothing changes.
fn bellman_ford(g: &GlobeTerrain, from: GlobeTile, blocked: &BTreeSet<GlobeTile>) -> Vec<Option<u32>> {
    let n = g.grid().tile_count() as usize;
    let mut best: Vec<Option<u32>> = vec![None; n];
    best[from.0 as usize] = Some(0);
    loop {
        let mut changed = false;
        for t in g.grid().tiles() {
            let Some(c) = best[t.0 as usize] else { continue };
            for &m in &g.grid().neighbors(t).unwrap() {
                if m == from || blocked.contains(&m) {
                    continue;
                }
                let Some(step) = enter(g, m) else { continue };
                if best[m.0 as usize].is_none_or(|b| c + step < b) {
                    best[m.0 as usize] = Some(c + step);
                    changed = true;
                }
            }
        }
        if !changed {
            return best;
        }
    }
}

/// A small random generator, so the tests pick the same tiles on every run.
fn picks(seed: u64, count: usize, below: u32) -> Vec<u32> {
    let mut s = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
    (0..count)
        .map(|_| {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s % u64::from(below)) as u32
        })
        .collect()
}

#[test]
fn paths_are_cheapest_by_bellman_ford_and_walk_the_tile_graph() {
    for (k, g) in cases().iter().enumerate() {
        let count = g.grid().tile_count();
        let froms = picks(k as u64 + 1, 6, count);
        for (i, &from) in froms.iter().enumerate() {
            let from = GlobeTile(from);
            // Every third search avoids a few tiles, as a unit avoids others.
            let blocked: BTreeSet<GlobeTile> = if i % 3 == 2 {
                picks(k as u64 * 31 + i as u64, 12, count).into_iter().map(GlobeTile).filter(|&t| t != from).collect()
            } else {
                BTreeSet::new()
            };
            let best = bellman_ford(g, from, &blocked);
            for to in picks(k as u64 * 7 + i as u64, 25, count).into_iter().map(GlobeTile) {
                let path = g.path_avoiding(from, to, |t| blocked.contains(&t));
                assert_eq!(path.as_ref().map(|p| p.cost), best[to.0 as usize], "globe {k}: {from:?} to {to:?}");
                let Some(path) = path else { continue };
                assert_eq!((path.tiles[0], *path.tiles.last().unwrap()), (from, to));
                let mut cost = 0;
                for w in path.tiles.windows(2) {
                    assert!(g.grid().neighbors(w[0]).unwrap().as_slice().contains(&w[1]), "a jump {w:?}");
                    assert!(!blocked.contains(&w[1]), "through a blocked tile");
                    cost += enter(g, w[1]).expect("through a tile it cannot enter");
                }
                assert_eq!(cost, path.cost, "globe {k}: the steps' costs add up");
            }
        }
    }
}

#[test]
fn reach_is_every_tile_within_the_budget_by_bellman_ford() {
    for (k, g) in cases().iter().enumerate() {
        for (i, from) in picks(k as u64 + 40, 4, g.grid().tile_count()).into_iter().map(GlobeTile).enumerate() {
            let best = bellman_ford(g, from, &BTreeSet::new());
            for budget in [0, 1, 3, 7, u32::MAX] {
                let reach = g.reachable(from, budget);
                let mut expected: Vec<(GlobeTile, u32)> = g
                    .grid()
                    .tiles()
                    .filter_map(|t| best[t.0 as usize].filter(|&c| c <= budget).map(|c| (t, c)))
                    .collect();
                expected.sort_by_key(|&(t, c)| (c, t));
                assert_eq!(reach, expected, "globe {k}, start {i}, budget {budget}");
            }
        }
    }
}

/// A tile's sight height by the rule: 2 a mountain, 1 a tall biome.
fn height(g: &GlobeTerrain, t: GlobeTile) -> u8 {
    if g.tile_kind(t) == Some(TileKind::Mountain) {
        2
    } else {
        u8::from(g.config().sight.tall.contains(&biome(g, t).unwrap()))
    }
}

/// Steps from `from` to every tile, by a breadth-first search.
fn steps_from(g: &GlobeTerrain, from: GlobeTile) -> Vec<u32> {
    let mut steps = vec![u32::MAX; g.grid().tile_count() as usize];
    steps[from.0 as usize] = 0;
    let mut queue = std::collections::VecDeque::from([from]);
    while let Some(t) = queue.pop_front() {
        for &m in &g.grid().neighbors(t).unwrap() {
            if steps[m.0 as usize] == u32::MAX {
                steps[m.0 as usize] = steps[t.0 as usize] + 1;
                queue.push_back(m);
            }
        }
    }
    steps
}

/// The point `t` of the way along the great circle from `a` to `b` (not opposite).
fn along(a: V, b: V, t: f64) -> V {
    let angle = dot(a, b).clamp(-1.0, 1.0).acos();
    if angle < 1e-12 {
        return a;
    }
    let (wa, wb) = (((1.0 - t) * angle).sin(), (t * angle).sin());
    let (pa, pb) = (scale(a, wa), scale(b, wb));
    normalize([pa[0] + pb[0], pa[1] + pb[1], pa[2] + pb[2]])
}

#[test]
fn sight_is_the_flat_rule_over_the_tile_graph_and_the_great_circle() {
    let mut hidden = 0;
    for (k, g) in cases().iter().enumerate().skip(1) {
        let sight = &g.config().sight;
        for from in picks(k as u64 + 90, 8, g.grid().tile_count()).into_iter().map(GlobeTile) {
            for radius in [0, 1, 2, 4] {
                let own = height(g, from);
                let reach = radius + [0, sight.tall_bonus, sight.mountain_bonus][usize::from(own)];
                let steps = steps_from(g, from);
                let a = g.grid().center(from).unwrap();
                let expected: Vec<GlobeTile> = g
                    .grid()
                    .tiles()
                    .filter(|&t| steps[t.0 as usize] <= reach)
                    .filter(|&t| {
                        let b = g.grid().center(t).unwrap();
                        let samples = steps[t.0 as usize] * hex_terrain::GLOBE_SIGHT_SAMPLES;
                        (1..samples).all(|s| {
                            let on = g.grid().tile_at(along(a, b, f64::from(s) / f64::from(samples))).unwrap();
                            on == from || on == t || (height(g, on) <= own && height(g, on) < 2)
                        })
                    })
                    .collect();
                hidden += steps.iter().filter(|&&s| s <= reach).count() - expected.len();
                let seen = g.field_of_view(from, radius);
                assert_eq!(seen, expected, "globe {k}, from {from:?}, radius {radius}");
                assert!(seen.contains(&from));
            }
        }
        // Any radius: the whole globe at most.
        assert!(g.field_of_view(GlobeTile(0), u32::MAX).len() <= g.grid().tile_count() as usize);
    }
    assert!(hidden > 0, "no view was ever blocked: the rule went untested");
}

#[test]
fn the_fog_is_the_union_of_the_units_views_and_saves_whole() {
    let g = globe(6, 3, true, Some(3));
    let other = globe(6, 4, true, Some(3));
    let mut fog = GlobeFog::new(&g, 2).unwrap();
    let units: Vec<(GlobeTile, u32)> =
        picks(5, 4, g.grid().tile_count()).into_iter().map(|t| (GlobeTile(t), 2)).collect();
    fog.update(&g, 0, units.clone()).unwrap();
    let union: BTreeSet<GlobeTile> = units.iter().flat_map(|&(t, r)| g.field_of_view(t, r)).collect();
    assert_eq!(fog.visible(0).collect::<BTreeSet<_>>(), union);
    for t in g.grid().tiles() {
        let expected = if union.contains(&t) { FogState::Visible } else { FogState::Unexplored };
        assert_eq!(fog.state(0, t), Some(expected));
        assert_eq!(fog.state(1, t), Some(FogState::Unexplored));
    }
    // The units moved on: what they saw is explored, never unexplored again.
    let moved = [(GlobeTile(0), 1)];
    fog.update(&g, 0, moved).unwrap();
    let now: BTreeSet<GlobeTile> = g.field_of_view(GlobeTile(0), 1).into_iter().collect();
    for t in g.grid().tiles() {
        let expected = if now.contains(&t) {
            FogState::Visible
        } else if union.contains(&t) {
            FogState::Explored
        } else {
            FogState::Unexplored
        };
        assert_eq!(fog.state(0, t), Some(expected), "{t:?}");
    }
    let bytes = fog.to_bytes();
    assert_eq!(GlobeFog::from_bytes(&bytes, &g).unwrap(), fog);
    assert!(matches!(GlobeFog::from_bytes(&bytes, &other), Err(SaveError::OtherMap { field: "seed", .. })));
    let mut damaged = bytes.clone();
    let middle = damaged.len() / 2;
    damaged[middle] ^= 0x40;
    assert!(matches!(GlobeFog::from_bytes(&damaged, &g), Err(SaveError::Corrupt(_))));
    assert!(fog.update(&other, 0, []).is_err(), "another globe's terrain");
    assert!(fog.update(&g, 2, []).is_err(), "a player it does not have");
    assert!(GlobeFog::new(&g, 0).is_err());
}

#[test]
fn climate_follows_latitude_and_biomes_the_table() {
    for seed in [1, 2, 3] {
        let g = globe(12, seed, true, None);
        let c = &g.config().climate;
        let (sea, mountain) = (g.config().terrain.sea_threshold, g.config().terrain.mountain_threshold);
        let mut cold = 0;
        for t in g.grid().tiles() {
            let info = g.tile_info(t).unwrap();
            let center = g.grid().center(t).unwrap();
            assert!((info.latitude - center[1].asin().to_degrees()).abs() < 1e-9);
            let climate = g.tile_climate(t).expect("a globe with a climate");
            let raw = g.tile_height(t).unwrap();
            let above = ((raw - sea) / (1.0 - sea)).max(0.0);
            let polar = 1.0 - (info.latitude.abs() / 90.0) as f32;
            let (lo, hi) = (
                polar - c.temperature_jitter - c.lapse_rate * above,
                polar + c.temperature_jitter - c.lapse_rate * above,
            );
            assert!(
                climate.temperature >= lo.clamp(0.0, 1.0) - 1e-5 && climate.temperature <= hi.clamp(0.0, 1.0) + 1e-5,
                "{t:?} at {:.1} degrees: {} outside {lo}..{hi}",
                info.latitude,
                climate.temperature
            );
            let neighbors = g.grid().neighbors(t).unwrap();
            let kinds: Vec<TileKind> = neighbors.as_slice().iter().map(|&n| g.tile_kind(n).unwrap()).collect();
            let expected = match info.kind {
                TileKind::Sea if kinds.iter().any(|&k| k != TileKind::Sea) => Biome::Coast,
                TileKind::Sea => Biome::Ocean,
                kind => {
                    let rule = c
                        .biomes
                        .iter()
                        .find(|r| r.relief == kind && r.covers(climate.temperature, climate.moisture))
                        .expect("the table covers every climate");
                    let high = kind == TileKind::Land && raw - sea >= c.hills * (mountain - sea) && c.hills < 1.0;
                    if high && !matches!(rule.biome, Biome::Snow | Biome::Tundra) { Biome::Hills } else { rule.biome }
                }
            };
            let got = g.ruleset().biome(info.terrain.terrain).unwrap();
            assert_eq!(got, expected, "{t:?}");
            // Its landform, by the same heights and neighbors.
            let high = info.kind == TileKind::Land && raw - sea >= c.hills * (mountain - sea) && c.hills < 1.0;
            let landform = match info.kind {
                TileKind::Sea if expected == Biome::Coast => Landform::Shore,
                TileKind::Sea => Landform::OpenSea,
                TileKind::Mountain => Landform::Mountain,
                TileKind::Land if high => Landform::Hills,
                TileKind::Land => Landform::Flat,
            };
            assert_eq!(info.terrain.landform, landform, "{t:?}");
            // Its traits, the config's for its biome.
            assert_eq!(info.terrain.traits.movement, g.config().movement.biome_cost(got));
            assert_eq!(info.terrain.traits.tall, g.config().sight.tall.contains(&got));
            cold += usize::from(info.latitude.abs() > 70.0 && matches!(got, Biome::Snow | Biome::Tundra));
        }
        assert!(cold > 0, "seed {seed}: no snow or tundra near the poles");
    }
    // Without a climate, biomes follow the kinds and no tile has a climate.
    let g = globe(5, 1, false, None);
    for t in g.grid().tiles() {
        assert_eq!(biome(&g, t), g.tile_kind(t).map(Biome::of_kind));
        assert_eq!(g.tile_climate(t), None);
    }
}

#[test]
fn tile_info_places_each_tile_and_refuses_strangers() {
    let g = globe(7, 9, false, None);
    let max = g.config().terrain.max_elevation;
    for t in g.grid().tiles() {
        let info = g.tile_info(t).unwrap();
        let center = g.grid().center(t).unwrap();
        let (lat, lon) = (info.latitude.to_radians(), info.longitude.to_radians());
        let back = [lat.cos() * lon.cos(), lat.sin(), -lat.cos() * lon.sin()];
        assert!(dot(back, center) > 1.0 - 1e-12, "{t:?}: {info:?}");
        assert!(info.longitude > -180.0 && info.longitude <= 180.0);
        assert_eq!(info.pentagon, g.grid().is_pentagon(t));
        let (sea, mountain) = (g.config().terrain.sea_threshold, g.config().terrain.mountain_threshold);
        let h = info.elevation / max;
        match info.kind {
            TileKind::Sea => assert!(h < sea, "{t:?}: {h}"),
            TileKind::Land => assert!((sea..mountain).contains(&h), "{t:?}: {h}"),
            TileKind::Mountain => assert!(h >= mountain, "{t:?}: {h}"),
        }
    }
    let stranger = GlobeTile(g.grid().tile_count());
    assert_eq!(g.tile_info(stranger), None);
    assert_eq!(g.path(GlobeTile(0), stranger), None);
    assert!(g.reachable(stranger, 5).is_empty());
    assert!(g.field_of_view(stranger, 5).is_empty());
}

/// Möller-Trumbore, written here: where a ray from `o` along unit `d` meets triangle `a b c`.
fn meets(o: V, d: V, [a, b, c]: [V; 3]) -> Option<f64> {
    let (e1, e2) = (vec3::sub(b, a), vec3::sub(c, a));
    let p = vec3::cross(d, e2);
    let det = dot(e1, p);
    if det.abs() < 1e-15 {
        return None;
    }
    let s = vec3::sub(o, a);
    let u = dot(s, p) / det;
    let q = vec3::cross(s, e1);
    let v = dot(d, q) / det;
    (u >= 0.0 && v >= 0.0 && u + v <= 1.0).then(|| dot(e2, q) / det).filter(|&t| t >= 0.0)
}

#[test]
fn rays_hit_the_first_triangle_of_the_whole_mesh() {
    for (k, g) in [globe(3, 6, true, None), globe(5, 7, false, None)].iter().enumerate() {
        let mesh = g.generate_whole();
        let corner = |i: u32| mesh.buffers.positions[i as usize].map(f64::from);
        let triangles: Vec<[V; 3]> =
            mesh.buffers.indices.chunks(3).map(|t| [corner(t[0]), corner(t[1]), corner(t[2])]).collect();
        let r = g.radius();
        let top = r + f64::from(g.config().terrain.max_elevation);
        let dirs = picks(k as u64 + 300, 240, 10_000);
        let mut hits = 0;
        for w in dirs.chunks(4) {
            let unit = |a: u32, b: u32| {
                let (lat, lon) =
                    ((f64::from(a) / 10_000.0 - 0.5) * 3.1, f64::from(b) / 10_000.0 * std::f64::consts::TAU);
                [lat.cos() * lon.cos(), lat.sin(), -lat.cos() * lon.sin()]
            };
            // From far out toward a point of the shell, and from just above the surface along it.
            let (from, to) = (unit(w[0], w[1]), unit(w[2], w[3]));
            for (origin, target) in [
                (scale(from, 3.0 * r), scale(to, r + 0.5 * (top - r))),
                (scale(from, top + 0.01), scale(normalize([to[0] + from[0], to[1] + from[1], to[2] + from[2]]), r)),
            ] {
                let d = normalize(vec3::sub(target, origin));
                let expected = triangles.iter().filter_map(|&t| meets(origin, d, t)).fold(f64::INFINITY, f64::min);
                let hit = g.raycast(origin, d, f64::MAX);
                match hit {
                    Some(h) => {
                        hits += 1;
                        assert!((h.distance - expected).abs() < 1e-3 * r, "globe {k}: {} vs {expected}", h.distance);
                        let at = g.tile_at(h.point).unwrap();
                        assert!(
                            at == h.tile || g.grid().neighbors(at).unwrap().as_slice().contains(&h.tile),
                            "globe {k}: hit {:?} under {at:?}",
                            h.tile
                        );
                        // Short of the hit, nothing.
                        assert_eq!(g.raycast(origin, d, h.distance * 0.999), None);
                    }
                    None => assert!(expected.is_infinite(), "globe {k}: missed a hit at {expected}"),
                }
            }
        }
        assert!(hits > 100, "globe {k}: {hits} hits");
        // Away from the globe: no hit; a zero ray: none.
        assert_eq!(g.raycast([3.0 * r, 0.0, 0.0], [1.0, 0.0, 0.0], f64::MAX), None);
        assert_eq!(g.raycast([3.0 * r, 0.0, 0.0], [0.0, 0.0, 0.0], f64::MAX), None);
    }
}
