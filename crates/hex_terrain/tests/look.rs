//! The look's data, property-tested over random configs: the water surface covers exactly the
//! sea floor below sea level and is the same cut into chunks; props are deterministic, stand on
//! the surface of their tile type, respect the cap and do not depend on the chunking.

use std::collections::HashMap;

use hex_terrain::{
    ChunkCoord, ChunkMesh, Detail, GenerateOptions, MapConfig, MapSize, Orientation, PropKind, ReliefConfig,
    RiverConfig, Shape, Terrain, TileKind, WaterBuffers,
};
use proptest::prelude::*;

#[path = "common/biome.rs"]
mod biome;
mod common;

prop_compose! {
    fn config()(
        seed in any::<u32>(),
        size in (4u32..28, 4u32..24),
        rings in 1u32..4,
        pointy in any::<bool>(),
        shape in prop_oneof![Just(Shape::None), (0.5f32..5.0, 0.5f32..8.0).prop_map(|(a, b)| Shape::Island { a, b })],
        relief in prop::option::of((0.0f32..=1.0, 0.0f32..=1.0, 0.0f32..=1.0)),
        climate in any::<bool>(),
        rivers in any::<bool>(),
        wrap in any::<bool>(),
        chunk in (3u32..9, 3u32..9),
        scale in 4.0f64..40.0,
    ) -> MapConfig {
        let mut c = MapConfig { seed, size: MapSize::Bounded { x: size.0, z: size.1 }, shape, chunk_size: chunk, ..MapConfig::default() };
        c.terrain.inner_rings = rings;
        c.noise.scale = scale;
        c.layout.orientation = if pointy { Orientation::Pointy } else { Orientation::Flat };
        if let Some((peaks, ridges, hills)) = relief {
            c.relief = ReliefConfig { peaks, ridges, hills };
        }
        c.climate.enabled = climate;
        if rivers {
            c.rivers = RiverConfig { enabled: true, threshold: 3.0, ..RiverConfig::default() };
        }
        common::wrapping(c, wrap)
    }
}

/// A triangle of a water mesh in world space, as exact bits: corners sorted, each corner its
/// world `(x, z)` rounded to 1e-4 and its height and depth bits.
type Triangle = [(i64, i64, u32, u32); 3];

fn triangles(water: &WaterBuffers, origin: [f64; 3]) -> Vec<Triangle> {
    water
        .indices
        .chunks_exact(3)
        .map(|t| {
            let mut corners = [0, 1, 2].map(|k| {
                let i = t[k] as usize;
                let [x, y, z] = water.positions[i];
                let q = |v: f64| (v * 1e4).round() as i64;
                (q(origin[0] + f64::from(x)), q(origin[2] + f64::from(z)), y.to_bits(), water.depths[i].to_bits())
            });
            corners.sort_unstable();
            corners
        })
        .collect()
}

