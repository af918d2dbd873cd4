//! The fBm kernel on x86-64's AVX2 ([`Kernel::Avx2`](super::Kernel::Avx2)): a batch of
//! [`LANES`] points as two vectors of four f64 lanes, interleaved octave by octave so that one
//! vector's table loads overlap the other's arithmetic.
//!
//! It does, lane by lane, exactly the IEEE operations of the portable loops in `fbm.rs`, in the
//! same order and without fused multiply-add, so it gives their bits; where the portable code
//! casts to an integer, this floors in f64 (exact within the `±2^52` both clamp to), and the low
//! eight bits of a cell index come from `c - 256 * floor(c / 256)`, also exact.
//!
//! Why `unsafe` here (the workspace denies it everywhere else): `std::arch` offers AVX2 only
//! through `#[target_feature]` functions, which are unsafe to call from code compiled for the
//! x86-64 baseline, and through loads and stores that take raw pointers. The one call into the
//! kernel is guarded by the run-time check that the CPU has AVX2
//! ([`Kernel::is_supported`](super::Kernel::is_supported)); every load and store reads or writes
//! four f64 of a `[f64; 4]` borrowed for the call.
#![allow(unsafe_code)]
#![warn(clippy::undocumented_unsafe_blocks)]

use std::arch::x86_64::{
    __m128i, __m256d, __m256i, _CMP_EQ_OQ, _CMP_GE_OQ, _CMP_LE_OQ, _CMP_LT_OQ, _mm_extract_epi32, _mm_set_epi32,
    _mm256_add_pd, _mm256_and_si256, _mm256_blendv_pd, _mm256_castsi256_pd, _mm256_ceil_pd, _mm256_cmp_pd,
    _mm256_cvtepu32_epi64, _mm256_cvttpd_epi32, _mm256_floor_pd, _mm256_loadu_pd, _mm256_max_pd, _mm256_min_pd,
    _mm256_mul_pd, _mm256_set1_epi64x, _mm256_set1_pd, _mm256_setzero_pd, _mm256_slli_epi64, _mm256_storeu_pd,
    _mm256_sub_pd, _mm256_xor_pd,
};

use super::periodic::{PERIODIC_OCTAVES, PeriodicCells};
use super::{Fbm, LANES, LIMIT, SCALE_2D, TABLE};

/// Whether this CPU has AVX2 (std caches the answer).
pub(super) fn supported() -> bool {
    std::arch::is_x86_feature_detected!("avx2")
}

/// [`Fbm::sample_batch`] on AVX2. `fbm.kernel` is only ever set to `Avx2` after
/// [`supported`] said yes ([`Fbm::with_kernel`], [`Kernel::detect`](super::Kernel::detect)).
pub(super) fn sample_batch(fbm: &Fbm, xs: &[f64; LANES], zs: &[f64; LANES], out: &mut [f64; LANES]) {
    debug_assert!(supported());
    // SAFETY: the CPU has AVX2: checked before the kernel was chosen (see above).
    unsafe { batch(fbm, xs, zs, out) }
}

/// Four lanes of `values` from `at`.
#[target_feature(enable = "avx2")]
#[inline]
fn load(values: &[f64; LANES], at: usize) -> __m256d {
    let quarter: &[f64; 4] = values[at..at + 4].try_into().expect("a batch holds two vectors");
    // SAFETY: `quarter` is four readable f64; `loadu` has no alignment requirement.
    unsafe { _mm256_loadu_pd(quarter.as_ptr()) }
}

/// Stores four lanes into `values` from `at`.
#[target_feature(enable = "avx2")]
#[inline]
fn store(values: &mut [f64; LANES], at: usize, v: __m256d) {
    let quarter: &mut [f64; 4] = (&mut values[at..at + 4]).try_into().expect("a batch holds two vectors");
    // SAFETY: `quarter` is four writable f64; `storeu` has no alignment requirement.
    unsafe { _mm256_storeu_pd(quarter.as_mut_ptr(), v) }
}

