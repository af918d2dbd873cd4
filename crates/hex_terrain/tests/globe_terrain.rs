//! A globe's terrain, checked by computations written here: the whole mesh is a closed surface
//! (every edge in two triangles, once each way, Euler's formula, five triangles around each of
//! the 12 pentagon centers and six around every other point) with the counts of the formula;
//! faces and normals point outward; every chunk's vertices are the whole globe's, bit for bit;
//! every inner vertex lies in its tile kind's range; bad globe configs are refused by field.

use std::collections::HashMap;

use hex_terrain::{GlobeChunk, GlobeMesh, GlobeTerrain, MapConfig, MapSize, MapType, MapTypeConfig, Terrain, TileKind};
#[path = "common/vec3.rs"]
mod vec3;
use vec3::{V, cross, dot, normalize, sub};

fn globe(frequency: u32, inner_rings: u32, seed: u32, chunk: u32) -> GlobeTerrain {
    let mut config =
        MapConfig { seed, size: MapSize::Globe { frequency }, chunk_size: (chunk, chunk), ..Default::default() };
    config.terrain.inner_rings = inner_rings;
    config.terrain.max_elevation = 1.0;
    config.terrain.sea_threshold = 0.45;
    config.terrain.mountain_threshold = 0.58;
    GlobeTerrain::new(config).unwrap()
}

/// The same globe with a map type shaping its land.
fn typed(frequency: u32, inner_rings: u32, seed: u32, chunk: u32, kind: MapType) -> GlobeTerrain {
    let mut config = globe(frequency, inner_rings, seed, chunk).config().clone();
    config.map_type = Some(MapTypeConfig { kind, ..Default::default() });
    GlobeTerrain::new(config).unwrap()
}

/// A vertex's place, in f64, from the mesh's origin.
fn position(mesh: &GlobeMesh, v: usize) -> V {
    let p = mesh.buffers.positions[v];
    [mesh.origin[0] + f64::from(p[0]), mesh.origin[1] + f64::from(p[1]), mesh.origin[2] + f64::from(p[2])]
}

/// A mesh's triangles as their points' ids, the smallest first (the winding kept).
fn triangles(mesh: &GlobeMesh) -> Vec<[u64; 3]> {
    mesh.buffers
        .indices
        .chunks(3)
        .map(|t| {
            let ids = [0, 1, 2].map(|k| mesh.points[t[k] as usize].0);
            let k = (0..3).min_by_key(|&k| ids[k]).unwrap();
            [ids[k], ids[(k + 1) % 3], ids[(k + 2) % 3]]
        })
        .collect()
}

const CASES: [(u32, u32); 7] = [(1, 1), (2, 1), (3, 2), (4, 1), (5, 3), (7, 1), (11, 2)];

