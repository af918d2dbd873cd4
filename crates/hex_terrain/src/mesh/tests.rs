use std::collections::HashSet;

use hexx::Hex;

use super::grid::AROUND;
use super::normals::NormalCoefficients;
use super::*;
use crate::config::{MapConfig, MapSize, Orientation};
use crate::terrain::Terrain;

fn boundary_edges(t: &Terrain, rect: TileRect) -> usize {
    let tiles: HashSet<Hex> = rect.iter().map(|oc| t.tile_from_offset(oc)).collect();
    tiles.iter().map(|h| h.all_neighbors().iter().filter(|n| !tiles.contains(n)).count()).sum()
}

#[test]
fn counts_follow_the_formula() {
    for rings in [1, 2, 3] {
        for (x, z) in [(1, 1), (2, 2), (6, 6), (10, 6), (7, 3)] {
            for o in [Orientation::Flat, Orientation::Pointy] {
                let mut c = MapConfig { size: MapSize::Bounded { x, z }, ..MapConfig::default() };
                c.terrain.inner_rings = rings;
                c.layout.orientation = o;
                let t = Terrain::new(c).unwrap();
                let m = t.generate_map().unwrap();
                let rect = t.bounds().unwrap();
                let tiles = (x * z) as usize;
                let expected = t.lattice().mesh_vertex_count(tiles, boundary_edges(&t, rect));
                assert_eq!(m.buffers.vertex_count(), expected, "{x}x{z} rings {rings} {o:?}");
                assert_eq!(m.buffers.triangle_count(), tiles * t.lattice().triangles_per_tile());
                assert_eq!(m.tiles.len(), tiles);
            }
        }
    }
}

#[test]
fn buffers_are_consistent() {
    let t = Terrain::new(MapConfig::default()).unwrap();
    let m = t.generate_map().unwrap();
    let b = &m.buffers;
    let v = b.vertex_count();
    assert_eq!(b.normals.len(), v);
    assert_eq!(b.uvs.len(), v);
    assert_eq!(b.tile_kinds.len(), v);
    assert_eq!(b.center_distances.len(), v);
    assert!(b.indices.iter().all(|&i| (i as usize) < v));
    for n in &b.normals {
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        assert!((len - 1.0).abs() < 1e-5 && n[1] > 0.0);
    }
    for tri in b.indices.chunks(3) {
        let p = [b.positions[tri[0] as usize], b.positions[tri[1] as usize], b.positions[tri[2] as usize]];
        let u = [p[1][0] - p[0][0], p[1][2] - p[0][2]];
        let w = [p[2][0] - p[0][0], p[2][2] - p[0][2]];
        assert!(u[1] * w[0] - u[0] * w[1] > 0.0, "every face is wound counter-clockwise seen from above");
    }
    let used: HashSet<u32> = b.indices.iter().copied().collect();
    assert_eq!(used.len(), v, "no vertex is left out of the triangles");
    let m = t.generate(t.bounds().unwrap(), GenerateOptions::DIAGNOSTICS);
    let unique: HashSet<Hex> = m.diagnostics.unwrap().lattice.iter().copied().collect();
    assert_eq!(unique.len(), v, "shared vertices exist once");
}

