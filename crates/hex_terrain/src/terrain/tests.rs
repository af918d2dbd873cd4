use super::*;
use crate::chunk::ChunkCoord;
use crate::config::Shape;
use crate::config::{MapSize, Orientation};

fn terrain() -> Terrain {
    Terrain::new(MapConfig::default()).unwrap()
}

#[test]
fn tile_at_inverts_tile_center() {
    for o in [Orientation::Flat, Orientation::Pointy] {
        let mut c = MapConfig::default();
        c.layout.orientation = o;
        c.layout.hex_size = 2.5;
        let t = Terrain::new(c).unwrap();
        for tile in t.tiles() {
            let [x, _, z] = t.tile_center(tile).unwrap();
            assert_eq!(t.tile_at(x, z).unwrap(), tile);
            assert_eq!(t.tile_at(x + 1.0, z - 0.5).unwrap(), tile, "within the hex radius");
        }
    }
}

#[test]
fn offset_shifts_the_window_over_one_world() {
    let map0 = terrain();
    let c = MapConfig { offset: (30, 0), ..MapConfig::default() };
    let map1 = Terrain::new(c).unwrap();
    // Map1's first column is the world's column 30, which Map0 computes too.
    for row in 0..30 {
        let a = map0.tile_kind(map0.tile_from_offset([30, row])).unwrap();
        let b = map1.tile_kind(map1.tile_from_offset([0, row])).unwrap();
        assert_eq!(a, b);
    }
}

#[test]
fn bounds_and_chunks() {
    let t = terrain();
    assert!(t.contains(t.tile_from_offset([0, 0])));
    assert!(t.contains(t.tile_from_offset([29, 29])));
    assert!(!t.contains(t.tile_from_offset([30, 0])));
    assert!(!t.contains(t.tile_from_offset([0, -1])));
    assert_eq!(t.tiles().count(), 900);
    let chunks = t.chunks();
    assert_eq!(chunks.len(), 4); // 16x16 chunks over 30x30
    let total: usize = chunks.iter().map(|&c| t.chunk_rect(c).unwrap().len()).sum();
    assert_eq!(total, 900);
    assert!(t.chunk_rect(ChunkCoord::new(5, 0)).is_none());
    for tile in t.tiles() {
        assert!(t.chunk_rect(t.chunk_of(tile).unwrap()).unwrap().contains(t.offset_of(tile)));
    }
}

#[test]
fn island_has_sea_all_around() {
    let c = MapConfig { offset: (30, 0), shape: Shape::Island { a: 3.0, b: 6.0 }, ..MapConfig::default() };
    let t = Terrain::new(c).unwrap();
    let b = t.bounds().unwrap();
    for oc in b.iter() {
        let edge = oc[0] == 0 || oc[1] == 0 || oc[0] == b.max[0] - 1 || oc[1] == b.max[1] - 1;
        if edge {
            assert_eq!(t.tile_kind(t.tile_from_offset(oc)).unwrap(), TileKind::Sea, "{oc:?}");
        }
    }
}

#[test]
fn surface_height_matches_vertices_and_raycast_hits_it() {
    let t = terrain();
    for tile in t.tiles().step_by(37) {
        let [x, y, z] = t.tile_center(tile).unwrap();
        assert!((t.surface_height(x, z).unwrap() - y).abs() < 1e-3);
        let hit = t.raycast([x + 3.0, 50.0, z - 2.0], [-3.0, -(50.0 - y), 2.0], 200.0).unwrap();
        assert_eq!(hit.tile, tile, "ray aimed at the center of {tile:?}");
        assert!((hit.point[1] - y).abs() < 0.05);
    }
    assert!(t.raycast([0.0, 50.0, 0.0], [0.0, 1.0, 0.0], 100.0).is_none());
    assert!(t.raycast([0.0, 50.0, 0.0], [0.0, 0.0, 0.0], 100.0).is_none());
    assert!(t.raycast([f64::NAN, 50.0, 0.0], [0.0, -1.0, 0.0], 100.0).is_none());
}

#[test]
fn raycasts_end_whatever_their_length_and_the_hex_size() {
    // Tiny hexes: the march step (1/10,000 of a unit) is below an f32 ulp 2,000 units out.
    let mut config = MapConfig { size: MapSize::Unbounded, ..MapConfig::default() };
    config.layout.hex_size = 1e-4;
    config.terrain.max_elevation = 1.0;
    let t = Terrain::new(config).unwrap();
    // Horizontal just above the relief: never hits, and ends after the step cap.
    assert!(t.raycast([0.0, 1.5, 0.0], [1.0, 0.0, 0.0], f64::MAX).is_none());
    // From far above and far out (the world of 10^-4-unit hexes ends 2,516 units out), aimed
    // down: hits; past the world's edge: no surface, no hit.
    let hit = t.raycast([2000.0, 1e6, 2000.0], [0.0, -1.0, 0.0], f64::MAX).unwrap();
    assert!((hit.point[1] - t.surface_height(2000.0, 2000.0).unwrap()).abs() < 1e-3, "{hit:?}");
    assert!(t.raycast([3000.0, 1e6, 3000.0], [0.0, -1.0, 0.0], f64::MAX).is_none());
    assert!(t.surface_height(3000.0, 3000.0).is_none());
    // Going up from above every height: no hit at once.
    assert!(t.raycast([0.0, 2.0, 0.0], [0.1, 1.0, 0.0], f64::MAX).is_none());
}

#[test]
fn surface_normals_are_unit_upward_and_follow_the_slope() {
    let t = Terrain::new(MapConfig { size: MapSize::Bounded { x: 12, z: 10 }, ..MapConfig::default() }).unwrap();
    for (x, z) in [(0.3, 0.2), (5.1, 4.7), (10.0, 8.2), (3.3, 11.9)] {
        let n = t.surface_normal(x, z).unwrap();
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        assert!((len - 1.0).abs() < 1e-9 && n[1] > 0.0, "{n:?}");
        // Moving a little along the slope's downhill direction lowers the surface.
        let (dx, dz) = (n[0] * 1e-3, n[2] * 1e-3);
        if n[1] < 0.999 {
            assert!(t.surface_height(x + dx, z + dz).unwrap() <= t.surface_height(x, z).unwrap() + 1e-9);
        }
    }
    assert_eq!(t.surface_normal(1e300, 0.0), None);
}