#[test]
fn the_whole_globe_is_a_closed_surface_with_the_formula_s_counts() {
    for (f, rings) in CASES {
        let g = globe(f, rings, 7, 4);
        let mesh = g.generate_whole();
        let b = &mesh.buffers;
        assert_eq!(b.positions.len() as u64, g.vertex_count(), "f = {f}, {rings} rings");
        assert_eq!((b.indices.len() / 3) as u64, g.triangle_count(), "f = {f}, {rings} rings");
        let mut points = mesh.points.clone();
        points.sort();
        points.dedup();
        assert_eq!(points.len(), mesh.points.len(), "a point twice");
        // Each directed edge once, and its reverse once: a closed, consistently wound surface.
        let mut directed: HashMap<(u32, u32), u32> = HashMap::new();
        let mut around = vec![0u32; b.positions.len()];
        let mut faces = vec![[0.0; 3]; b.positions.len()];
        for t in b.indices.chunks(3) {
            assert!(t[0] != t[1] && t[1] != t[2] && t[0] != t[2], "a degenerate triangle");
            for k in 0..3 {
                *directed.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
                around[t[k] as usize] += 1;
            }
            let [a, bb, c] = [0, 1, 2].map(|k| position(&mesh, t[k] as usize));
            let face = cross(sub(bb, a), sub(c, a));
            let middle = [(a[0] + bb[0] + c[0]) / 3.0, (a[1] + bb[1] + c[1]) / 3.0, (a[2] + bb[2] + c[2]) / 3.0];
            assert!(dot(face, middle) > 0.0, "f = {f}: a triangle faces inward");
            for &k in t {
                let s = &mut faces[k as usize];
                *s = [s[0] + face[0], s[1] + face[1], s[2] + face[2]];
            }
        }
        for (&(a, b2), &count) in &directed {
            assert_eq!(count, 1, "f = {f}: edge {a}-{b2} twice the same way");
            assert_eq!(directed.get(&(b2, a)), Some(&1), "f = {f}: edge {a}-{b2} on one triangle");
        }
        let (v, e, t) = (b.positions.len(), directed.len() / 2, b.indices.len() / 3);
        assert_eq!(v + t, e + 2, "f = {f}: Euler's formula");
        let fives = around.iter().filter(|&&k| k == 5).count();
        assert_eq!(fives, 12, "f = {f}: the pentagons' centers");
        assert!(around.iter().all(|&k| k == 5 || k == 6), "f = {f}: a point with {:?} triangles", around.iter().max());
        for (i, n) in b.normals.iter().enumerate() {
            let p = position(&mesh, i);
            let n = n.map(f64::from);
            assert!((dot(n, n) - 1.0).abs() < 1e-5 && dot(n, p) > 0.0, "f = {f}: normal {i} {n:?}");
            // The normal is the mean of the faces round its vertex, measured here from the
            // mesh's own triangles.
            assert!(dot(n, normalize(faces[i])) > 1.0 - 1e-6, "f = {f}: normal {i} {n:?}, faces {:?}", faces[i]);
        }
    }
}

#[test]
fn tiles_hold_six_or_five_times_n_squared_triangles_and_chunks_partition_them() {
    for (f, rings) in CASES {
        let g = globe(f, rings, 3, 3);
        let n = rings + 1;
        let mut seen = vec![0u32; g.grid().tile_count() as usize];
        for chunk in g.chunks() {
            let tiles = g.chunk_tiles(chunk);
            assert_eq!(tiles.iter().map(|&t| g.chunk_of(t)).collect::<Vec<_>>(), vec![Some(chunk); tiles.len()]);
            for &t in &tiles {
                seen[t.0 as usize] += 1;
            }
            let mesh = g.generate(chunk);
            let pentagons = tiles.iter().filter(|&&t| g.grid().is_pentagon(t)).count();
            let expected = 6 * n * n * (tiles.len() - pentagons) as u32 + 5 * n * n * pentagons as u32;
            assert_eq!(mesh.buffers.indices.len() as u32 / 3, expected, "f = {f}: {chunk:?}");
        }
        assert!(seen.iter().all(|&s| s == 1), "f = {f}: a tile in no chunk or in two");
        assert_eq!(g.chunks().first(), Some(&GlobeChunk::North));
    }
}

