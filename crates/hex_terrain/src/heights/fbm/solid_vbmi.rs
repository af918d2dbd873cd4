//! The solid fBm on x86-64 with AVX-512 VBMI: a batch of [`LANES`] points as eight f32 lanes,
//! and Perlin's hash looked up in registers.
//!
//! The hash reads the permutation table fourteen times an octave (two, then four, then eight
//! lookups, each needing the last); as gathers from memory those cost more than the rest of the
//! octave. Here the table's 256 bytes sit in four registers and each step of the hash is one
//! lookup of all its bytes at once (`vpermi2b` over each half of the table, the index's top bit
//! choosing): the eight lanes' `x` and `x + 1` (16 bytes), then the four `x, y` corners (32),
//! then the eight corners' codes (64).
//!
//! The floating-point work is `solid.rs`' portable loop, lane by lane, in the same order and
//! without fused multiply-add, so the bits are the same (a test compares every kernel).
//!
//! Why `unsafe` here (the workspace denies it everywhere else): `std::arch` offers these
//! instructions only through `#[target_feature]` functions, unsafe to call from code compiled
//! for the x86-64 baseline. The one call is guarded by the run-time check that the CPU has the
//! features ([`supported`]); the loads read the fbm's own tables and the batch's arrays.
#![allow(unsafe_code)]
#![warn(clippy::undocumented_unsafe_blocks)]

use std::arch::x86_64::{
    __m128i, __m256, __m256i, __m512i, _CMP_LE_OQ, _mm_add_epi8, _mm_set1_epi8, _mm_unpackhi_epi64, _mm_unpacklo_epi64,
    _mm_xor_si128, _mm256_add_ps, _mm256_broadcastq_epi64, _mm256_cmp_ps_mask, _mm256_cvtepi32_epi8,
    _mm256_cvtepi32_ps, _mm256_cvttps_epi32, _mm256_mask_blend_ps, _mm256_mask_sub_epi32, _mm256_mask_xor_ps,
    _mm256_max_ps, _mm256_min_ps, _mm256_mul_ps, _mm256_set_m128i, _mm256_set1_epi32, _mm256_set1_ps,
    _mm256_setzero_ps, _mm256_storeu_ps, _mm256_sub_ps, _mm256_xor_si256, _mm512_castsi128_si512,
    _mm512_castsi256_si512, _mm512_castsi512_si128, _mm512_castsi512_si256, _mm512_inserti64x4, _mm512_loadu_si512,
    _mm512_mask_blend_epi8, _mm512_movepi8_mask, _mm512_permutex2var_epi8, _mm512_set1_epi8, _mm512_test_epi8_mask,
};

use super::{LANES, SCALE_3D, SOLID_LIMIT, TABLE};

/// Whether this CPU has AVX-512F, BW, DQ, VL and VBMI (std caches the answer).
pub(super) fn supported() -> bool {
    std::arch::is_x86_feature_detected!("avx512f")
        && std::arch::is_x86_feature_detected!("avx512bw")
        && std::arch::is_x86_feature_detected!("avx512dq")
        && std::arch::is_x86_feature_detected!("avx512vl")
        && std::arch::is_x86_feature_detected!("avx512vbmi")
}

/// The batch on this kernel, from the fbm's permutation table, its edges' codes as bytes and its
/// octaves. The fbm picks it only after [`supported`] said yes.
pub(super) fn batch(
    permutation: &[u8; TABLE],
    codes: &[u8; TABLE],
    octaves: &[(f32, f32)],
    points: &[[f32; 3]; LANES],
    out: &mut [f32; LANES],
) {
    debug_assert!(supported());
    // SAFETY: the CPU has every feature the kernel is compiled for: checked before it was picked.
    unsafe { kernel(permutation, codes, octaves, points, out) }
}

/// A table of 256 bytes in four registers.
#[derive(Clone, Copy)]
struct Table([__m512i; 4]);

impl Table {
    #[target_feature(enable = "avx512f,avx512bw,avx512vl,avx512vbmi")]
    fn load(bytes: &[u8; TABLE]) -> Self {
        // SAFETY: each load reads 64 of the table's 256 bytes; `loadu` has no alignment need.
        Self(std::array::from_fn(|k| unsafe { _mm512_loadu_si512(bytes[64 * k..].as_ptr().cast()) }))
    }

