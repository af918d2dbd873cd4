use hexx::{HexLayout, Vec2};

use super::*;
use crate::terrain::hex_orientation;

fn lattices() -> Vec<Lattice> {
    let mut out = Vec::new();
    for n in 1..=6 {
        for o in [Orientation::Flat, Orientation::Pointy] {
            out.push(Lattice::new(n, o, 1.5));
        }
    }
    out
}

#[test]
fn template_counts_follow_formula() {
    for l in lattices() {
        let n = l.subdivisions() as usize;
        assert_eq!(l.template().len(), 1 + 3 * n * (n + 1));
        assert_eq!(l.points_per_tile(), l.template().len());
        assert_eq!(l.template_triangles().len(), 6 * n * n);
        assert_eq!(l.triangles_per_tile(), 6 * n * n);
        for k in 0..=n as u32 {
            let count = l.template().iter().filter(|p| p.ring == k).count();
            assert_eq!(count, if k == 0 { 1 } else { 6 * k as usize });
        }
    }
}

#[test]
fn tile_centers_match_hexx_layout() {
    for l in lattices() {
        let layout =
            HexLayout { orientation: hex_orientation(l.orientation()), origin: Vec2::ZERO, scale: Vec2::splat(1.5) };
        for q in -7..7 {
            for r in -7..7 {
                let tile = Hex::new(q, r);
                let [x, z] = l.world(l.tile_center(tile));
                let expected = layout.hex_to_world_pos(tile);
                assert!((x as f32 - expected.x).abs() < 1e-4 && (z as f32 - expected.y).abs() < 1e-4, "{tile:?}");
                // and back: the center's tile is the tile itself
                let set = l.tiles_at(l.tile_center(tile));
                assert_eq!(set.tiles(), &[tile]);
                assert_eq!(set.ring, 0);
            }
        }
    }
}

#[test]
fn points_belong_to_one_two_or_three_tiles() {
    for l in lattices() {
        let n = l.subdivisions();
        let tile = Hex::new(3, -2);
        let c = l.tile_center(tile);
        for tp in l.template() {
            let set = l.tiles_at(c + tp.offset);
            assert!(set.tiles().contains(&tile));
            assert_eq!(set.ring, tp.ring);
            let corner = tp.ring == n && tp.offset.x % n as i32 == 0 && tp.offset.y % n as i32 == 0;
            let expected = if tp.ring < n {
                1
            } else if corner {
                3
            } else {
                2
            };
            assert_eq!(set.tiles().len(), expected, "{tp:?} n={n}");
            for &t in set.tiles() {
                assert!((c + tp.offset).distance_to(l.tile_center(t)) <= n as i32);
            }
        }
    }
}

#[test]
fn triangles_face_up_and_stay_in_the_tile() {
    for l in lattices() {
        for tri in l.template_triangles() {
            let p = tri.map(|h| l.world(h));
            let u = [p[1][0] - p[0][0], p[1][1] - p[0][1]];
            let v = [p[2][0] - p[0][0], p[2][1] - p[0][1]];
            // y of (u.x, 0, u.z) x (v.x, 0, v.z)
            let up = u[1] * v[0] - u[0] * v[1];
            assert!(up > 0.0, "triangle {tri:?} faces down");
            assert!(tri.iter().all(|h| h.ulength() <= l.subdivisions()));
        }
    }
}

#[test]
fn triangle_at_reproduces_the_point() {
    let l = Lattice::new(3, Orientation::Pointy, 2.0);
    for k in 0..200 {
        let (x, z) = (f64::from(k) * 0.731 - 70.0, f64::from(k) * -0.377 + 20.0);
        let (tri, w) = l.triangle_at(x, z);
        assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-9);
        assert!(w.iter().all(|&w| (-1e-9..=1.0 + 1e-9).contains(&w)));
        let px: f64 = tri.iter().zip(w).map(|(&h, w)| l.world(h)[0] * w).sum();
        let pz: f64 = tri.iter().zip(w).map(|(&h, w)| l.world(h)[1] * w).sum();
        assert!((px - x).abs() < 1e-9 && (pz - z).abs() < 1e-9);
    }
}

/// The tiles sharing each border point of a template, found once for the origin tile, are the
/// tiles `tiles_at` finds for the same point of any tile.
#[test]
fn shared_tiles_are_the_tiles_at_every_template_point() {
    for n in [1, 2, 3, 5] {
        for o in [Orientation::Flat, Orientation::Pointy] {
            let l = Lattice::new(n, o, 1.5);
            for tile in [Hex::ZERO, Hex::new(3, -2), Hex::new(-7, 11), Hex::new(1000, -4000)] {
                for (k, tp) in l.template().iter().enumerate() {
                    let mut expected: Vec<Hex> = l.tiles_at(l.tile_center(tile) + tp.offset).tiles().to_vec();
                    let mut found = vec![tile];
                    for d in l.shared_tiles(k) {
                        if d != u8::MAX {
                            found.push(tile.all_neighbors()[usize::from(d)]);
                        }
                    }
                    expected.sort_by_key(|h| (h.x, h.y));
                    found.sort_by_key(|h| (h.x, h.y));
                    assert_eq!(found, expected, "n {n} {o:?} tile {tile:?} point {k}");
                    assert_eq!(found.len() > 1, tp.ring == n, "only border points are shared");
                }
            }
        }
    }
}

/// The tiles around each template point's neighbors, found once for the origin tile, are the
/// tiles `tiles_at` finds for the same neighbor of any tile, with the same ring.
#[test]
fn around_tiles_are_the_tiles_at_every_neighbor() {
    for n in [1, 2, 4] {
        for o in [Orientation::Flat, Orientation::Pointy] {
            let l = Lattice::new(n, o, 1.5);
            for tile in [Hex::ZERO, Hex::new(-3, 5), Hex::new(-900, -2000), Hex::new(4000, 17)] {
                for (k, tp) in l.template().iter().enumerate() {
                    for (d, &step) in NEIGHBORS.iter().enumerate() {
                        let truth = l.tiles_at(l.tile_center(tile) + tp.offset + step);
                        let table = l.around_tiles(k, d);
                        let mut expected = truth.tiles().to_vec();
                        let mut found: Vec<Hex> = table.tiles().iter().map(|&t| tile + t).collect();
                        expected.sort_by_key(|h| (h.x, h.y));
                        found.sort_by_key(|h| (h.x, h.y));
                        assert_eq!(found, expected, "n {n} {o:?} tile {tile:?} point {k} direction {d}");
                        assert_eq!(table.ring, truth.ring, "n {n} {o:?} tile {tile:?} point {k} direction {d}");
                    }
                }
            }
        }
    }
}