/// Every triangle of a chunk's mesh and of the whole mesh is named with the tile it lies in: the
/// grid's own `tile_at` of the triangle's centroid, each tile naming `6 n^2` triangles (a
/// pentagon `5 n^2`).
#[test]
fn each_triangle_is_named_with_the_tile_it_lies_in() {
    for (f, rings) in CASES {
        let g = globe(f, rings, 5, 3);
        let n = rings + 1;
        let meshes: Vec<GlobeMesh> =
            g.chunks().into_iter().map(|c| g.generate(c)).chain([g.generate_whole()]).collect();
        for mesh in &meshes {
            assert_eq!(mesh.triangle_tiles.len(), mesh.buffers.indices.len() / 3);
            let mut count: HashMap<u32, u32> = HashMap::new();
            for (k, (triangle, tile)) in mesh.buffers.indices.chunks(3).zip(&mesh.triangle_tiles).enumerate() {
                let c = triangle
                    .iter()
                    .map(|&v| position(mesh, v as usize))
                    .fold([0.0; 3], |a, p| [a[0] + p[0], a[1] + p[1], a[2] + p[2]]);
                assert_eq!(g.grid().tile_at(c), Some(*tile), "f = {f}, n = {n}: triangle {k}");
                *count.entry(tile.0).or_default() += 1;
            }
            assert!(mesh.tiles.iter().all(|t| count.contains_key(&t.0)), "f = {f}: a tile without triangles");
            for (&t, &c) in &count {
                let per = if g.grid().is_pentagon(hex_terrain::GlobeTile(t)) { 5 } else { 6 };
                assert_eq!(c, per * n * n, "f = {f}: tile {t}");
            }
        }
    }
}

#[test]
fn chunks_are_the_whole_globe_bit_for_bit() {
    for (f, rings, kind) in [(3, 1, None), (5, 2, None), (8, 1, None), (6, 2, Some(MapType::Pangaea))] {
        let g = match kind {
            Some(kind) => {
                // With a climate too: the vertex colors.
                let mut config = typed(f, rings, 11, 2, kind).config().clone();
                config.climate.enabled = true;
                GlobeTerrain::new(config).unwrap()
            }
            None => globe(f, rings, 11, 2),
        };
        let whole = g.generate_whole();
        let at: HashMap<_, _> = whole.points.iter().enumerate().map(|(i, &p)| (p, i)).collect();
        let mut copies = 0;
        for chunk in g.chunks() {
            let mesh = g.generate(chunk);
            for (v, p) in mesh.points.iter().enumerate() {
                let w = at[p];
                assert_eq!(mesh.heights[v].to_bits(), whole.heights[w].to_bits(), "f = {f}: height of {p:?}");
                assert_eq!(
                    mesh.buffers.normals[v].map(f32::to_bits),
                    whole.buffers.normals[w].map(f32::to_bits),
                    "f = {f}: normal of {p:?} in {chunk:?}"
                );
                assert_eq!(mesh.buffers.tile_kinds[v], whole.buffers.tile_kinds[w]);
                assert_eq!(mesh.buffers.colors.get(v), whole.buffers.colors.get(w), "f = {f}: color of {p:?}");
                assert_eq!(mesh.buffers.center_distances[v].to_bits(), whole.buffers.center_distances[w].to_bits());
                let (a, b) = (position(&mesh, v), position(&whole, w));
                // Both are the same f64 point rounded to f32 from their own origins.
                let tolerance = 4.0 * f64::from(f32::EPSILON) * (g.radius() + 2.0);
                assert!(sub(a, b).iter().all(|d| d.abs() <= tolerance), "f = {f}: {p:?} at {a:?} and {b:?}");
                copies += 1;
            }
            // The chunk's triangles are the whole's (same points, same winding).
            let mut mine = triangles(&mesh);
            mine.sort();
            let all: std::collections::HashSet<[u64; 3]> = triangles(&whole).into_iter().collect();
            assert!(mine.iter().all(|t| all.contains(t)), "f = {f}: {chunk:?} has a triangle the whole has not");
        }
        assert!(copies > whole.points.len(), "chunks share their border points");
        // With a climate, an inner vertex has its tile's biome color; without, no colors.
        if g.config().climate.enabled {
            assert_eq!(whole.buffers.colors.len(), whole.points.len());
            for (v, &c) in whole.buffers.colors.iter().enumerate() {
                if whole.buffers.center_distances[v] < 1.0 {
                    let p = position(&whole, v);
                    let tile = g.tile_at(p).unwrap();
                    let [r, gg, b] = g.ruleset().biome(g.tile_info(tile).unwrap().terrain.terrain).unwrap().color();
                    assert_eq!(c, [r, gg, b, 0], "f = {f}: inner vertex {v} of {tile:?}");
                }
            }
        } else {
            assert!(whole.buffers.colors.is_empty());
        }
    }
}

