//! The indices pass: each tile's triangles as point numbers, from the template's triangle table
//! and the grid.
//!
//! Points are numbered in slot order, and every slot of a template row holds a point (of the
//! tile or of a neighbor), so along a row the numbers run on by one: a template point's number
//! is the number of its row's first point plus its column in the row. A tile then needs one
//! grid lookup a row, not a point, and the numbers of its triangle table are that of the
//! center row's first point plus offsets that depend only on how the rows' first numbers lie
//! around it ([`Rows::relative`]). Those are the same for the tiles of one row of the map away
//! from its ragged top and bottom edges, so a task keeps the offsets of the last two such
//! layouts it met (two, for the staggered tiles of a flat map's row) and writes most tiles as
//! one number added to a table: a loop the compiler vectorises, not a gather a point.

use hexx::Hex;

use super::grid::{GridShape, Points};
use super::lanes;
use super::parallel::Split;
use crate::heights::Kernel;
use crate::lattice::Lattice;

/// Tiles a task of the pass takes together.
const TILES: usize = 64;

/// The template's rows and its triangle table in row terms.
pub(super) struct Rows {
    /// Slot offset of each row's first point from the tile's center, by the center's parity.
    firsts: [Vec<isize>; 2],
    /// The row of the center.
    center: usize,
    /// For each index of the triangle table: its point's row.
    row_of: Vec<usize>,
    /// For each index of the triangle table: its point's column in the row.
    column: Vec<u32>,
}

/// The offsets of one layout: each table index's number less the center row's first number.
struct Layout {
    /// The rows' first numbers less the center row's.
    key: Vec<u32>,
    offsets: Vec<u32>,
}

impl Rows {
    pub fn new(lattice: &Lattice, shape: &GridShape) -> Self {
        let n = lattice.subdivisions() as i32;
        let template = lattice.template();
        // A template point's row is its lattice row (`y` for flat tiles, `x` for pointy), its
        // column the steps from the row's first point; rows run from `-n` to `n`.
        let pointy = lattice.orientation() == crate::config::Orientation::Pointy;
        let row = |h: Hex| if pointy { (h.x, h.y) } else { (h.y, h.x) };
        // The first step along each row, rows `-n..=n` at `0..=2n`.
        let mut first_along = vec![i32::MAX; 2 * n as usize + 1];
        for tp in template {
            let (r, a) = row(tp.offset);
            let f = &mut first_along[(r + n) as usize];
            *f = (*f).min(a);
        }
        let firsts = [0, 1].map(|parity| {
            (-n..=n)
                .zip(&first_along)
                .map(|(r, &a)| shape.offset(parity, if pointy { Hex::new(r, a) } else { Hex::new(a, r) }))
                .collect()
        });
        let (mut row_of, mut column) = (Vec::new(), Vec::new());
        for &k in lattice.template_triangle_indices().as_flattened() {
            let (r, a) = row(template[usize::from(k)].offset);
            let r = (r + n) as usize;
            row_of.push(r);
            column.push((a - first_along[r]) as u32);
        }
        Self { firsts, center: n as usize, row_of, column }
    }

    /// The first number of each row of the tile centered on `center` into `firsts`.
    #[inline(always)]
    fn firsts(&self, points: &Points, center: Hex, firsts: &mut [u32]) {
        let base = points.grid.slot(center);
        for (f, &d) in firsts.iter_mut().zip(&self.firsts[points.grid.shape.parity(center)]) {
            *f = points.grid.slots[base.wrapping_add_signed(d)];
        }
    }

    /// Each table index's number less the center row's first number, for rows whose first
    /// numbers less the center row's are `key`.
    fn relative(&self, key: &[u32], out: &mut Vec<u32>) {
        out.clear();
        out.extend(self.row_of.iter().zip(&self.column).map(|(&r, &c)| key[r].wrapping_add(c)));
    }
}

impl Rows {
    /// Triangle indices of `tiles`, tile by tile, from the template's triangles and the grid, on
    /// the job's `split` with loops compiled for its `kernel`.
    pub(super) fn indices_pass(
        &self,
        split: Split,
        kernel: Kernel,
        lattice: &Lattice,
        tiles: &[Hex],
        points: &Points,
        indices: &mut [u32],
    ) {
        let per_tile = self.row_of.len();
        split.for_each_chunk(indices, per_tile * TILES, 1, |g, out| {
            lanes::run(
                kernel,
                #[inline(always)]
                || self.indices_of(lattice, &tiles[g * TILES..], points, out),
            );
        });
    }

    /// The indices of `tiles` (from their first on, as many as `out` holds) into `out`.
    #[inline(always)]
    fn indices_of(&self, lattice: &Lattice, tiles: &[Hex], points: &Points, out: &mut [u32]) {
        let per_tile = self.row_of.len();
        let row_count = self.firsts[0].len();
        let mut layouts = [(); 2].map(|()| Layout { key: vec![u32::MAX; row_count], offsets: Vec::new() });
        let (mut firsts, mut key) = (vec![0; row_count], vec![0; row_count]);
        for (t, out) in out.chunks_mut(per_tile).enumerate() {
            let center = lattice.tile_center(tiles[t]);
            self.firsts(points, center, &mut firsts);
            let first = firsts[self.center];
            for (k, &f) in key.iter_mut().zip(&firsts) {
                *k = f.wrapping_sub(first);
            }
            // The most recent layout first; a new one replaces the older.
            if layouts[0].key != key {
                layouts.swap(0, 1);
                if layouts[0].key != key {
                    layouts[0].key.copy_from_slice(&key);
                    self.relative(&key, &mut layouts[0].offsets);
                }
            }
            for (d, &o) in out.iter_mut().zip(&layouts[0].offsets) {
                *d = first.wrapping_add(o);
            }
        }
    }
}
