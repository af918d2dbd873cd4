//! The parallel policy of a generation: whether it spreads over rayon's pool, how work is cut
//! into batches, and the disjoint output slices each batch writes.
//!
//! A [`Split`] that does not split runs everything on the calling thread and never touches
//! rayon (not even to ask its thread count), so a caller on another pool (Bevy's async compute
//! pool, say) keeps one pool per kind of work.

use rayon::prelude::*;

/// Points processed together by one task.
pub(super) const BATCH: usize = 1024;

/// Whether a generation spreads its work over the thread pool: only when asked to and when
/// there is enough of it to pay for waking other threads.
#[derive(Clone, Copy)]
pub(super) struct Split(pub bool);

impl Split {
    /// Most points not worth splitting (one batch): up to this many, a generation runs on the
    /// calling thread.
    pub const MIN_POINTS: usize = BATCH;

    /// Fewest points for which the work beside the point enumeration goes to another thread.
    pub const SIDE_MIN_POINTS: usize = 4 * BATCH;

    /// `f()`, inside the thread pool when splitting (entered once, rather than at every
    /// parallel call inside `f`).
    pub fn in_pool<R: Send>(self, f: impl FnOnce() -> R + Send) -> R {
        if self.0 && rayon::current_thread_index().is_none() { rayon::scope(|_| f()) } else { f() }
    }

    /// `(a(), b())`, in parallel when splitting.
    pub fn join<A: Send, B: Send>(self, a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B + Send) -> (A, B) {
        if self.0 { rayon::join(a, b) } else { (a(), b()) }
    }

    /// `f(i)` for `i` in `0..len`, in order, on all cores when splitting.
    pub fn map<O: Send>(self, len: usize, f: impl Fn(usize) -> O + Sync + Send) -> Vec<O> {
        if self.0 { (0..len).into_par_iter().with_min_len(512).map(f).collect() } else { (0..len).map(f).collect() }
    }

    /// `f(k, chunk)` for the `k`-th chunk of `size` elements of `data`, with at least
    /// `min_chunks` chunks a task when splitting.
    pub fn for_each_chunk<T: Send>(
        self,
        data: &mut [T],
        size: usize,
        min_chunks: usize,
        f: impl Fn(usize, &mut [T]) + Sync + Send,
    ) {
        if self.0 {
            data.par_chunks_mut(size).with_min_len(min_chunks).enumerate().for_each(|(k, c)| f(k, c));
        } else {
            data.chunks_mut(size).enumerate().for_each(|(k, c)| f(k, c));
        }
    }
}

/// The per-vertex outputs of a run of owned points, split in halves for the tasks, with the
/// part of the height grid from the run's first slot up to the next run's. The diagnostic
/// slices are empty when the generation does not keep diagnostics.
pub(super) struct Outputs<'a> {
    pub positions: &'a mut [[f32; 3]],
    pub uvs: &'a mut [[f32; 2]],
    pub kinds: &'a mut [u32],
    pub distances: &'a mut [f32],
    pub colors: &'a mut [[u8; 4]],
    pub layers: &'a mut [[u8; 3]],
    pub raws: &'a mut [f32],
    pub moved: &'a mut [bool],
    pub rings: &'a mut [u8],
    pub heights: &'a mut [f32],
    /// The slot of `heights[0]`.
    pub first_slot: usize,
}

/// `s` split at `mid`, or two empty halves when `s` is empty (an unused diagnostic).
fn split_opt<T>(s: &mut [T], mid: usize) -> (&mut [T], &mut [T]) {
    s.split_at_mut(mid.min(s.len()))
}

impl Outputs<'_> {
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// Splits at point `mid`, whose slot is `slot`.
    fn split_at(self, mid: usize, slot: usize) -> (Self, Self) {
        let (p0, p1) = self.positions.split_at_mut(mid);
        let (u0, u1) = self.uvs.split_at_mut(mid);
        let (k0, k1) = self.kinds.split_at_mut(mid);
        let (d0, d1) = self.distances.split_at_mut(mid);
        let (c0, c1) = split_opt(self.colors, mid);
        let (l0, l1) = split_opt(self.layers, mid);
        let (r0, r1) = split_opt(self.raws, mid);
        let (m0, m1) = split_opt(self.moved, mid);
        let (g0, g1) = split_opt(self.rings, mid);
        let (h0, h1) = self.heights.split_at_mut(slot - self.first_slot);
        let first = Outputs {
            positions: p0,
            uvs: u0,
            kinds: k0,
            distances: d0,
            colors: c0,
            layers: l0,
            raws: r0,
            moved: m0,
            rings: g0,
            heights: h0,
            first_slot: self.first_slot,
        };
        let second = Outputs {
            positions: p1,
            uvs: u1,
            kinds: k1,
            distances: d1,
            colors: c1,
            layers: l1,
            raws: r1,
            moved: m1,
            rings: g1,
            heights: h1,
            first_slot: slot,
        };
        (first, second)
    }
}

/// Runs `f(start, outputs)` on batches of at most [`BATCH`] points (`start` is the index of the
/// first; `slot_of(i)` the slot of point `i`), on all cores when splitting.
pub(super) fn in_batches<F: Fn(usize, Outputs<'_>) + Sync>(
    split: Split,
    out: Outputs<'_>,
    start: usize,
    slot_of: &(impl Fn(usize) -> usize + Sync),
    f: &F,
) {
    if out.len() <= BATCH {
        f(start, out);
    } else {
        let mid = (out.len() / BATCH).div_ceil(2) * BATCH;
        let (a, b) = out.split_at(mid, slot_of(start + mid));
        split.join(|| in_batches(split, a, start, slot_of, f), || in_batches(split, b, start + mid, slot_of, f));
    }
}
