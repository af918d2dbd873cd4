//! Where [`TileStates`](super::TileStates) keeps every tile's texel, by offset coordinate: a
//! dense array over a bounded map (one index a write), a hash map of the tiles not in the default
//! state over an unbounded one.

use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use hex_terrain::TileRect;

use super::window::{Texel, TexelSource};

/// Bounded maps up to this many tiles (32 MiB of texels) are stored densely.
const DENSE_TILES: usize = 1 << 22;

#[derive(Debug, Clone)]
pub(crate) enum TileStore {
    /// Every tile of a bounded map, row by row from `rect.min`.
    Dense { rect: TileRect, texels: Vec<Texel>, stored: usize },
    /// The tiles not in the default state.
    Sparse(HashMap<IVec2, Texel>),
}

impl Default for TileStore {
    fn default() -> Self {
        Self::Sparse(HashMap::default())
    }
}

impl TileStore {
    /// An empty store for a map's tiles (`None`: unbounded).
    pub fn new(bounds: Option<TileRect>) -> Self {
        match bounds {
            Some(rect) if rect.len() <= DENSE_TILES => {
                Self::Dense { rect, texels: vec![[0; 4]; rect.len()], stored: 0 }
            }
            _ => Self::default(),
        }
    }

    fn index(rect: &TileRect, oc: IVec2) -> Option<usize> {
        rect.contains(oc.to_array()).then(|| {
            let width = (rect.max[0] - rect.min[0]) as usize;
            (oc.y - rect.min[1]) as usize * width + (oc.x - rect.min[0]) as usize
        })
    }

    /// The texel of a tile (the default state when none is stored).
    pub fn get(&self, oc: IVec2) -> Texel {
        match self {
            Self::Dense { rect, texels, .. } => Self::index(rect, oc).map_or([0; 4], |i| texels[i]),
            Self::Sparse(map) => map.get(&oc).copied().unwrap_or_default(),
        }
    }

    /// Stores a texel (a dense store ignores tiles outside its map).
    pub fn set(&mut self, oc: IVec2, texel: Texel) {
        let empty = texel == [0; 4];
        match self {
            Self::Dense { rect, texels, stored } => {
                if let Some(i) = Self::index(rect, oc) {
                    let was_empty = texels[i] == [0; 4];
                    texels[i] = texel;
                    *stored = *stored + usize::from(was_empty && !empty) - usize::from(!was_empty && empty);
                }
            }
            Self::Sparse(map) => {
                if empty {
                    map.remove(&oc);
                } else {
                    map.insert(oc, texel);
                }
            }
        }
    }

    /// Tiles not in the default state.
    pub fn len(&self) -> usize {
        match self {
            Self::Dense { stored, .. } => *stored,
            Self::Sparse(map) => map.len(),
        }
    }

    /// The tiles not in the default state, with their texels.
    pub fn stored(&self) -> Vec<(IVec2, Texel)> {
        match self {
            Self::Dense { rect, texels, .. } => {
                rect.iter().zip(texels).filter(|(_, t)| **t != [0; 4]).map(|(oc, t)| (IVec2::from(oc), *t)).collect()
            }
            Self::Sparse(map) => map.iter().map(|(oc, t)| (*oc, *t)).collect(),
        }
    }
}

impl TexelSource for TileStore {
    fn texel(&self, oc: IVec2) -> Texel {
        self.get(oc)
    }

    fn each_stored_in(&self, rect: IRect, f: &mut dyn FnMut(IVec2, Texel)) -> bool {
        let Self::Sparse(map) = self else { return false };
        // Walking the map's entries costs a few nanoseconds each, a lookup of every tile of
        // `rect` tens: walk them unless the map holds far more tiles than `rect`.
        if map.len() >= 16 * rect.width() as usize * rect.height() as usize {
            return false;
        }
        for (&oc, &texel) in map {
            if oc.x >= rect.min.x && oc.x < rect.max.x && oc.y >= rect.min.y && oc.y < rect.max.y {
                f(oc, texel);
            }
        }
        true
    }
}
