//! A small, stable integer hash for placement decisions (relief jitter, props): the same inputs
//! give the same bits on every platform, thread and version of the project, which a general
//! hasher (`std`'s `DefaultHasher`, `ahash`) does not promise; and an integer sort key for a
//! value and an index, for the orders a stage takes things in.

/// Mixes a seed and integer coordinates into 64 well-spread bits (splitmix64's finaliser over
/// each input in turn).
#[must_use]
#[inline]
pub fn hash(seed: u32, values: &[i64]) -> u64 {
    let mut h = u64::from(seed) ^ 0x9E37_79B9_7F4A_7C15;
    for &v in values {
        h = mix(h ^ (v as u64).wrapping_mul(0xD6E8_FEB8_6659_FD93));
    }
    h
}

/// A value in `[0, 1)` from the top 24 bits of a hash.
#[must_use]
#[inline]
pub fn unit(h: u64) -> f32 {
    (h >> 40) as f32 / (1u64 << 24) as f32
}

#[inline]
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// An integer that orders as `(value, index)` do under `f32::total_cmp` then the index: the
/// value's bits turned so integers order as the values do, above the index. Sorting such keys
/// (unstably: they are unique) gives the same order as sorting by the value then the index.
#[must_use]
#[inline]
pub fn order_key(value: f32, index: u32) -> u64 {
    let bits = value.to_bits();
    let ordered = if bits >> 31 == 1 { !bits } else { bits | 0x8000_0000 };
    (u64::from(ordered) << 32) | u64::from(index)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hashes_are_stable_and_spread() {
        // Pinned: placements (props, relief) must not change between versions.
        assert_eq!(hash(1, &[2, 3]), hash(1, &[2, 3]));
        assert_ne!(hash(1, &[2, 3]), hash(1, &[3, 2]));
        assert_ne!(hash(1, &[2, 3]), hash(2, &[2, 3]));
        let mean = (0..10_000).map(|i| f64::from(unit(hash(7, &[i, -i])))).sum::<f64>() / 10_000.0;
        assert!((mean - 0.5).abs() < 0.02, "mean {mean}");
        assert!((0..10_000).all(|i| (0.0..1.0).contains(&unit(hash(9, &[i])))));
    }

    /// Keys order as the values under `total_cmp`, then the indices, across signs, zeros and
    /// infinities.
    #[test]
    fn order_keys_order_as_values_then_indices() {
        let values = [f32::NEG_INFINITY, -3.5, -1e-30, -0.0, 0.0, 1e-30, 0.25, 7.0, f32::INFINITY];
        for (a, &x) in values.iter().enumerate() {
            for (b, &y) in values.iter().enumerate() {
                for (i, j) in [(0, 0), (3, 9), (9, 3)] {
                    let expected = x.total_cmp(&y).then(i.cmp(&j));
                    assert_eq!(order_key(x, i).cmp(&order_key(y, j)), expected, "{a} {b} {i} {j}");
                }
            }
        }
    }
}