#[test]
fn every_inner_vertex_lies_in_its_tile_kind_s_range() {
    for seed in 0..6 {
        for (f, rings) in [(5, 1), (6, 2), (9, 3)] {
            // Every other globe with a map type's land.
            let kind = MapType::ALL[(seed as usize + f as usize) % MapType::ALL.len()];
            let g = if (seed + f) % 2 == 0 { globe(f, rings, seed, 4) } else { typed(f, rings, seed, 4, kind) };
            let mesh = g.generate_whole();
            let mut kinds = [0; 3];
            for (v, &h) in mesh.heights.iter().enumerate() {
                if mesh.buffers.center_distances[v] >= 1.0 {
                    continue;
                }
                let kind = [TileKind::Sea, TileKind::Land, TileKind::Mountain][mesh.buffers.tile_kinds[v] as usize];
                kinds[kind as usize] += 1;
                let (lo, hi) = g.thresholds().range(kind);
                assert!((lo..=hi).contains(&h), "seed {seed}, f = {f}: {kind:?} vertex at {h} outside [{lo}, {hi}]");
            }
            assert!(kinds.iter().filter(|&&k| k > 0).count() >= 2, "seed {seed}, f = {f}: one kind only, {kinds:?}");
        }
    }
}

#[test]
fn tile_kinds_follow_their_center_height() {
    let g = globe(9, 1, 5, 4);
    let t = g.thresholds();
    for tile in g.grid().tiles() {
        assert_eq!(g.tile_kind(tile), g.tile_height(tile).map(|h| t.classify(h)));
    }
    let share = g.sea_share();
    assert!(share > 0.0 && share < 1.0, "{share}");
    assert_eq!(g.tile_kind(hex_terrain::GlobeTile(g.grid().tile_count())), None);
}

#[test]
fn bad_globe_configs_are_refused_by_field() {
    let globe = |frequency| MapConfig { size: MapSize::Globe { frequency }, ..Default::default() };
    let refused = |config: MapConfig, field: &str| {
        let e = GlobeTerrain::new(config).unwrap_err();
        assert_eq!(e.field, field, "{e}");
    };
    refused(globe(0), "size.Globe.frequency");
    refused(globe(257), "size.Globe.frequency");
    let mut big = globe(256);
    big.terrain.inner_rings = 16;
    refused(big, "size.Globe.frequency");
    refused(MapConfig { wrap: true, ..globe(8) }, "wrap");
    let mut rivers = globe(8);
    rivers.rivers.enabled = true;
    refused(rivers, "rivers.enabled");
    let mut climate = globe(8);
    climate.climate.enabled = true;
    climate.climate.latitudes = (0.6, -0.6);
    refused(climate.clone(), "climate.latitudes");
    climate.climate.latitudes = (1.0, -1.0);
    climate.climate.winds = Some(Default::default());
    refused(climate.clone(), "climate.winds");
    climate.climate.winds = None;
    assert!(GlobeTerrain::new(climate).is_ok(), "a globe with a climate");
    refused(MapConfig { size: MapSize::Unbounded, ..Default::default() }, "size");
    // A flat map's compiler refuses a globe by name too.
    assert_eq!(Terrain::new(globe(8)).unwrap_err().field, "size");
    // And a globe config goes through RON.
    let text = ron::to_string(&globe(21)).unwrap();
    assert!(text.contains("Globe(frequency:21)"), "{text}");
    assert_eq!(ron::from_str::<MapConfig>(&text).unwrap().size, MapSize::Globe { frequency: 21 });
}