    /// Each byte of `index` looked up (only the bytes the caller reads matter).
    #[target_feature(enable = "avx512f,avx512bw,avx512vl,avx512vbmi")]
    fn get(&self, index: __m512i) -> __m512i {
        let low = _mm512_permutex2var_epi8(self.0[0], index, self.0[1]);
        let high = _mm512_permutex2var_epi8(self.0[2], index, self.0[3]);
        _mm512_mask_blend_epi8(_mm512_movepi8_mask(index), low, high)
    }

    #[target_feature(enable = "avx512f,avx512bw,avx512vl,avx512vbmi")]
    fn get16(&self, index: __m128i) -> __m128i {
        _mm512_castsi512_si128(self.get(_mm512_castsi128_si512(index)))
    }

    #[target_feature(enable = "avx512f,avx512bw,avx512vl,avx512vbmi")]
    fn get32(&self, index: __m256i) -> __m256i {
        _mm512_castsi512_si256(self.get(_mm512_castsi256_si512(index)))
    }
}

#[target_feature(enable = "avx512f,avx512bw,avx512dq,avx512vl,avx512vbmi")]
fn kernel(
    permutation: &[u8; TABLE],
    codes: &[u8; TABLE],
    octaves: &[(f32, f32)],
    points: &[[f32; 3]; LANES],
    out: &mut [f32; LANES],
) {
    let (permutation, codes) = (Table::load(permutation), Table::load(codes));
    let lane = |c: usize| -> __m256 {
        let v: [f32; LANES] = std::array::from_fn(|l| points[l][c]);
        // SAFETY: `v` is eight readable f32.
        unsafe { std::arch::x86_64::_mm256_loadu_ps(v.as_ptr()) }
    };
    let (x, y, z) = (lane(0), lane(1), lane(2));
    let mut total = _mm256_setzero_ps();
    for &(freq, amp) in octaves {
        let freq = _mm256_set1_ps(freq);
        let noise =
            octave(&permutation, &codes, _mm256_mul_ps(x, freq), _mm256_mul_ps(y, freq), _mm256_mul_ps(z, freq));
        total = _mm256_add_ps(total, _mm256_mul_ps(_mm256_set1_ps(amp), noise));
    }
    let result = clamp01(_mm256_mul_ps(_mm256_add_ps(total, _mm256_set1_ps(1.0)), _mm256_set1_ps(0.5)));
    // SAFETY: `out` is eight writable f32.
    unsafe { _mm256_storeu_ps(out.as_mut_ptr(), result) }
}

/// `solid.rs`' `clamp01`: `maxps(minps(v, 1), 0)`.
#[target_feature(enable = "avx512f,avx512vl")]
fn clamp01(v: __m256) -> __m256 {
    _mm256_max_ps(_mm256_min_ps(v, _mm256_set1_ps(1.0)), _mm256_setzero_ps())
}

/// `solid.rs`' `split`: the cell (as bytes, the hash's coordinates mod 256) and the offset.
#[target_feature(enable = "avx512f,avx512bw,avx512dq,avx512vl")]
fn split(v: __m256) -> (__m128i, __m256) {
    let v = _mm256_max_ps(_mm256_min_ps(v, _mm256_set1_ps(SOLID_LIMIT)), _mm256_set1_ps(-SOLID_LIMIT));
    let truncated = _mm256_cvttps_epi32(v);
    let at_or_below_zero = _mm256_cmp_ps_mask::<_CMP_LE_OQ>(v, _mm256_setzero_ps());
    let cell = _mm256_mask_sub_epi32(truncated, at_or_below_zero, truncated, _mm256_set1_epi32(1));
    (_mm256_cvtepi32_epi8(cell), clamp01(_mm256_sub_ps(v, _mm256_cvtepi32_ps(cell))))
}

#[target_feature(enable = "avx512f,avx512vl")]
fn quintic(x: __m256) -> __m256 {
    let inner = _mm256_add_ps(
        _mm256_mul_ps(x, _mm256_sub_ps(_mm256_mul_ps(x, _mm256_set1_ps(6.0)), _mm256_set1_ps(15.0))),
        _mm256_set1_ps(10.0),
    );
    _mm256_mul_ps(_mm256_mul_ps(_mm256_mul_ps(x, x), x), inner)
}

