//! The fBm kernel on x86-64's AVX-512 ([`Kernel::Avx512`](super::Kernel::Avx512)): a batch of
//! [`LANES`] points as one vector of eight f64 lanes.
//!
//! The same IEEE operations as the portable loops in `fbm.rs` and the AVX2 kernel, lane by lane,
//! in the same order and without fused multiply-add, so it gives their bits: comparisons give
//! masks where AVX2 gives vectors, and `roundscale` floors and ceils where AVX2 has `floor` and
//! `ceil`; the rest is the AVX2 kernel at twice the width.
//!
//! Why `unsafe` here (the workspace denies it everywhere else): as for AVX2, `std::arch` offers
//! AVX-512 only through `#[target_feature]` functions, unsafe to call from code compiled for the
//! x86-64 baseline, and through loads and stores that take raw pointers. The one call into the
//! kernel is guarded by the run-time check that the CPU has AVX-512F
//! ([`Kernel::is_supported`](super::Kernel::is_supported)); every load and store reads or writes
//! eight lanes of an array borrowed for the call.
#![allow(unsafe_code)]
#![warn(clippy::undocumented_unsafe_blocks)]

use std::arch::x86_64::{
    __m256i, __m512d, __m512i, _CMP_EQ_OQ, _CMP_GE_OQ, _CMP_LE_OQ, _CMP_LT_OQ, _mm256_setr_epi32, _mm256_storeu_si256,
    _mm512_add_pd, _mm512_and_si512, _mm512_castpd_si512, _mm512_castsi512_pd, _mm512_cmp_pd_mask,
    _mm512_cvtepu32_epi64, _mm512_cvttpd_epi32, _mm512_loadu_pd, _mm512_mask_blend_pd, _mm512_max_pd, _mm512_min_pd,
    _mm512_mul_pd, _mm512_roundscale_pd, _mm512_set1_epi64, _mm512_set1_pd, _mm512_setzero_pd, _mm512_slli_epi64,
    _mm512_storeu_pd, _mm512_sub_pd, _mm512_xor_si512,
};

use super::periodic::{PERIODIC_OCTAVES, PeriodicCells};
use super::{Fbm, LANES, LIMIT, SCALE_2D, TABLE};

/// `roundscale`'s rounding toward negative infinity, exceptions suppressed.
const FLOOR: i32 = 0x09;
/// `roundscale`'s rounding toward positive infinity, exceptions suppressed.
const CEIL: i32 = 0x0A;

/// Whether this CPU has AVX-512F (std caches the answer).
pub(super) fn supported() -> bool {
    std::arch::is_x86_feature_detected!("avx512f")
}

/// [`Fbm::sample_batch`] on AVX-512. `fbm.kernel` is only ever set to `Avx512` after
/// [`supported`] said yes ([`Fbm::with_kernel`], [`Kernel::detect`](super::Kernel::detect)).
pub(super) fn sample_batch(fbm: &Fbm, xs: &[f64; LANES], zs: &[f64; LANES], out: &mut [f64; LANES]) {
    debug_assert!(supported());
    // SAFETY: the CPU has AVX-512F: checked before the kernel was chosen (see above).
    unsafe { batch(fbm, xs, zs, out) }
}

#[target_feature(enable = "avx512f")]
fn batch(fbm: &Fbm, xs: &[f64; LANES], zs: &[f64; LANES], out: &mut [f64; LANES]) {
    let inv_scale = _mm512_set1_pd(fbm.inv_scale);
    // SAFETY: `xs` and `zs` are eight readable f64; `loadu` has no alignment requirement.
    let (x, z) = unsafe { (_mm512_loadu_pd(xs.as_ptr()), _mm512_loadu_pd(zs.as_ptr())) };
    let (mut px, pz) = (_mm512_mul_pd(x, inv_scale), _mm512_mul_pd(z, inv_scale));
    let mut total = _mm512_setzero_pd();
    if let Some(periodic) = &fbm.periods {
        px = reduce(px, periodic);
        for (o, (&(freq, amp), &cells)) in fbm.octaves.iter().zip(&periodic.cells).enumerate() {
            let (freq, amp) = (_mm512_set1_pd(freq), _mm512_set1_pd(amp));
            let last = _mm512_set1_pd(cells as f64 - 1.0);
            let seam = _mm512_set1_pd((TABLE * TABLE + (o % PERIODIC_OCTAVES) * TABLE) as f64);
            let noise = periodic_lane(periodic, last, seam, _mm512_mul_pd(px, freq), _mm512_mul_pd(pz, freq));
            total = _mm512_add_pd(total, _mm512_mul_pd(amp, noise));
        }
    } else {
        let table = &fbm.perlin.cells;
        for &(freq, amp) in &fbm.octaves {
            let (freq, amp) = (_mm512_set1_pd(freq), _mm512_set1_pd(amp));
            let noise = planar_lane(table, _mm512_mul_pd(px, freq), _mm512_mul_pd(pz, freq));
            total = _mm512_add_pd(total, _mm512_mul_pd(amp, noise));
        }
    }
    let (one, half) = (_mm512_set1_pd(1.0), _mm512_set1_pd(0.5));
    let result = clamp01(_mm512_mul_pd(_mm512_add_pd(total, one), half));
    // SAFETY: `out` is eight writable f64; `storeu` has no alignment requirement.
    unsafe { _mm512_storeu_pd(out.as_mut_ptr(), result) }
}