/// The batched generator and the one-vertex evaluator (`Terrain::vertex`, which finds the tiles
/// around a point from scratch) agree on every vertex, on map edges and chunk edges too.
#[test]
fn every_vertex_matches_the_single_vertex_evaluator() {
    use crate::config::Shape;
    for rings in [1, 2, 4] {
        for o in [Orientation::Flat, Orientation::Pointy] {
            for (shape, water) in [(Shape::None, false), (Shape::Island { a: 3.0, b: 2.2 }, false), (Shape::None, true)]
            {
                let mut c =
                    MapConfig { size: MapSize::Bounded { x: 9, z: 7 }, shape: shape.clone(), ..MapConfig::default() };
                // Climate and rivers: low thresholds so this small map has rivers and lakes.
                c.climate.enabled = water;
                c.rivers.enabled = water;
                c.rivers.threshold = 1.5;
                c.terrain.inner_rings = rings;
                c.layout.orientation = o;
                c.seed = 11 + rings;
                let t = Terrain::new(c).unwrap();
                let max = t.config().terrain.max_elevation;
                for rect in [t.bounds().unwrap(), TileRect::new([2, 1], [6, 5]), TileRect::new([7, 0], [9, 3])] {
                    let m = t.generate(rect, GenerateOptions::DIAGNOSTICS);
                    let d = m.diagnostics.as_ref().unwrap();
                    for (i, &p) in d.lattice.iter().enumerate() {
                        let s = t.vertex(p).unwrap();
                        let what = format!("{p:?} rings {rings} {o:?} {shape:?} rect {rect:?}");
                        assert_eq!(d.raw_heights[i].to_bits(), s.raw.to_bits(), "raw {what}");
                        assert_eq!(m.buffers.positions[i][1].to_bits(), (s.height * max).to_bits(), "height {what}");
                        assert_eq!(m.buffers.tile_kinds[i], s.kind as u32, "kind {what}");
                        assert_eq!(d.moved[i], s.moved, "moved {what}");
                        assert_eq!(u32::from(d.rings[i]), s.ring, "ring {what}");
                        if water {
                            assert_eq!(m.buffers.colors[i], t.point_color(p).unwrap(), "color {what}");
                        }
                    }
                    if water && rect == t.bounds().unwrap() {
                        assert!(t.rivers().len() > 1, "the water case has rivers");
                        assert!(m.buffers.colors.iter().any(|c| c[3] > 0), "some vertex is wet");
                    } else if !water {
                        assert!(m.buffers.colors.is_empty());
                    }
                    for info in &m.tiles {
                        assert_eq!(*info, t.tile_info(info.hex).unwrap());
                    }
                }
            }
        }
    }
}

/// Every normal is the one of the six lattice neighbors' heights, looked up by coordinate (the
/// generator finds them by index arithmetic).
#[test]
fn normals_come_from_the_six_lattice_neighbors() {
    use std::collections::HashMap;
    for rings in [1, 3] {
        for o in [Orientation::Flat, Orientation::Pointy] {
            let mut c = MapConfig { size: MapSize::Bounded { x: 7, z: 5 }, ..MapConfig::default() };
            // With rivers carved, so the normals follow the channels too.
            c.rivers.enabled = true;
            c.rivers.threshold = 1.5;
            c.terrain.inner_rings = rings;
            c.layout.orientation = o;
            let t = Terrain::new(c).unwrap();
            let max = t.config().terrain.max_elevation;
            let m = t.generate(TileRect::new([1, 1], [6, 4]), GenerateOptions::DIAGNOSTICS);
            let lattice = &m.diagnostics.as_ref().unwrap().lattice;
            let at: HashMap<Hex, f32> = lattice.iter().zip(&m.buffers.positions).map(|(&p, pos)| (p, pos[1])).collect();
            let height = |p: Hex| at.get(&p).copied().unwrap_or_else(|| t.vertex(p).unwrap().height * max);
            let (a, b) = t.lattice().steps();
            let around = AROUND.map(|d| {
                let (i, j) = (f64::from(d.x), f64::from(d.y));
                [(i * a[0] + j * b[0]) as f32, (i * a[1] + j * b[1]) as f32]
            });
            let coefficients = NormalCoefficients::new(&around);
            for (i, &p) in lattice.iter().enumerate() {
                let expected = coefficients.normal(height(p), |d| height(p + AROUND[d]));
                assert_eq!(m.buffers.normals[i], expected, "{p:?} rings {rings} {o:?}");
            }
        }
    }
}

#[test]
fn vertex_colors_do_not_depend_on_the_order_of_the_tiles() {
    let a = [crate::Biome::Forest, crate::Biome::Desert, crate::Biome::Coast];
    let b = [crate::Biome::Coast, crate::Biome::Forest, crate::Biome::Desert];
    assert_eq!(vertex_color(&a, 0.3), vertex_color(&b, 0.3));
    assert_eq!(vertex_color(&[crate::Biome::Snow], 1.0), [238, 242, 246, 255]);
}

