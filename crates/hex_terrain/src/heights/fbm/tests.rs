use noise::{NoiseFn, Perlin};

use super::*;

/// The gradient table read back from `noise::Perlin` itself: just past a lattice corner the
/// noise equals the corner's gradient term alone (the fade curve is ~1e-8 there), and the four
/// gradients give four distinct values.
fn read_back(seed: u32) -> Box<[u8; TABLE * TABLE]> {
    let reference = Perlin::new(seed);
    let (dx, dy) = (1.0 / 1024.0, 1.0 / 512.0);
    // Gradient terms times the scale: (dx + dy), (-dx + dy), (dx - dy), (-dx - dy).
    let split = (dx + dy + (dy - dx)) * 0.5 * SCALE_2D;
    let code = |x: usize, y: usize| {
        let v = reference.get([x as f64 + dx, y as f64 + dy]);
        if v > split {
            0
        } else if v > 0.0 {
            1
        } else if v > -split {
            2
        } else {
            3
        }
    };
    let mut cells = Box::new([0_u8; TABLE * TABLE]);
    for x in 0..TABLE {
        for y in 0..TABLE {
            let (x1, y1) = ((x + 1) % TABLE, (y + 1) % TABLE);
            cells[x * TABLE + y] = code(x, y) | code(x1, y) << 2 | code(x, y1) << 4 | code(x1, y1) << 6;
        }
    }
    cells
}

/// The table made as `noise` makes it equals the table read back from `noise`, on edge seeds
/// and a spread of others.
#[test]
fn gradient_tables_equal_noises_own() {
    let mut seeds = vec![0, 1, 2, 255, 256, 1000, 2024, 65_535, 65_536, u32::MAX - 1, u32::MAX];
    seeds.extend((0..40u32).map(|i| i.wrapping_mul(2_654_435_761) ^ 0x5bd1_e995));
    for seed in seeds {
        assert!(FastPerlin::new(seed).cells == read_back(seed), "seed {seed}");
    }
}

#[test]
fn fast_perlin_is_bit_identical_to_noise_perlin() {
    for seed in [0, 1, 1000, 2401, u32::MAX] {
        let fast = FastPerlin::new(seed);
        let reference = Perlin::new(seed);
        let mut state = u64::from(seed) ^ 0x9E37_79B9_7F4A_7C15;
        for i in 0..20_000 {
            state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            let x = ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 2000.0;
            let y = ((state >> 3) as f64 % 4096.0) / 7.0 - 300.0;
            // Integers (including negative ones and zero) exercise noise's flooring quirk.
            let (x, y) = if i % 10 == 0 { (x.round(), y.round()) } else { (x, y) };
            assert_eq!(fast.get(x, y).to_bits(), reference.get([x, y]).to_bits(), "seed {seed} at ({x}, {y})");
        }
    }
}

#[test]
fn fbm_stays_in_unit_range_and_matches_reference() {
    let config = NoiseConfig::default();
    let fbm = Fbm::new(1000, &config);
    let reference = Perlin::new(1000);
    for i in 0..5000 {
        let (x, z) = (f64::from(i) * 0.37 - 500.0, f64::from(i % 71) * 1.3 - 40.0);
        let v = fbm.sample(x, z);
        assert!((0.0..=1.0).contains(&v));
        assert!((v - fbm.sample_reference(&reference, x, z)).abs() < 1e-6);
    }
}

#[test]
fn batches_give_the_bits_of_single_samples() {
    let config = NoiseConfig { octaves: 7, persistence: 0.5, lacunarity: 2.3, scale: 17.0 };
    let fbm = Fbm::new(42, &config);
    let points: Vec<[f64; 2]> = (0..1001).map(|i| [f64::from(i) * 0.61 - 300.0, f64::from(i % 37) * -2.1]).collect();
    let mut out = vec![0.0; points.len()];
    fbm.sample_many(&points, &mut out);
    for (p, v) in points.iter().zip(&out) {
        assert_eq!(v.to_bits(), fbm.sample(p[0], p[1]).to_bits());
    }
}

#[test]
fn map0_parameters_give_thesis_like_type_shares() {
    // docs/ARCHITECTURE.md (departures from the thesis): with (v + 1) / 2 and Map0's parameters about 12% of samples fall below 0.3
    // and 12% above 0.7; allow a wide band, this guards the mapping, not the exact share.
    let fbm = Fbm::new(1000, &NoiseConfig::default());
    let (mut low, mut high, mut total) = (0, 0, 0);
    for i in 0..400 {
        for j in 0..400 {
            let v = fbm.sample(f64::from(i) * 0.5, f64::from(j) * 0.5);
            total += 1;
            low += usize::from(v < 0.3);
            high += usize::from(v > 0.7);
        }
    }
    let (low, high) = (low as f64 / total as f64, high as f64 / total as f64);
    assert!((0.03..0.3).contains(&low), "share below 0.3: {low}");
    assert!((0.03..0.3).contains(&high), "share above 0.7: {high}");
}