/// `fbm.rs`'s `clamp01`: `maxpd(minpd(v, 1), 0)`.
#[target_feature(enable = "avx512f")]
#[inline]
fn clamp01(v: __m512d) -> __m512d {
    _mm512_max_pd(_mm512_min_pd(v, _mm512_set1_pd(1.0)), _mm512_setzero_pd())
}

/// `fbm.rs`'s `split`: the cell (as an f64 integer) and the offset in it.
#[target_feature(enable = "avx512f")]
#[inline]
fn split(v: __m512d) -> (__m512d, __m512d) {
    let v = _mm512_max_pd(_mm512_min_pd(v, _mm512_set1_pd(LIMIT)), _mm512_set1_pd(-LIMIT));
    let below = _mm512_sub_pd(_mm512_roundscale_pd::<CEIL>(v), _mm512_set1_pd(1.0));
    let at_or_below_zero = _mm512_cmp_pd_mask::<_CMP_LE_OQ>(v, _mm512_setzero_pd());
    let c = _mm512_mask_blend_pd(at_or_below_zero, _mm512_roundscale_pd::<FLOOR>(v), below);
    (c, clamp01(_mm512_sub_pd(v, c)))
}

/// `c & 0xff` of an integral `c` (`|c| <= 2^52`), as an f64: every step is exact.
#[target_feature(enable = "avx512f")]
#[inline]
fn low8(c: __m512d) -> __m512d {
    let q = _mm512_roundscale_pd::<FLOOR>(_mm512_mul_pd(c, _mm512_set1_pd(1.0 / 256.0)));
    _mm512_sub_pd(c, _mm512_mul_pd(q, _mm512_set1_pd(256.0)))
}

/// The packed corner gradients at eight table indices (integral f64 below the table's length).
#[target_feature(enable = "avx512f")]
#[inline]
fn cells_at(table: &[u8], index: __m512d) -> __m256i {
    let mut lanes = [0_i32; 8];
    // SAFETY: `lanes` is eight writable i32; `storeu` has no alignment requirement.
    unsafe { _mm256_storeu_si256(lanes.as_mut_ptr().cast::<__m256i>(), _mm512_cvttpd_epi32(index)) };
    let at = |lane: usize| i32::from(table[lanes[lane] as usize]);
    _mm256_setr_epi32(at(0), at(1), at(2), at(3), at(4), at(5), at(6), at(7))
}

#[target_feature(enable = "avx512f")]
#[inline]
fn planar_lane(table: &[u8; TABLE * TABLE], x: __m512d, y: __m512d) -> __m512d {
    let (cx, dx) = split(x);
    let (cy, dy) = split(y);
    let index = _mm512_add_pd(_mm512_mul_pd(low8(cx), _mm512_set1_pd(256.0)), low8(cy));
    interpolate(cells_at(table, index), dx, dy)
}

/// `fbm.rs`'s `PeriodicCells::lane`; `last` is the period's last cell, `seam` where its octave's
/// seam cells start in the table.
#[target_feature(enable = "avx512f")]
#[inline]
fn periodic_lane(periodic: &PeriodicCells, last: __m512d, seam: __m512d, xw: __m512d, y: __m512d) -> __m512d {
    let cx = _mm512_min_pd(_mm512_max_pd(_mm512_roundscale_pd::<FLOOR>(xw), _mm512_setzero_pd()), last);
    let dx = clamp01(_mm512_sub_pd(xw, cx));
    let (cy, dy) = split(y);
    let row = low8(cy);
    let planar = _mm512_add_pd(_mm512_mul_pd(low8(cx), _mm512_set1_pd(256.0)), row);
    let index = _mm512_mask_blend_pd(_mm512_cmp_pd_mask::<_CMP_EQ_OQ>(cx, last), planar, _mm512_add_pd(seam, row));
    interpolate(cells_at(&periodic.table[..], index), dx, dy)
}

