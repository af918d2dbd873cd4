//! Chunks: rectangular ranges of tiles in offset coordinates, and which chunks a map has.

use serde::{Deserialize, Serialize};

/// A rectangle of tiles in offset coordinates `[col, row]`: columns `min[0]..max[0]`, rows
/// `min[1]..max[1]` (ends exclusive).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct TileRect {
    /// First column and row.
    pub min: [i32; 2],
    /// One past the last column and row.
    pub max: [i32; 2],
}

impl TileRect {
    /// A rectangle from its first tile and size.
    #[must_use]
    pub fn new(min: [i32; 2], size: [u32; 2]) -> Self {
        Self { min, max: [min[0] + size[0] as i32, min[1] + size[1] as i32] }
    }

    /// Whether no tile is inside.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.max[0] <= self.min[0] || self.max[1] <= self.min[1]
    }

    /// Number of tiles.
    #[must_use]
    pub fn len(&self) -> usize {
        if self.is_empty() {
            0
        } else {
            ((self.max[0] - self.min[0]) as usize) * ((self.max[1] - self.min[1]) as usize)
        }
    }

    /// Whether offset coordinate `[col, row]` is inside.
    #[must_use]
    pub fn contains(&self, [col, row]: [i32; 2]) -> bool {
        col >= self.min[0] && col < self.max[0] && row >= self.min[1] && row < self.max[1]
    }

    /// Row-major index of offset coordinate `[col, row]` (the order of [`TileRect::iter`]),
    /// `None` outside.
    #[must_use]
    #[inline]
    pub fn index(&self, [col, row]: [i32; 2]) -> Option<usize> {
        let width = (self.max[0] - self.min[0]) as usize;
        self.contains([col, row]).then(|| (row - self.min[1]) as usize * width + (col - self.min[0]) as usize)
    }

    /// The overlap of two rectangles (possibly empty).
    #[must_use]
    pub fn intersect(&self, other: &Self) -> Self {
        Self {
            min: [self.min[0].max(other.min[0]), self.min[1].max(other.min[1])],
            max: [self.max[0].min(other.max[0]), self.max[1].min(other.max[1])],
        }
    }

    /// The rectangle grown by `by` tiles on every side.
    #[must_use]
    pub fn grow(&self, by: i32) -> Self {
        Self { min: [self.min[0] - by, self.min[1] - by], max: [self.max[0] + by, self.max[1] + by] }
    }

    /// Offset coordinates inside, row by row.
    pub fn iter(&self) -> impl Iterator<Item = [i32; 2]> + use<> {
        let r = *self;
        (r.min[1]..r.max[1]).flat_map(move |row| (r.min[0]..r.max[0]).map(move |col| [col, row]))
    }
}

/// Coordinates of a chunk: chunk `(x, z)` covers columns `x * w .. (x + 1) * w` and rows
/// `z * h .. (z + 1) * h` for a chunk size of `(w, h)` tiles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct ChunkCoord {
    /// Chunk column.
    pub x: i32,
    /// Chunk row.
    pub z: i32,
}

impl ChunkCoord {
    /// A chunk coordinate.
    #[must_use]
    pub const fn new(x: i32, z: i32) -> Self {
        Self { x, z }
    }

    /// Its tiles, before clipping to a bounded map.
    #[must_use]
    pub fn rect(self, size: (u32, u32)) -> TileRect {
        let (w, h) = (size.0 as i32, size.1 as i32);
        TileRect { min: [self.x * w, self.z * h], max: [(self.x + 1) * w, (self.z + 1) * h] }
    }

    /// The chunk holding offset coordinate `[col, row]`.
    #[must_use]
    pub fn of([col, row]: [i32; 2], size: (u32, u32)) -> Self {
        Self { x: col.div_euclid(size.0 as i32), z: row.div_euclid(size.1 as i32) }
    }

    /// Chebyshev distance in chunks.
    #[must_use]
    pub fn distance(self, other: Self) -> u32 {
        (self.x - other.x).unsigned_abs().max((self.z - other.z).unsigned_abs())
    }
}