#[target_feature(enable = "avx512f,avx512vl")]
fn lerp(a: __m256, b: __m256, t: __m256) -> __m256 {
    _mm256_add_ps(_mm256_mul_ps(b, t), _mm256_mul_ps(a, _mm256_sub_ps(_mm256_set1_ps(1.0), t)))
}

/// The gradient sum of one corner, from its lanes' code bits (`u64` masks, the corner's eight
/// lanes at bits `8 block..`).
#[target_feature(enable = "avx512f,avx512dq,avx512vl")]
fn gradient(masks: [u64; 4], block: u32, px: __m256, py: __m256, pz: __m256) -> __m256 {
    let [negate_u, negate_v, u_is_y, v_is_z] = masks.map(|m| (m >> (8 * block)) as u8);
    let sign = _mm256_set1_ps(-0.0);
    let u = _mm256_mask_blend_ps(u_is_y, px, py);
    let v = _mm256_mask_blend_ps(v_is_z, py, pz);
    let u = _mm256_mask_xor_ps(u, negate_u, u, sign);
    let v = _mm256_mask_xor_ps(v, negate_v, v, sign);
    _mm256_add_ps(u, v)
}

/// `solid.rs`' `SolidFbm::noise` at eight points.
#[target_feature(enable = "avx512f,avx512bw,avx512dq,avx512vl,avx512vbmi")]
fn octave(permutation: &Table, codes: &Table, x: __m256, y: __m256, z: __m256) -> __m256 {
    let (cx, dx) = split(x);
    let (cy, dy) = split(y);
    let (cz, dz) = split(z);
    let one = _mm_set1_epi8(1);
    // P[x], P[x + 1]; then P[P[x] ^ y] for the four (x, y) corners; then the codes of the eight
    // corners, P[P[P[x] ^ y] ^ z] & 15 as its edge's code. Each byte is a coordinate mod 256.
    let xs = permutation.get16(_mm_unpacklo_epi64(cx, _mm_add_epi8(cx, one)));
    let ys = _mm_unpacklo_epi64(cy, _mm_add_epi8(cy, one));
    let x0 = _mm_unpacklo_epi64(xs, xs);
    let x1 = _mm_unpackhi_epi64(xs, xs);
    // [h00 | h01 | h10 | h11], each eight lanes.
    let hashes = permutation.get32(_mm256_set_m128i(_mm_xor_si128(x1, ys), _mm_xor_si128(x0, ys)));
    let z0 = _mm256_broadcastq_epi64(cz);
    let z1 = _mm256_broadcastq_epi64(_mm_add_epi8(cz, one));
    let corners =
        _mm512_inserti64x4::<1>(_mm512_castsi256_si512(_mm256_xor_si256(hashes, z0)), _mm256_xor_si256(hashes, z1));
    // Block `4 z + 2 x + y` holds corner (x, y, z)'s eight lanes.
    let code = codes.get(corners);
    let masks = [1, 2, 4, 8].map(|bit| _mm512_test_epi8_mask(code, _mm512_set1_epi8(bit)));
    let one = _mm256_set1_ps(1.0);
    let (ex, ey, ez) = (_mm256_sub_ps(dx, one), _mm256_sub_ps(dy, one), _mm256_sub_ps(dz, one));
    let g000 = gradient(masks, 0, dx, dy, dz);
    let g100 = gradient(masks, 2, ex, dy, dz);
    let g010 = gradient(masks, 1, dx, ey, dz);
    let g110 = gradient(masks, 3, ex, ey, dz);
    let g001 = gradient(masks, 4, dx, dy, ez);
    let g101 = gradient(masks, 6, ex, dy, ez);
    let g011 = gradient(masks, 5, dx, ey, ez);
    let g111 = gradient(masks, 7, ex, ey, ez);
    let (sx, sy, sz) = (quintic(dx), quintic(dy), quintic(dz));
    let result = _mm256_mul_ps(
        lerp(
            lerp(lerp(g000, g001, sz), lerp(g010, g011, sz), sy),
            lerp(lerp(g100, g101, sz), lerp(g110, g111, sz), sy),
            sx,
        ),
        _mm256_set1_ps(SCALE_3D),
    );
    _mm256_max_ps(_mm256_min_ps(result, one), _mm256_set1_ps(-1.0))
}
