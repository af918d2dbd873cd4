use proptest::prelude::*;

use super::{Batch, NormalCoefficients};
use crate::config::{MapConfig, MapSize, Orientation};
use crate::hash;
use crate::heights::Kernel;
use crate::mesh::grid::{GridShape, Points};
use crate::terrain::Terrain;

/// Heights for every slot: from the seed, spread over `scale`, some of them far out of any
/// map's range and some infinite (whose normals fall back to straight up).
fn heights(seed: u32, slots: usize, scale: f32) -> Vec<f32> {
    (0..slots as i64)
        .map(|s| {
            let h = hash::hash(seed, &[s]);
            match h % 97 {
                0 => f32::INFINITY,
                1 => 1e30,
                _ => (hash::unit(h) - 0.5) * scale,
            }
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Every kernel this CPU runs gives every point the bits of the one-vertex formula, whatever
    /// lane it falls in and wherever the batch starts.
    #[test]
    fn every_kernel_gives_the_one_vertex_bits(
        seed in any::<u32>(),
        (x, z) in (1_u32..9, 1_u32..7),
        rings in 1_u32..4,
        pointy in any::<bool>(),
        scale in prop::sample::select(vec![0.0_f32, 1.0, 40.0, 1e6]),
        start in 0_usize..40,
    ) {
        let mut config = MapConfig { size: MapSize::Bounded { x, z }, ..MapConfig::default() };
        config.terrain.inner_rings = rings;
        config.layout.orientation = if pointy { Orientation::Pointy } else { Orientation::Flat };
        let terrain = Terrain::new(config).expect("valid config");
        let lattice = terrain.lattice();
        let tiles: Vec<_> = terrain.bounds().expect("bounded").iter().map(|oc| terrain.tile_from_offset(oc)).collect();
        let shape = GridShape::around(lattice, &tiles);
        let points = Points::collect(lattice, &tiles, shape, &shape.template_offsets(lattice));
        let heights = heights(seed, shape.len(), scale);
        let around = [[1.0, 0.0], [0.5, 0.8], [-0.5, 0.8], [-1.0, 0.0], [-0.5, -0.8], [0.5, -0.8]];
        let coefficients = NormalCoefficients::new(&around);
        let batch = Batch { points: &points, heights: &heights, coefficients: &coefficients };
        let start = start.min(points.owned);
        let expected: Vec<[f32; 3]> = (start..points.owned).map(|i| batch.single(i)).collect();
        for kernel in Kernel::ALL.into_iter().filter(|k| k.is_supported()) {
            let mut out = vec![[f32::NAN; 3]; points.owned - start];
            batch.normals_on(kernel, start, &mut out);
            for (i, (got, want)) in out.iter().zip(&expected).enumerate() {
                prop_assert_eq!(got.map(f32::to_bits), want.map(f32::to_bits), "{:?} point {}", kernel, start + i);
            }
        }
    }
}