#[target_feature(enable = "avx2")]
fn batch(fbm: &Fbm, xs: &[f64; LANES], zs: &[f64; LANES], out: &mut [f64; LANES]) {
    let inv_scale = _mm256_set1_pd(fbm.inv_scale);
    let mut px = [_mm256_mul_pd(load(xs, 0), inv_scale), _mm256_mul_pd(load(xs, 4), inv_scale)];
    let pz = [_mm256_mul_pd(load(zs, 0), inv_scale), _mm256_mul_pd(load(zs, 4), inv_scale)];
    let mut total = [_mm256_setzero_pd(); 2];
    if let Some(periodic) = &fbm.periods {
        for x in &mut px {
            *x = reduce(*x, periodic);
        }
        for (o, (&(freq, amp), &cells)) in fbm.octaves.iter().zip(&periodic.cells).enumerate() {
            let (freq, amp) = (_mm256_set1_pd(freq), _mm256_set1_pd(amp));
            let last = _mm256_set1_pd(cells as f64 - 1.0);
            let seam = _mm256_set1_pd((TABLE * TABLE + (o % PERIODIC_OCTAVES) * TABLE) as f64);
            for (t, (&x, &z)) in total.iter_mut().zip(px.iter().zip(&pz)) {
                let noise = periodic_lane(periodic, last, seam, _mm256_mul_pd(x, freq), _mm256_mul_pd(z, freq));
                *t = _mm256_add_pd(*t, _mm256_mul_pd(amp, noise));
            }
        }
    } else {
        let table = &fbm.perlin.cells;
        for &(freq, amp) in &fbm.octaves {
            let (freq, amp) = (_mm256_set1_pd(freq), _mm256_set1_pd(amp));
            for (t, (&x, &z)) in total.iter_mut().zip(px.iter().zip(&pz)) {
                let noise = planar_lane(table, _mm256_mul_pd(x, freq), _mm256_mul_pd(z, freq));
                *t = _mm256_add_pd(*t, _mm256_mul_pd(amp, noise));
            }
        }
    }
    let (one, half) = (_mm256_set1_pd(1.0), _mm256_set1_pd(0.5));
    for (at, t) in [0, 4].into_iter().zip(total) {
        store(out, at, clamp01(_mm256_mul_pd(_mm256_add_pd(t, one), half)));
    }
}

/// `fbm.rs`'s `clamp01`: `maxpd(minpd(v, 1), 0)`.
#[target_feature(enable = "avx2")]
#[inline]
fn clamp01(v: __m256d) -> __m256d {
    _mm256_max_pd(_mm256_min_pd(v, _mm256_set1_pd(1.0)), _mm256_setzero_pd())
}

/// `fbm.rs`'s `split`: the cell (as an f64 integer) and the offset in it.
#[target_feature(enable = "avx2")]
#[inline]
fn split(v: __m256d) -> (__m256d, __m256d) {
    let v = _mm256_max_pd(_mm256_min_pd(v, _mm256_set1_pd(LIMIT)), _mm256_set1_pd(-LIMIT));
    let below = _mm256_sub_pd(_mm256_ceil_pd(v), _mm256_set1_pd(1.0));
    let at_or_below_zero = _mm256_cmp_pd::<_CMP_LE_OQ>(v, _mm256_setzero_pd());
    let c = _mm256_blendv_pd(_mm256_floor_pd(v), below, at_or_below_zero);
    (c, clamp01(_mm256_sub_pd(v, c)))
}

/// `c & 0xff` of an integral `c` (`|c| <= 2^52`), as an f64: every step is exact.
#[target_feature(enable = "avx2")]
#[inline]
fn low8(c: __m256d) -> __m256d {
    let q = _mm256_floor_pd(_mm256_mul_pd(c, _mm256_set1_pd(1.0 / 256.0)));
    _mm256_sub_pd(c, _mm256_mul_pd(q, _mm256_set1_pd(256.0)))
}

/// The packed corner gradients at four table indices (integral f64 below the table's length).
#[target_feature(enable = "avx2")]
#[inline]
fn cells_at(table: &[u8], index: __m256d) -> __m128i {
    let i = _mm256_cvttpd_epi32(index);
    let at = |lane: i32| i32::from(table[lane as usize]);
    _mm_set_epi32(
        at(_mm_extract_epi32::<3>(i)),
        at(_mm_extract_epi32::<2>(i)),
        at(_mm_extract_epi32::<1>(i)),
        at(_mm_extract_epi32::<0>(i)),
    )
}

#[target_feature(enable = "avx2")]
#[inline]
fn planar_lane(table: &[u8; TABLE * TABLE], x: __m256d, y: __m256d) -> __m256d {
    let (cx, dx) = split(x);
    let (cy, dy) = split(y);
    let index = _mm256_add_pd(_mm256_mul_pd(low8(cx), _mm256_set1_pd(256.0)), low8(cy));
    interpolate(cells_at(table, index), dx, dy)
}

/// `fbm.rs`'s `PeriodicCells::lane`; `last` is the period's last cell, `seam` where its octave's
/// seam cells start in the table.
#[target_feature(enable = "avx2")]
#[inline]
fn periodic_lane(periodic: &PeriodicCells, last: __m256d, seam: __m256d, xw: __m256d, y: __m256d) -> __m256d {
    let cx = _mm256_min_pd(_mm256_max_pd(_mm256_floor_pd(xw), _mm256_setzero_pd()), last);
    let dx = clamp01(_mm256_sub_pd(xw, cx));
    let (cy, dy) = split(y);
    let row = low8(cy);
    let planar = _mm256_add_pd(_mm256_mul_pd(low8(cx), _mm256_set1_pd(256.0)), row);
    let index = _mm256_blendv_pd(planar, _mm256_add_pd(seam, row), _mm256_cmp_pd::<_CMP_EQ_OQ>(cx, last));
    interpolate(cells_at(&periodic.table[..], index), dx, dy)
}