#[test]
fn chunks_within_an_angle_hold_every_point_that_close_and_no_far_chunk() {
    let g = globe(9, 1, 2, 3);
    let whole = g.generate_whole();
    // Each chunk's points, as directions, recomputed from the meshes.
    let chunks: Vec<(GlobeChunk, Vec<V>)> = g
        .chunks()
        .into_iter()
        .map(|c| {
            let m = g.generate(c);
            let dirs = (0..m.points.len())
                .map(|v| {
                    let p = position(&m, v);
                    let l = dot(p, p).sqrt();
                    p.map(|x| x / l)
                })
                .collect();
            (c, dirs)
        })
        .collect();
    assert!(!whole.points.is_empty());
    let mut state = 12345u64;
    let mut next = || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..60 {
        let dir = [next() - 0.5, next() - 0.5, next() - 0.5];
        let l = dot(dir, dir).sqrt();
        let dir = dir.map(|x| x / l);
        let angle = next() * 0.8;
        let found = g.chunks_within(dir, angle);
        let arc = |p: V| dot(p, dir).clamp(-1.0, 1.0).acos();
        for (chunk, points) in &chunks {
            let nearest = points.iter().map(|&p| arc(p)).fold(f64::INFINITY, f64::min);
            // Points within the angle (up to rounding of the f32 positions): their chunk is found.
            if nearest < angle - 1e-5 {
                assert!(found.contains(chunk), "{chunk:?} has a point {nearest} away, within {angle}");
            }
            // A found chunk reaches within the angle and its own diameter.
            let farthest = points.iter().map(|&p| arc(p)).fold(0.0, f64::max);
            if found.contains(chunk) {
                assert!(nearest <= angle + (farthest - nearest) + 1e-5, "{chunk:?} found from {nearest} away");
            }
        }
        assert_eq!(g.chunk_at(dir), g.tile_at(dir).and_then(|t| g.chunk_of(t)));
        assert!(g.chunk_at(dir).is_some_and(|c| found.contains(&c) || angle < 1e-9));
    }
    assert!(g.chunks_within([0.0; 3], 1.0).is_empty());
    assert!(g.chunks_within([0.0, 1.0, 0.0], -1.0).is_empty());
    assert_eq!(g.chunks_within([0.0, 1.0, 0.0], 4.0), g.chunks());
}

/// A mesh's directed edges as their points' ids.
fn directed_edges(mesh: &GlobeMesh) -> HashMap<(u64, u64), u32> {
    let mut out = HashMap::new();
    for t in mesh.buffers.indices.chunks(3) {
        for k in 0..3 {
            let (a, b) = (mesh.points[t[k] as usize].0, mesh.points[t[(k + 1) % 3] as usize].0);
            *out.entry((a, b)).or_default() += 1;
        }
    }
    out
}