/// `fbm.rs`'s `reduce`: `x` modulo the period.
#[target_feature(enable = "avx512f")]
#[inline]
fn reduce(x: __m512d, periodic: &PeriodicCells) -> __m512d {
    let (period, zero) = (_mm512_set1_pd(periodic.period), _mm512_setzero_pd());
    let t = _mm512_mul_pd(x, _mm512_set1_pd(periodic.inv_period));
    let t = _mm512_max_pd(_mm512_min_pd(t, _mm512_set1_pd(LIMIT)), _mm512_set1_pd(-LIMIT));
    let below = _mm512_sub_pd(_mm512_roundscale_pd::<CEIL>(t), _mm512_set1_pd(1.0));
    let q = _mm512_mask_blend_pd(_mm512_cmp_pd_mask::<_CMP_LT_OQ>(t, zero), _mm512_roundscale_pd::<FLOOR>(t), below);
    // An integer cast has no negative zero: adding +0 turns floor(-0) into +0 as well.
    let q = _mm512_add_pd(q, zero);
    let xw = _mm512_sub_pd(x, _mm512_mul_pd(q, period));
    let over = _mm512_cmp_pd_mask::<_CMP_GE_OQ>(xw, period);
    let xw = _mm512_mask_blend_pd(over, xw, _mm512_sub_pd(xw, period));
    let under = _mm512_cmp_pd_mask::<_CMP_LT_OQ>(xw, zero);
    _mm512_mask_blend_pd(under, xw, _mm512_add_pd(xw, period))
}

/// `fbm.rs`'s `interpolate`. A gradient component of `±1` times an offset is the offset with its
/// sign bit flipped or not (the product is exact), so the gradient codes become sign masks.
#[target_feature(enable = "avx512f")]
#[inline]
fn interpolate(cell: __m256i, dx: __m512d, dy: __m512d) -> __m512d {
    let codes = _mm512_cvtepu32_epi64(cell);
    let one = _mm512_set1_pd(1.0);
    let (dx1, dy1) = (_mm512_sub_pd(dx, one), _mm512_sub_pd(dy, one));
    // Corner code bits: (x, y) 0-1, (x+1, y) 2-3, (x, y+1) 4-5, (x+1, y+1) 6-7; bit b moves to
    // the sign bit with a left shift by 63 - b.
    let g00 = _mm512_add_pd(flip(dx, _mm512_slli_epi64::<63>(codes)), flip(dy, _mm512_slli_epi64::<62>(codes)));
    let g10 = _mm512_add_pd(flip(dx1, _mm512_slli_epi64::<61>(codes)), flip(dy, _mm512_slli_epi64::<60>(codes)));
    let g01 = _mm512_add_pd(flip(dx, _mm512_slli_epi64::<59>(codes)), flip(dy1, _mm512_slli_epi64::<58>(codes)));
    let g11 = _mm512_add_pd(flip(dx1, _mm512_slli_epi64::<57>(codes)), flip(dy1, _mm512_slli_epi64::<56>(codes)));
    let (sx, sy) = (quintic(dx), quintic(dy));
    let result = _mm512_mul_pd(lerp(lerp(g00, g01, sy), lerp(g10, g11, sy), sx), _mm512_set1_pd(SCALE_2D));
    _mm512_max_pd(_mm512_min_pd(result, one), _mm512_set1_pd(-1.0))
}

/// `v` with its sign flipped where `bits` has its sign bit set.
#[target_feature(enable = "avx512f")]
#[inline]
fn flip(v: __m512d, bits: __m512i) -> __m512d {
    let sign = _mm512_and_si512(bits, _mm512_set1_epi64(i64::MIN));
    _mm512_castsi512_pd(_mm512_xor_si512(_mm512_castpd_si512(v), sign))
}

/// `x * x * x * (x * (x * 6 - 15) + 10)`, evaluated left to right as in `fbm.rs`.
#[target_feature(enable = "avx512f")]
#[inline]
fn quintic(x: __m512d) -> __m512d {
    let inner = _mm512_mul_pd(x, _mm512_sub_pd(_mm512_mul_pd(x, _mm512_set1_pd(6.0)), _mm512_set1_pd(15.0)));
    let inner = _mm512_add_pd(inner, _mm512_set1_pd(10.0));
    _mm512_mul_pd(_mm512_mul_pd(_mm512_mul_pd(x, x), x), inner)
}

/// `b * t + a * (1 - t)`, as in `fbm.rs`.
#[target_feature(enable = "avx512f")]
#[inline]
fn lerp(a: __m512d, b: __m512d, t: __m512d) -> __m512d {
    _mm512_add_pd(_mm512_mul_pd(b, t), _mm512_mul_pd(a, _mm512_sub_pd(_mm512_set1_pd(1.0), t)))
}