/// `fbm.rs`'s `reduce`: `x` modulo the period.
#[target_feature(enable = "avx2")]
#[inline]
fn reduce(x: __m256d, periodic: &PeriodicCells) -> __m256d {
    let (period, zero) = (_mm256_set1_pd(periodic.period), _mm256_setzero_pd());
    let t = _mm256_mul_pd(x, _mm256_set1_pd(periodic.inv_period));
    let t = _mm256_max_pd(_mm256_min_pd(t, _mm256_set1_pd(LIMIT)), _mm256_set1_pd(-LIMIT));
    let below = _mm256_sub_pd(_mm256_ceil_pd(t), _mm256_set1_pd(1.0));
    let q = _mm256_blendv_pd(_mm256_floor_pd(t), below, _mm256_cmp_pd::<_CMP_LT_OQ>(t, zero));
    // An integer cast has no negative zero: adding +0 turns floor(-0) into +0 as well.
    let q = _mm256_add_pd(q, zero);
    let xw = _mm256_sub_pd(x, _mm256_mul_pd(q, period));
    let over = _mm256_cmp_pd::<_CMP_GE_OQ>(xw, period);
    let xw = _mm256_blendv_pd(xw, _mm256_sub_pd(xw, period), over);
    let under = _mm256_cmp_pd::<_CMP_LT_OQ>(xw, zero);
    _mm256_blendv_pd(xw, _mm256_add_pd(xw, period), under)
}

/// `fbm.rs`'s `interpolate`. A gradient component of `±1` times an offset is the offset with its
/// sign bit flipped or not (the product is exact), so the gradient codes become sign masks.
#[target_feature(enable = "avx2")]
#[inline]
fn interpolate(cell: __m128i, dx: __m256d, dy: __m256d) -> __m256d {
    let codes = _mm256_cvtepu32_epi64(cell);
    let one = _mm256_set1_pd(1.0);
    let (dx1, dy1) = (_mm256_sub_pd(dx, one), _mm256_sub_pd(dy, one));
    // Corner code bits: (x, y) 0-1, (x+1, y) 2-3, (x, y+1) 4-5, (x+1, y+1) 6-7; bit b moves to
    // the sign bit with a left shift by 63 - b.
    let g00 = _mm256_add_pd(flip(dx, _mm256_slli_epi64::<63>(codes)), flip(dy, _mm256_slli_epi64::<62>(codes)));
    let g10 = _mm256_add_pd(flip(dx1, _mm256_slli_epi64::<61>(codes)), flip(dy, _mm256_slli_epi64::<60>(codes)));
    let g01 = _mm256_add_pd(flip(dx, _mm256_slli_epi64::<59>(codes)), flip(dy1, _mm256_slli_epi64::<58>(codes)));
    let g11 = _mm256_add_pd(flip(dx1, _mm256_slli_epi64::<57>(codes)), flip(dy1, _mm256_slli_epi64::<56>(codes)));
    let (sx, sy) = (quintic(dx), quintic(dy));
    let result = _mm256_mul_pd(lerp(lerp(g00, g01, sy), lerp(g10, g11, sy), sx), _mm256_set1_pd(SCALE_2D));
    _mm256_max_pd(_mm256_min_pd(result, one), _mm256_set1_pd(-1.0))
}

/// `v` with its sign flipped where `bits` has its sign bit set.
#[target_feature(enable = "avx2")]
#[inline]
fn flip(v: __m256d, bits: __m256i) -> __m256d {
    _mm256_xor_pd(v, _mm256_castsi256_pd(_mm256_and_si256(bits, _mm256_set1_epi64x(i64::MIN))))
}

/// `x * x * x * (x * (x * 6 - 15) + 10)`, evaluated left to right as in `fbm.rs`.
#[target_feature(enable = "avx2")]
#[inline]
fn quintic(x: __m256d) -> __m256d {
    let inner = _mm256_mul_pd(x, _mm256_sub_pd(_mm256_mul_pd(x, _mm256_set1_pd(6.0)), _mm256_set1_pd(15.0)));
    let inner = _mm256_add_pd(inner, _mm256_set1_pd(10.0));
    _mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(x, x), x), inner)
}

/// `b * t + a * (1 - t)`, as in `fbm.rs`.
#[target_feature(enable = "avx2")]
#[inline]
fn lerp(a: __m256d, b: __m256d, t: __m256d) -> __m256d {
    _mm256_add_pd(_mm256_mul_pd(b, t), _mm256_mul_pd(a, _mm256_sub_pd(_mm256_set1_pd(1.0), t)))
}
