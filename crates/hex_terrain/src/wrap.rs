//! East-west wrapping: a bounded map whose column `x + width` is column `x` (Civilization's
//! cylinder).
//!
//! Every point of the plane stands for one point of the map: its *canonical* point, shifted by
//! a whole number of periods into one strip of the width of the map. Heights, shapes, climate
//! and the tile table are read at the canonical point or tile, so a point and its copy one
//! period away get the same bits, and the mesh across the seam meets like two neighbouring
//! chunks. The shift is integer arithmetic on lattice coordinates: no rounding decides which
//! copy a point is.
//!
//! The noise itself must also join across the seam, or the heights would jump there: on a
//! wrapping map the fBm is periodic in x ([`Fbm::wrapped`](crate::heights::Fbm::wrapped)), each
//! octave's frequency rounded so the map's width holds a whole number of noise cells.
//!
//! Chunks of a wrapping map are numbered on, east and west, past the map: chunk column
//! `x = k * columns + i` is chunk `i` of the map (its canonical chunk) placed `k` periods east.
//! The last chunk of a period may be narrower than the others when the chunk width does not
//! divide the map's width.

use hexx::Hex;

use crate::chunk::ChunkCoord;
use crate::config::Orientation;
use crate::lattice::Lattice;

/// The period of a wrapping map in the coordinates each stage uses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wrap {
    /// Map width in columns.
    pub columns: i32,
    /// Axial tile translation of one period (the tile `columns` columns east of the origin
    /// tile, in the same row).
    pub tile_shift: Hex,
    /// Lattice translation of one period.
    pub lattice_shift: Hex,
    /// World x of one period.
    pub width: f64,
    /// Whether the lattice's x key is `2i + j` (flat tiles) rather than `i` (pointy).
    flat: bool,
    /// Key of one period.
    key_period: i64,
    /// First key of the canonical strip.
    key_start: i64,
    /// Chunk columns of one period.
    chunk_columns: i32,
    /// Chunk width in tiles.
    chunk_width: i32,
}

impl Wrap {
    /// The wrap of a map `columns` wide (`columns` even for flat tiles: the validation checks).
    pub(crate) fn new(lattice: &Lattice, columns: i32, chunk_width: u32) -> Self {
        let flat = lattice.orientation() == Orientation::Flat;
        // Odd columns (flat) or rows (pointy) are shoved: `columns` columns east in the same row
        // is (columns, -columns / 2) axially for flat tiles and (columns, 0) for pointy ones.
        let tile_shift = if flat { Hex::new(columns, -columns / 2) } else { Hex::new(columns, 0) };
        let lattice_shift = lattice.tile_center(tile_shift);
        let key = |p: Hex| if flat { 2 * i64::from(p.x) + i64::from(p.y) } else { i64::from(p.x) };
        let key_period = key(lattice_shift);
        // The strip starts half a column west of the first column's center.
        let column_keys = key_period / i64::from(columns);
        let chunk_width = chunk_width as i32;
        Self {
            columns,
            tile_shift,
            lattice_shift,
            width: lattice.world(lattice_shift)[0],
            flat,
            key_period,
            key_start: -column_keys / 2,
            chunk_columns: (columns + chunk_width - 1) / chunk_width,
            chunk_width,
        }
    }

    /// An integer proportional to the world x of a lattice point.
    #[inline]
    fn key(&self, p: Hex) -> i64 {
        if self.flat { 2 * i64::from(p.x) + i64::from(p.y) } else { i64::from(p.x) }
    }

    /// How many periods east of the canonical strip a lattice point lies.
    #[inline]
    #[must_use]
    pub fn point_period(&self, p: Hex) -> i32 {
        (self.key(p) - self.key_start).div_euclid(self.key_period) as i32
    }

    /// The canonical point of a lattice point: the same point of the map inside the canonical
    /// strip.
    #[inline]
    #[must_use]
    pub fn point(&self, p: Hex) -> Hex {
        let k = self.point_period(p);
        if k == 0 { p } else { p - self.lattice_shift * k }
    }

    /// How many periods east of the map a tile's column lies.
    #[inline]
    #[must_use]
    pub fn tile_period(&self, column: i32) -> i32 {
        column.div_euclid(self.columns)
    }

    /// Chunk columns of one period.
    #[must_use]
    pub fn chunk_columns(&self) -> i32 {
        self.chunk_columns
    }

    /// The chunk of the map a chunk stands for, and how many periods east it is placed.
    #[must_use]
    pub fn chunk(&self, chunk: ChunkCoord) -> (ChunkCoord, i32) {
        let k = chunk.x.div_euclid(self.chunk_columns);
        // `chunk.x.rem_euclid` without the product, which overflows for the westmost chunks.
        (ChunkCoord::new(chunk.x.rem_euclid(self.chunk_columns), chunk.z), k)
    }

    /// The chunk holding offset coordinate `[col, row]` (any column).
    #[must_use]
    pub fn chunk_of(&self, [col, row]: [i32; 2], chunk_height: u32) -> ChunkCoord {
        let k = self.tile_period(col);
        let local = col - k * self.columns;
        ChunkCoord::new(k * self.chunk_columns + local / self.chunk_width, row.div_euclid(chunk_height as i32))
    }
}