/// Manipulation of a batch compiled for every kernel this CPU runs gives each point the bits of
/// the one-vertex chain, for every manipulation config, at every batch length (the vector part
/// and the tail).
#[test]
fn every_kernel_manipulates_as_one_vertex() {
    use super::lanes;
    use crate::config::PullMode;
    use crate::heights::Kernel;
    use crate::kind::TileKind;
    use crate::vertex::VertexRules;
    let h = |seed: u32, i: usize| crate::hash::hash(seed, &[i as i64]);
    for (c, (hex_unity, edge_correction, interpolation, pull)) in [
        (true, true, true, PullMode::Clamp),
        (true, true, true, PullMode::Thesis),
        (false, true, true, PullMode::Clamp),
        (true, false, false, PullMode::Thesis),
        (false, false, false, PullMode::Clamp),
    ]
    .into_iter()
    .enumerate()
    {
        let mut config = MapConfig::default();
        config.terrain.inner_rings = 2;
        config.manipulation.hex_unity = hex_unity;
        config.manipulation.edge_correction = edge_correction;
        config.manipulation.interpolation = interpolation;
        config.manipulation.pull = pull;
        let t = Terrain::new(config).unwrap();
        let rules: &VertexRules = t.pipeline().vertex_rules();
        let n = t.lattice().subdivisions();
        for len in [0, 1, 15, 16, 17, 40, 1024] {
            let kind = |v: u64| TileKind::ALL[(v % 3) as usize];
            let raws: Vec<f32> = (0..len).map(|i| crate::hash::unit(h(c as u32, i)) * 1.2 - 0.1).collect();
            let rings: Vec<u32> = (0..len).map(|i| (h(50 + c as u32, i) % u64::from(n + 1)) as u32).collect();
            let spans: Vec<(TileKind, TileKind)> = (0..len)
                .map(|i| {
                    let (a, b) = (kind(h(90, i)), kind(h(91, i)));
                    // An inner vertex has one tile.
                    if rings[i] < n { (a, a) } else { (a.min(b), a.max(b)) }
                })
                .collect();
            let (los, his): (Vec<TileKind>, Vec<TileKind>) = spans.iter().copied().unzip();
            let expected: Vec<_> = (0..len)
                .map(|i| {
                    let m = rules.manipulated(raws[i], rings[i], Some(spans[i]));
                    (m.height.to_bits(), m.moved)
                })
                .collect();
            for kernel in Kernel::ALL.into_iter().filter(|k| k.is_supported()) {
                let (mut heights, mut moved) = (vec![f32::NAN; len], vec![true; len]);
                lanes::run(
                    kernel,
                    #[inline(always)]
                    || rules.manipulated_many((&raws, &rings), (&los, &his), &mut heights, &mut moved),
                );
                for (i, want) in expected.iter().enumerate() {
                    assert_eq!((heights[i].to_bits(), moved[i]), *want, "{kernel:?} config {c} point {i}");
                }
            }
        }
    }
}

/// The noise a side thread samples while the points are enumerated, however many tiles it got
/// to, leaves the mesh the same bits: every tile sampled early against none, over random maps
/// (each orientation, 1-4 inner rings, bounded, wrapping or unbounded, with or without climate
/// and rivers) and random rectangles of them (negative coordinates on an unbounded world).
mod early_noise {
    use proptest::prelude::*;

    use super::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]
        #[test]
        fn changes_no_bit(
            pointy in any::<bool>(),
            world in 0..3_u8,
            rings in 1..=4_u32,
            climate in any::<bool>(),
            seed in any::<u32>(),
            (x, z) in (2..=12_u32, 1..=10_u32),
            (c0, r0, w, h) in (-8..=12_i32, -8..=10_i32, 1..=14_u32, 1..=12_u32),
        ) {
            let size = if world == 2 { MapSize::Unbounded } else { MapSize::Bounded { x: 2 * x, z } };
            let mut c = MapConfig { seed, size, wrap: world == 1, ..MapConfig::default() };
            c.layout.orientation = if pointy { Orientation::Pointy } else { Orientation::Flat };
            c.terrain.inner_rings = rings;
            (c.climate.enabled, c.rivers.enabled) = (climate && world != 2, climate && world != 2);
            let t = Terrain::new(c).unwrap();
            let rect = TileRect::new([c0, r0], [w, h]);
            let run = |all: bool| {
                let job = job::Job::new(t.pipeline(), rect, GenerateOptions::DIAGNOSTICS);
                let tiles = job.tiles.len();
                let (points, buffers, kinds, _) = job.prelude();
                let early = if all { job.early_noise(|| false) } else { early::Early::default() };
                assert_eq!(early.tiles, if all { tiles } else { 0 });
                job.passes(points, buffers, kinds, &early)
            };
            prop_assert_eq!(run(true), run(false));
        }
    }
}
