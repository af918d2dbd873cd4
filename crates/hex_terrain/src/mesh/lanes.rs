//! The mesh's loops compiled for the instruction set of the map's fBm kernel
//! ([`Kernel`](crate::heights::Kernel), the widest this CPU runs unless
//! [`Terrain::with_kernel`](crate::Terrain::with_kernel) chose another): a batch of owned
//! points, a batch of normals, a group of tiles' indices, each compiled again inside a function
//! built for AVX2 or AVX-512 so that its loops vectorise sixteen f32 lanes wide (eight on AVX2 and
//! on the x86-64 baseline). Every build runs the same IEEE operations lane by lane, in the same
//! order and without fused multiply-add, so a mesh has the same bits on every kernel (tested:
//! `tests/kernels.rs` compares whole maps; the unit tests compare the normals and the
//! manipulation lane by lane).
//!
//! Why `unsafe` here (the workspace denies it everywhere else): a function compiled for AVX2 or
//! AVX-512 is a `#[target_feature]` function, unsafe to call from code compiled for the baseline.
//! Each call is guarded by the run-time check that the CPU has the feature
//! ([`Kernel::is_supported`], which std caches).
#![allow(unsafe_code)]
#![warn(clippy::undocumented_unsafe_blocks)]

use crate::heights::Kernel;

/// `f()` compiled for `kernel`'s instruction set when this CPU runs it, else for the build's
/// target: the same result either way, only the speed differs. `f` must be an
/// `#[inline(always)]` closure, so that its body is compiled inside the kernel's function rather
/// than only called from it.
#[inline(always)]
pub(super) fn run<R>(kernel: Kernel, f: impl FnOnce() -> R) -> R {
    match kernel {
        // SAFETY: the CPU has AVX-512F (checked in the guard).
        #[cfg(target_arch = "x86_64")]
        Kernel::Avx512 if kernel.is_supported() => unsafe { avx512(f) },
        // SAFETY: the CPU has AVX2 (checked in the guard).
        #[cfg(target_arch = "x86_64")]
        Kernel::Avx2 if kernel.is_supported() => unsafe { avx2(f) },
        _ => f(),
    }
}

/// f32 lanes a loop of `kernel` works on: a vector of AVX-512, two of AVX2 or of SSE2 (whose
/// loops the compiler unrolls).
pub(super) fn f32_lanes(kernel: Kernel) -> usize {
    if kernel == Kernel::Avx512 { 16 } else { 8 }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn avx2<R>(f: impl FnOnce() -> R) -> R {
    f()
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn avx512<R>(f: impl FnOnce() -> R) -> R {
    f()
}