/// The far level of detail: the whole globe's coarse mesh is a closed, outward surface of six
/// triangles a hexagon and five a pentagon, each named with the tile it lies in; every vertex it
/// keeps is the full mesh's, bit for bit; a coarse chunk's outline is its full mesh's, edge for
/// edge (so any two levels meet without a crack), and inside it the tiles are the whole coarse
/// mesh's; props moved onto a coarse chunk lie on a triangle of their tile.
#[test]
fn coarse_meshes_are_closed_fans_with_the_full_meshes_outline() {
    for (f, rings) in CASES {
        let g = globe(f, rings, 9, 3);
        let full = g.generate_whole();
        let coarse = full.coarse();
        let b = &coarse.buffers;
        let tiles = g.grid().tile_count() as usize;
        assert_eq!(b.indices.len() / 3, 6 * tiles - 12, "f = {f}: six triangles a hexagon, five a pentagon");
        let directed = directed_edges(&coarse);
        for (&(a, c), &count) in &directed {
            assert_eq!(count, 1, "f = {f}: edge {a}-{c} twice the same way");
            assert_eq!(directed.get(&(c, a)), Some(&1), "f = {f}: edge {a}-{c} on one triangle");
        }
        assert_eq!(b.positions.len() + b.indices.len() / 3, directed.len() / 2 + 2, "f = {f}: Euler's formula");
        let full_vertex: HashMap<u64, usize> = full.points.iter().enumerate().map(|(i, p)| (p.0, i)).collect();
        for (i, p) in coarse.points.iter().enumerate() {
            let j = full_vertex[&p.0];
            assert_eq!(b.positions[i].map(f32::to_bits), full.buffers.positions[j].map(f32::to_bits));
            assert_eq!(b.normals[i].map(f32::to_bits), full.buffers.normals[j].map(f32::to_bits));
            assert_eq!(b.center_distances[i].to_bits(), full.buffers.center_distances[j].to_bits());
        }
        for (k, (t, tile)) in b.indices.chunks(3).zip(&coarse.triangle_tiles).enumerate() {
            let [a, bb, c] = [0, 1, 2].map(|i| position(&coarse, t[i] as usize));
            let face = cross(sub(bb, a), sub(c, a));
            let middle = [0, 1, 2].map(|i| (a[i] + bb[i] + c[i]) / 3.0);
            assert!(dot(face, middle) > 0.0, "f = {f}: coarse triangle {k} faces inward");
            assert_eq!(b.center_distances[t[0] as usize], 0.0, "f = {f}: coarse triangle {k} starts off its center");
            assert_eq!(g.grid().tile_at(middle), Some(*tile), "f = {f}: coarse triangle {k}");
        }
        // Chunk by chunk: the outline kept, the inner tiles the whole coarse mesh's.
        let whole: std::collections::HashSet<[u64; 3]> = triangles(&coarse).into_iter().collect();
        for chunk in g.chunks() {
            let mesh = g.generate(chunk);
            let small = mesh.coarse();
            let outline = |m: &GlobeMesh| {
                let d = directed_edges(m);
                let mut o: Vec<(u64, u64)> = d.keys().filter(|&&(a, c)| !d.contains_key(&(c, a))).copied().collect();
                o.sort_unstable();
                o
            };
            assert_eq!(outline(&small), outline(&mesh), "f = {f}: {chunk:?}'s outline");
            let inner: Vec<hex_terrain::GlobeTile> = mesh
                .tiles
                .iter()
                .copied()
                .filter(|&t| g.grid().neighbors(t).unwrap().as_slice().iter().all(|&nb| g.chunk_of(nb) == Some(chunk)))
                .collect();
            for (tri, tile) in triangles(&small).into_iter().zip(&small.triangle_tiles) {
                if inner.contains(tile) {
                    assert!(whole.contains(&tri), "f = {f}: {chunk:?}: a triangle of {tile:?} not the whole mesh's");
                }
            }
            assert!(small.buffers.indices.len() <= mesh.buffers.indices.len());
            // Props from the full mesh, stood on the coarse one: on a triangle of their tile.
            let mut props = g.props(&mesh, usize::MAX, 1.0);
            small.stand_on(&mut props);
            for p in &props {
                let at = [0, 1, 2].map(|k| small.origin[k] + f64::from(p.position[k]));
                let on = small.buffers.indices.chunks(3).zip(&small.triangle_tiles).any(|(t, &tile)| {
                    let [a, bb, c] = [0, 1, 2].map(|i| position(&small, t[i] as usize));
                    let n = normalize(cross(sub(bb, a), sub(c, a)));
                    let inside =
                        [(a, bb), (bb, c), (c, a)].iter().all(|&(u, v)| dot(cross(sub(v, u), sub(at, u)), n) > -1e-4);
                    tile == p.tile && dot(sub(at, a), n).abs() < 1e-4 && inside
                });
                assert!(on, "f = {f}: a prop of {:?} off its tile's coarse triangles", p.tile);
            }
        }
    }
}