#[test]
fn coordinates_beyond_i64_give_finite_noise() {
    let perlin = FastPerlin::new(3);
    for (x, y) in [(-1e300, 5.5), (1e300, -1e19), (-9.3e18, -9.3e18), (f64::MAX, f64::MIN)] {
        let v = perlin.get(x, y);
        assert!(v.is_finite() && (-1.0..=1.0).contains(&v), "noise at ({x}, {y}) = {v}");
    }
}

/// Points that exercise every branch of the kernels: the flooring quirk at integers and zeros
/// of both signs, cell borders, the period's edges, and coordinates past `±2^52`, infinite or
/// NaN (the same bits are owed there too, whatever they are).
fn awkward_points() -> Vec<[f64; 2]> {
    let specials = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.5,
        -0.5,
        255.0,
        256.0,
        -256.0,
        1e-300,
        -1e-300,
        4_503_599_627_370_496.0,
        -4_503_599_627_370_497.0,
        9.3e18,
        -1e300,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
    ];
    let mut points = Vec::new();
    for &x in &specials {
        for &z in &specials {
            points.push([x, z]);
        }
    }
    points
}

/// The kernel's batches against the portable loops, bit for bit, at `points`.
fn assert_kernel_bits(fbm: &Fbm, kernel: Kernel, points: &[[f64; 2]]) -> Result<(), String> {
    let Some(fast) = fbm.clone().with_kernel(kernel) else { return Ok(()) };
    let portable = fbm.clone().with_kernel(Kernel::Portable).expect("the portable kernel runs anywhere");
    let (mut a, mut b) = (vec![0.0; points.len()], vec![0.0; points.len()]);
    fast.sample_many(points, &mut a);
    portable.sample_many(points, &mut b);
    for ((p, a), b) in points.iter().zip(&a).zip(&b) {
        if a.to_bits() != b.to_bits() {
            return Err(format!("{} at {p:?}: {a} but portable {b}", kernel.name()));
        }
    }
    Ok(())
}

#[test]
fn every_kernel_gives_the_portable_bits_at_awkward_points() {
    let points = awkward_points();
    let config = NoiseConfig::default();
    for kernel in Kernel::ALL {
        for fbm in [Fbm::new(7, &config), Fbm::wrapped(7, &config, 84.0), Fbm::wrapped(7, &config, 0.5)] {
            assert_kernel_bits(&fbm, kernel, &points).unwrap();
        }
    }
    // The portable loops are `noise::Perlin` bit for bit, so every kernel is.
    let fbm = Fbm::new(1000, &config);
    let reference = Perlin::new(1000);
    for p in points.iter().filter(|p| p[0].abs() < 1e6 && p[1].abs() < 1e6) {
        assert_eq!(fbm.sample(p[0], p[1]).to_bits(), fbm.sample_reference(&reference, p[0], p[1]).to_bits(), "{p:?}");
    }
}

#[test]
fn detection_picks_a_supported_kernel() {
    let kernel = Kernel::detect();
    assert!(kernel.is_supported());
    assert!(Kernel::Portable.is_supported());
    assert_eq!(Fbm::new(1, &NoiseConfig::default()).kernel(), kernel);
    #[cfg(target_arch = "x86_64")]
    {
        assert_eq!(Kernel::Avx2.is_supported(), std::arch::is_x86_feature_detected!("avx2"));
        assert_eq!(Kernel::Avx512.is_supported(), std::arch::is_x86_feature_detected!("avx512f"));
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]

    /// Random configs (octaves, persistence, lacunarity, scale), seeds, periods and points: every
    /// kernel this CPU runs gives the portable bits, planar and wrapping.
    #[test]
    fn every_kernel_gives_the_portable_bits(
        seed in proptest::prelude::any::<u32>(),
        octaves in 1..=crate::config::MAX_OCTAVES,
        persistence in 0.05..1.0_f64,
        lacunarity in 1.0..4.0_f64,
        scale in 0.5..500.0_f64,
        width in proptest::option::of(1.0..5000.0_f64),
        origin in (-1e6..1e6_f64, -1e6..1e6_f64),
        spread in 0.01..1e4_f64,
        offsets in proptest::collection::vec((-1.0..1.0_f64, -1.0..1.0_f64), 1..40),
    ) {
        let config = NoiseConfig { octaves, persistence, lacunarity, scale };
        let fbm = match width {
            Some(w) => Fbm::wrapped(seed, &config, w),
            None => Fbm::new(seed, &config),
        };
        let points: Vec<[f64; 2]> =
            offsets.iter().map(|&(dx, dz)| [origin.0 + dx * spread, origin.1 + dz * spread]).collect();
        for kernel in Kernel::ALL {
            proptest::prop_assert!(assert_kernel_bits(&fbm, kernel, &points).is_ok(), "{:?}", assert_kernel_bits(&fbm, kernel, &points));
        }
    }
}
