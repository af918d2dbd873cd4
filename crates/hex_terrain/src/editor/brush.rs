//! Which tiles a stroke touches: a hex range around a tile, or a flood fill of the connected
//! tiles of one type.

use std::collections::{HashSet, VecDeque};

use hexx::Hex;

use crate::terrain::Terrain;

/// Most tiles a brush range reaches out from its tile.
pub const MAX_BRUSH_RADIUS: u32 = 16;

/// Most tiles one flood fill takes (on an unbounded map a sea has no end; the largest ocean of a
/// Civilization VI Huge map, 10,640 tiles in all, fits).
pub const MAX_FLOOD_TILES: usize = 1 << 14;

/// The tiles one stroke edits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum Brush {
    /// Every tile within this many steps of the stroke's tile (0: the tile alone), up to
    /// [`MAX_BRUSH_RADIUS`] (a stroke with more is refused: `EditError::Range`).
    Range(u32),
    /// The tiles connected to the stroke's tile through tiles of its type (sea, land or
    /// mountain), up to [`MAX_FLOOD_TILES`].
    Flood,
    /// The tiles connected to the stroke's tile through tiles of its terrain
    /// ([`TileInfo::terrain`](crate::TileInfo::terrain): its biome on a map without its own
    /// ruleset), up to [`MAX_FLOOD_TILES`].
    FloodTerrain,
}

impl Brush {
    /// The map's own tiles the brush covers around `tile` (on a wrapping map a range across the
    /// seam takes the map's tiles on the other side), each once, in a fixed order; none when
    /// `tile` is off the map or a range is above [`MAX_BRUSH_RADIUS`].
    #[must_use]
    pub fn tiles(self, terrain: &Terrain, tile: Hex) -> Vec<Hex> {
        let own = |t: Hex| terrain.wrap_tile(t);
        let Some(start) = own(tile) else { return Vec::new() };
        let mut seen = HashSet::new();
        let mut out = Vec::new();
        match self {
            Self::Range(radius) if radius > MAX_BRUSH_RADIUS => {}
            Self::Range(radius) => {
                for t in tile.range(radius) {
                    if let Some(t) = own(t)
                        && seen.insert(t)
                    {
                        out.push(t);
                    }
                }
            }
            Self::Flood | Self::FloodTerrain => {
                let class = |t: Hex| {
                    terrain.tile_info(t).map(|i| if self == Self::Flood { i.kind as u8 } else { i.terrain.terrain.0 })
                };
                return flood(start, class, |t| t.all_neighbors().into_iter().filter_map(own));
            }
        }
        out
    }
}

/// The tiles connected to `start` through tiles of its `class`, breadth first from it (each
/// tile's `neighbors` in their order), up to [`MAX_FLOOD_TILES`]: a flood brush's tiles on a
/// flat map or a globe.
pub(crate) fn flood<T, C, I>(start: T, class: impl Fn(T) -> C, neighbors: impl Fn(T) -> I) -> Vec<T>
where
    T: Copy + Eq + std::hash::Hash,
    C: PartialEq,
    I: IntoIterator<Item = T>,
{
    let kind = class(start);
    let mut seen = HashSet::from([start]);
    let mut queue = VecDeque::from([start]);
    let mut out = Vec::new();
    while let Some(t) = queue.pop_front() {
        out.push(t);
        if out.len() >= MAX_FLOOD_TILES {
            break;
        }
        for n in neighbors(t) {
            if !seen.contains(&n) && class(n) == kind {
                seen.insert(n);
                queue.push_back(n);
            }
        }
    }
    out
}