fn chunk_meshes(t: &Terrain) -> Vec<(ChunkCoord, ChunkMesh)> {
    t.chunks().into_iter().filter_map(|c| t.generate_chunk(c).map(|m| (c, m))).collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// The water surface cut into chunks is the whole map's, triangle for triangle; its sea
    /// part sits at sea level with depth = sea level - floor at every vertex (so the
    /// interpolated depth is 0 exactly on the coastline); every lattice triangle with a corner
    /// under sea level is under water.
    #[test]
    fn water_is_chunk_independent_and_covers_the_sea(config in config()) {
        let t = Terrain::new(config).unwrap();
        let whole = t.generate_map().unwrap();
        let water = t.water_surface(&whole, 0.1);
        let mut expected = triangles(&water, whole.origin);
        let mut chunked: Vec<Triangle> = chunk_meshes(&t)
            .iter()
            .flat_map(|(_, m)| triangles(&t.water_surface(m, 0.1), m.origin))
            .collect();
        expected.sort_unstable();
        chunked.sort_unstable();
        prop_assert_eq!(expected.len(), chunked.len());
        prop_assert!(expected == chunked, "chunked water differs from the whole map's");

        let sea = t.sea_level();
        let b = &whole.buffers;
        let mut under = 0;
        for tri in b.indices.chunks_exact(3) {
            if tri.iter().any(|&i| b.positions[i as usize][1] < sea) {
                under += 1;
            }
        }
        let flat = water.indices.chunks_exact(3).filter(|t| t.iter().all(|&i| water.positions[i as usize][1] == sea)).count();
        prop_assert!(flat >= under, "{} sea triangles for {} triangles under sea level", flat, under);
        // At a sea vertex, depth is exactly sea level minus the floor below it.
        let floor: HashMap<(u32, u32), f32> = b.positions.iter().map(|p| ((p[0].to_bits(), p[2].to_bits()), p[1])).collect();
        for (p, d) in water.positions.iter().zip(&water.depths) {
            if p[1] == sea && *d != 0.0 {
                let y = floor[&(p[0].to_bits(), p[2].to_bits())];
                prop_assert_eq!(*d, sea - y);
            }
        }
    }

    /// Props: the same map gives the same props; each chunk's props are the whole map's props
    /// of its tiles; every prop stands on the surface, above the sea, on a tile whose type
    /// grows it; the cap holds.
    #[test]
    fn props_are_deterministic_on_the_surface_and_capped(config in config(), cap in 1usize..60) {
        let t = Terrain::new(config.clone()).unwrap();
        let again = Terrain::new(config).unwrap();
        let whole = t.generate_map().unwrap();
        let all = t.props(&whole, usize::MAX, 1.0);
        prop_assert_eq!(&all, &again.props(&again.generate_map().unwrap(), usize::MAX, 1.0));
        // The whole map's props by tile, in world coordinates.
        let world = |o: [f64; 3], p: [f32; 3]| (o[0] + f64::from(p[0]), o[2] + f64::from(p[2]));
        let mut by_tile: HashMap<_, Vec<_>> = HashMap::new();
        for p in &all {
            by_tile.entry(p.tile).or_default().push((world(whole.origin, p.position), p.kind, p.variant));
        }
        let mut seen = 0;
        let size = f64::from(t.config().layout.hex_size);
        for (_, m) in chunk_meshes(&t) {
            let props = t.props(&m, usize::MAX, 1.0);
            for p in &props {
                let (x, z) = world(m.origin, p.position);
                let same = |&&((wx, wz), kind, variant): &&((f64, f64), PropKind, u8)| {
                    (wx - x).abs() < 1e-3 && (wz - z).abs() < 1e-3 && kind == p.kind && variant == p.variant
                };
                prop_assert!(by_tile.get(&p.tile).is_some_and(|v| v.iter().any(|q| same(&q))), "a chunk's prop is not in the whole map's");
                seen += 1;
                prop_assert!((t.surface_height(x, z).unwrap() - f64::from(p.position[1])).abs() < 1e-3 * size.max(1.0));
                prop_assert!(p.position[1] > t.sea_level());
                prop_assert_eq!(t.tile_at(x, z).unwrap(), p.tile);
                let kind = t.tile_kind(p.tile).unwrap();
                match p.kind {
                    PropKind::Rock => prop_assert!(kind == TileKind::Mountain || biome::at(&t, p.tile).unwrap().is_rocky()),
                    PropKind::Reed => {
                        prop_assert_eq!(kind, TileKind::Land);
                        prop_assert!(t.neighbors(p.tile).unwrap().iter().flatten().any(|&n| t.map_tile_kind(n) == Some(TileKind::Sea)));
                    }
                    _ => prop_assert_eq!(kind, TileKind::Land),
                }
                prop_assert!(p.variant < hex_terrain::PROP_VARIANTS);
            }
            let capped = t.props(&m, cap, 1.0);
            prop_assert!(capped.len() <= cap);
            prop_assert_eq!(capped.len(), props.len().min(cap));
            prop_assert!(capped.iter().all(|p| props.contains(p)));
        }
        prop_assert_eq!(seen, all.len(), "the chunks' props are not the whole map's");
    }

    /// Props of a coarse chunk ([`Detail::Coarse`]) are the full chunk's props (same kind,
    /// place, yaw, size, tile, order), each standing on the coarse mesh: its height is the coarse
    /// triangle's under its foot, found by brute force over the coarse mesh's triangles.
    #[test]
    fn coarse_props_are_the_full_props_on_the_coarse_surface(config in config()) {
        let t = Terrain::new(config).unwrap();
        let size = f64::from(t.config().layout.hex_size);
        for chunk in t.chunks().into_iter().take(6) {
            let rect = t.chunk_rect(chunk).unwrap();
            let full = t.generate(rect, GenerateOptions::DIAGNOSTICS);
            let coarse = t.coarsen(&full, false).unwrap();
            prop_assert_eq!(&coarse.buffers, &t.generate_detail(rect, GenerateOptions::CURRENT_THREAD, Detail::Coarse).buffers);
            let on_full = t.props(&full, usize::MAX, 1.0);
            let on_coarse = t.props_on(&full, usize::MAX, 1.0, Detail::Coarse);
            prop_assert_eq!(&t.props_on(&full, usize::MAX, 1.0, Detail::Full), &on_full);
            prop_assert_eq!(on_full.len(), on_coarse.len());
            let b = &coarse.buffers;
            for (f, c) in on_full.iter().zip(&on_coarse) {
                prop_assert_eq!((f.kind, f.variant, f.tile, f.yaw, f.scale), (c.kind, c.variant, c.tile, c.yaw, c.scale));
                prop_assert_eq!([f.position[0], f.position[2]], [c.position[0], c.position[2]]);
                let (x, z) = (f64::from(c.position[0]), f64::from(c.position[2]));
                let under = b.indices.chunks_exact(3).find_map(|tri| {
                    let [p, q, r] = [0, 1, 2].map(|k| b.positions[tri[k] as usize].map(f64::from));
                    let det = (q[0] - p[0]) * (r[2] - p[2]) - (r[0] - p[0]) * (q[2] - p[2]);
                    let u = ((x - p[0]) * (r[2] - p[2]) - (r[0] - p[0]) * (z - p[2])) / det;
                    let v = ((q[0] - p[0]) * (z - p[2]) - (x - p[0]) * (q[2] - p[2])) / det;
                    (det != 0.0 && u >= -1e-6 && v >= -1e-6 && u + v <= 1.0 + 1e-6).then(|| p[1] + u * (q[1] - p[1]) + v * (r[1] - p[1]))
                });
                let y = under.expect("a coarse prop off its chunk's coarse mesh");
                prop_assert!((y - f64::from(c.position[1])).abs() < 1e-4 * size.max(1.0), "prop at {} on a coarse surface at {}", c.position[1], y);
            }
        }
    }
}

/// A forested map grows trees and its mountains rocks; density 0 or a cap of 0 grows nothing.
#[test]
fn wooded_maps_grow_trees_and_mountains_rocks() {
    let mut c = MapConfig { size: MapSize::Bounded { x: 40, z: 30 }, ..MapConfig::default() };
    c.noise.scale = 40.0;
    let t = Terrain::new(c).unwrap();
    let m = t.generate_map().unwrap();
    let props = t.props(&m, usize::MAX, 1.0);
    assert!(props.iter().any(|p| p.kind == PropKind::Rock), "no rocks");
    assert!(props.iter().any(|p| p.kind == PropKind::Reed), "no reeds");
    assert!(props.iter().any(|p| matches!(p.kind, PropKind::Broadleaf | PropKind::Pine)), "no trees");
    assert!(t.props(&m, 0, 1.0).is_empty());
    assert!(t.props(&m, usize::MAX, 0.0).is_empty());
    let half = t.props(&m, usize::MAX, 0.5).len();
    assert!(half > 0 && half < props.len());
}
