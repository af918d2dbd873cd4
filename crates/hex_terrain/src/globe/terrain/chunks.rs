//! A globe's chunks: the two poles, and parallelograms of `chunk_size.0` tiles in each of the ten
//! diamonds; which chunk holds a tile or a direction, and which chunks have ground within an
//! angle of a direction (each chunk's cap, found once).

use super::super::GlobeTile;
use super::super::atlas::Spot;
use super::super::project::{self, Dir};
use super::GlobeTerrain;

/// A piece of a globe generated at once: a pole's tile, or a parallelogram of at most
/// `chunk_size.0` by `chunk_size.0` tiles of a diamond.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum GlobeChunk {
    /// The north pole's pentagon.
    North,
    /// The south pole's pentagon.
    South,
    /// Rows `row * side..` and columns `column * side..` of a diamond (0-4 northern, 5-9
    /// southern), `side` being the config's `chunk_size.0`.
    Diamond {
        /// The diamond.
        diamond: u8,
        /// The chunk's row in the diamond.
        row: u32,
        /// The chunk's column in the diamond.
        column: u32,
    },
}

impl GlobeTerrain {
    /// The chunk holding the tile a direction falls in: the chunk nearest it.
    #[must_use]
    pub fn chunk_at(&self, direction: [f64; 3]) -> Option<GlobeChunk> {
        self.chunk_of(self.tile_at(direction)?)
    }

    /// The chunks with ground within `angle` radians of a direction (what streaming around a
    /// point of view asks), in [`GlobeTerrain::chunks`]' order: every chunk holding a point that
    /// close, and only chunks whose cap (the circle round their middle that holds their ground)
    /// reaches that close. Empty for a zero or non-finite direction or a negative or NaN angle.
    #[must_use]
    pub fn chunks_within(&self, direction: [f64; 3], angle: f64) -> Vec<GlobeChunk> {
        let len = project::dot(direction, direction).sqrt();
        if !len.is_finite() || len == 0.0 || angle.is_nan() || angle < 0.0 {
            return Vec::new();
        }
        let dir = project::normalize(direction);
        self.caps
            .get_or_init(|| self.caps())
            .iter()
            .filter(|(_, middle, radius)| arc(dir, *middle) <= angle + radius)
            .map(|&(chunk, _, _)| chunk)
            .collect()
    }

    /// Every chunk's cap: its tiles' centers' mean direction, and the largest angle from it to
    /// a corner of a triangle of its tiles (found on its outline: the tiles with a neighbor in
    /// another chunk).
    fn caps(&self) -> Vec<(GlobeChunk, Dir, f64)> {
        self.chunks()
            .into_iter()
            .map(|chunk| {
                let tiles = self.chunk_tiles(chunk);
                let sum = tiles.iter().fold([0.0; 3], |s, &t| {
                    let c = self.direction(self.fine.center(self.spot(t)));
                    [s[0] + c[0], s[1] + c[1], s[2] + c[2]]
                });
                let middle = project::normalize(sum);
                let outline = tiles.iter().filter(|&&t| {
                    let neighbors = self.grid.neighbors(t).expect("a tile of the grid");
                    neighbors.as_slice().iter().any(|&m| self.chunk_of(m) != Some(chunk))
                });
                let radius = outline
                    .flat_map(|&t| self.fine.tile_points(self.spot(t)))
                    .map(|p| arc(middle, self.direction(p)))
                    .fold(0.0, f64::max);
                (chunk, middle, radius)
            })
            .collect()
    }

    /// The side of a diamond's chunks, in tiles.
    fn side(&self) -> u32 {
        self.config.chunk_size.0.min(self.grid.frequency())
    }

    /// Every chunk: the two poles and each diamond's parallelograms, row by row.
    #[must_use]
    pub fn chunks(&self) -> Vec<GlobeChunk> {
        let per = self.grid.frequency().div_ceil(self.side());
        let mut out = vec![GlobeChunk::North];
        for diamond in 0..10 {
            for row in 0..per {
                out.extend((0..per).map(|column| GlobeChunk::Diamond { diamond, row, column }));
            }
        }
        out.push(GlobeChunk::South);
        out
    }

    /// The chunk holding a tile; `None` for a tile not of this globe.
    #[must_use]
    pub fn chunk_of(&self, tile: GlobeTile) -> Option<GlobeChunk> {
        let s = self.side();
        Some(match self.grid.spot(tile)? {
            Spot::North => GlobeChunk::North,
            Spot::South => GlobeChunk::South,
            Spot::Diamond { d, i, j } => GlobeChunk::Diamond { diamond: d, row: i / s, column: j / s },
        })
    }

    /// A chunk's tiles, by id; empty for a chunk not of this globe.
    #[must_use]
    pub fn chunk_tiles(&self, chunk: GlobeChunk) -> Vec<GlobeTile> {
        let (f, s) = (self.grid.frequency(), self.side());
        match chunk {
            GlobeChunk::North => vec![self.grid.id(Spot::North)],
            GlobeChunk::South => vec![self.grid.id(Spot::South)],
            GlobeChunk::Diamond { diamond, row, column } if diamond < 10 && row * s < f && column * s < f => {
                let rows = row * s..((row + 1) * s).min(f);
                rows.flat_map(|i| {
                    ((column * s)..((column + 1) * s).min(f))
                        .map(move |j| self.grid.id(Spot::Diamond { d: diamond, i, j }))
                })
                .collect()
            }
            GlobeChunk::Diamond { .. } => Vec::new(),
        }
    }
}

/// The angle between two unit vectors, in radians.
fn arc(a: Dir, b: Dir) -> f64 {
    project::dot(a, b).clamp(-1.0, 1.0).acos()
}
