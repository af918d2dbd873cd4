//! The mesh's vector loops (the normals' batches, the indices' tiles) compiled for the widest
//! vectors this CPU has, picked at run time: sixteen lanes of f32 on AVX-512, eight on AVX2,
//! eight on the x86-64 baseline (or any other target). Every build runs the same IEEE operations
//! lane by lane, in the same order and without fused multiply-add, so the normals have the same
//! bits on every path (tested in `normals/tests.rs`); the indices are integer copies (tested in
//! `tests.rs`).
//!
//! Why `unsafe` here (the workspace denies it everywhere else): a function compiled for AVX2 or
//! AVX-512 is a `#[target_feature]` function, unsafe to call from code compiled for the baseline.
//! Each call is guarded by the run-time check that the CPU has the feature ([`Kernel::detect`]).
#![allow(unsafe_code)]
#![warn(clippy::undocumented_unsafe_blocks)]

use super::grid::TEMPLATE_MAX;
use super::normals::Batch;
use crate::kind::TileKind;
use crate::manipulate::{Lanes, Manipulated};
use crate::vertex::VertexRules;

/// The instruction set the mesh's vector loops run on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kernel {
    /// Baseline code, eight lanes.
    Portable,
    /// AVX2, eight lanes.
    #[cfg(target_arch = "x86_64")]
    Avx2,
    /// AVX-512F, sixteen lanes.
    #[cfg(target_arch = "x86_64")]
    Avx512,
}

impl Kernel {
    /// The widest kernel this CPU runs (std caches the feature checks).
    pub fn detect() -> Self {
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx512f") {
                return Self::Avx512;
            }
            if std::arch::is_x86_feature_detected!("avx2") {
                return Self::Avx2;
            }
        }
        Self::Portable
    }

    /// Every kernel this CPU runs, for the tests.
    #[cfg(test)]
    pub fn supported() -> Vec<Self> {
        let mut all = vec![Self::Portable];
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx2") {
                all.push(Self::Avx2);
            }
            if std::arch::is_x86_feature_detected!("avx512f") {
                all.push(Self::Avx512);
            }
        }
        all
    }

    /// The normals of points `first..first + out.len()` of `batch`. A kernel other than
    /// `Portable` comes only from [`Kernel::detect`] or [`Kernel::supported`], which checked
    /// that the CPU has its feature.
    pub fn normals(self, batch: &Batch<'_>, first: usize, out: &mut [[f32; 3]]) {
        match self {
            Self::Portable => batch.normals::<8>(first, out),
            // SAFETY: the CPU has AVX2 (see above).
            #[cfg(target_arch = "x86_64")]
            Self::Avx2 => unsafe { normals_avx2(batch, first, out) },
            // SAFETY: the CPU has AVX-512F (see above).
            #[cfg(target_arch = "x86_64")]
            Self::Avx512 => unsafe { normals_avx512(batch, first, out) },
        }
    }

    /// Fills `out` (one tile's indices) with `own[table[i]]`, the point index of each corner of
    /// each template triangle; every entry of `table` is below [`TEMPLATE_MAX`]. As
    /// [`Kernel::normals`] for the kernels.
    pub fn indices(self, own: &[u32; OWN], table: &[u16], out: &mut [u32]) {
        match self {
            Self::Portable => indices(own, table, out),
            // SAFETY: the CPU has AVX2 (see above).
            #[cfg(target_arch = "x86_64")]
            Self::Avx2 => unsafe { indices_avx2(own, table, out) },
            // SAFETY: the CPU has AVX-512F (see above).
            #[cfg(target_arch = "x86_64")]
            Self::Avx512 => unsafe { indices_avx512(own, table, out) },
        }
    }
}

impl Kernel {
    /// Manipulation of the points of a batch ([`VertexRules::manipulated_lanes`]), sixteen at a
    /// time, the tail one by one: the same bits as one by one. As [`Kernel::normals`] for the
    /// kernels.
    pub fn manipulate(
        self,
        rules: &VertexRules,
        raws: &[f32],
        rings: &[u32],
        spans: &[(TileKind, TileKind)],
        out: &mut [Manipulated],
    ) {
        match self {
            Self::Portable => manipulate(rules, raws, rings, spans, out),
            // SAFETY: the CPU has AVX2 (see above).
            #[cfg(target_arch = "x86_64")]
            Self::Avx2 => unsafe { manipulate_avx2(rules, raws, rings, spans, out) },
            // SAFETY: the CPU has AVX-512F (see above).
            #[cfg(target_arch = "x86_64")]
            Self::Avx512 => unsafe { manipulate_avx512(rules, raws, rings, spans, out) },
        }
    }
}

#[inline(always)]
fn manipulate(
    rules: &VertexRules,
    raws: &[f32],
    rings: &[u32],
    spans: &[(TileKind, TileKind)],
    out: &mut [Manipulated],
) {
    const L: usize = 16;
    let done = out.len() / L * L;
    let mut lanes = Lanes { raw: [0.0; L], ring: [0; L], lo: [TileKind::Sea; L], hi: [TileKind::Sea; L] };
    for (c, out) in out.chunks_exact_mut(L).enumerate() {
        let range = c * L..(c + 1) * L;
        lanes.raw.copy_from_slice(&raws[range.clone()]);
        lanes.ring.copy_from_slice(&rings[range.clone()]);
        for (l, &(lo, hi)) in spans[range].iter().enumerate() {
            (lanes.lo[l], lanes.hi[l]) = (lo, hi);
        }
        rules.manipulated_lanes(&lanes, out.try_into().expect("L points"));
    }
    for (i, m) in out.iter_mut().enumerate().skip(done) {
        *m = rules.manipulated(raws[i], rings[i], Some(spans[i]));
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn manipulate_avx2(
    rules: &VertexRules,
    raws: &[f32],
    rings: &[u32],
    spans: &[(TileKind, TileKind)],
    out: &mut [Manipulated],
) {
    manipulate(rules, raws, rings, spans, out);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn manipulate_avx512(
    rules: &VertexRules,
    raws: &[f32],
    rings: &[u32],
    spans: &[(TileKind, TileKind)],
    out: &mut [Manipulated],
) {
    manipulate(rules, raws, rings, spans, out);
}

/// Slots of a tile's point indices: a power of two at least [`TEMPLATE_MAX`], so that an index
/// masked into it needs no bounds check and the copy vectorises into gathers.
pub(super) const OWN: usize = TEMPLATE_MAX.next_power_of_two();

#[inline(always)]
fn indices(own: &[u32; OWN], table: &[u16], out: &mut [u32]) {
    for (d, &k) in out.iter_mut().zip(table) {
        *d = own[usize::from(k) & (OWN - 1)];
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn indices_avx2(own: &[u32; OWN], table: &[u16], out: &mut [u32]) {
    indices(own, table, out);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn indices_avx512(own: &[u32; OWN], table: &[u16], out: &mut [u32]) {
    indices(own, table, out);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn normals_avx2(batch: &Batch<'_>, first: usize, out: &mut [[f32; 3]]) {
    batch.normals::<8>(first, out);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn normals_avx512(batch: &Batch<'_>, first: usize, out: &mut [[f32; 3]]) {
    batch.normals::<16>(first, out);
}
