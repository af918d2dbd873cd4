//! What an operation changed: the tiles whose look or data changed and the chunks whose meshes
//! must be built again; nothing else is regenerated.

use std::collections::HashSet;

use hexx::Hex;

use crate::chunk::ChunkCoord;
use crate::setup::{PlacedResource, PlacedWonder};
use crate::terrain::Terrain;

/// What one operation (or its undo) changed.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct Change {
    /// The map's own tiles that changed: the edited tiles and their neighbors (whose shared
    /// border vertices moved), and every tile whose type, elevation, biome, river or lake
    /// changed as a consequence (rivers drain whole basins), with their neighbors, or whose game
    /// setup marker (start, resource, wonder) moved. Sorted by `(y, x)` of the axial
    /// coordinate, each once. (A lake's id may change without the lake changing, when a lake
    /// before it in the ids' order appears or goes.)
    pub tiles: Vec<Hex>,
    /// The map's own tiles whose edits the operation changed (what the stroke edited, or what
    /// its undo or redo set back), a part of `tiles`. Sorted by `(y, x)`, each once.
    pub edited: Vec<Hex>,
    /// The chunks holding `tiles` or a neighbor of one (a chunk's mesh holds its tiles'
    /// border vertices and normals, shared with the next chunk): the meshes to build again.
    /// Chunks of the map (on a wrapping map, the chunks its copies show). Sorted by `(z, x)`,
    /// each once.
    pub chunks: Vec<ChunkCoord>,
}

impl Change {
    /// Whether nothing changed.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.tiles.is_empty()
    }

    /// The change from `old` to `new`, two compilations of one map whose edits differ on the
    /// `touched` tiles.
    pub(super) fn between(old: &Terrain, new: &Terrain, touched: &[Hex]) -> Self {
        let mut tiles = HashSet::new();
        for &t in touched {
            tiles.insert(t);
            tiles.extend(new.neighbors(t).into_iter().flatten().flatten());
        }
        if let (Some(a), Some(b)) = (old.pipeline().table(), new.pipeline().table()) {
            // Rivers, lakes and biomes reach past the edited tiles: compare every tile's row of
            // the two tables (cheap), and take the neighbors of a tile that changed too (its
            // border vertices follow its type).
            let geometry = new.geometry();
            for t in new.tiles() {
                let changed = b.index(geometry, t).is_none_or(|i| !a.same_tile(b, i));
                if changed || marker(old, t) != marker(new, t) {
                    tiles.insert(t);
                    tiles.extend(new.neighbors(t).into_iter().flatten().flatten());
                }
            }
        } else if new.bounds().is_some() {
            // A bounded map without a table: compare every tile.
            for t in new.tiles() {
                if old.tile_info(t) != new.tile_info(t) || marker(old, t) != marker(new, t) {
                    tiles.insert(t);
                }
            }
        } else {
            // Without a tile table, a tile depends on its own heights and its neighbors' types.
            let near: HashSet<Hex> = touched.iter().flat_map(|t| t.range(2)).filter_map(|t| new.wrap_tile(t)).collect();
            for r in near {
                if old.tile_info(r) != new.tile_info(r) {
                    tiles.insert(r);
                }
            }
        }
        let mut chunks = HashSet::new();
        for &t in &tiles {
            let around = new.neighbors(t).into_iter().flatten().flatten();
            for c in std::iter::once(t).chain(around).filter_map(|t| new.chunk_of(t)) {
                chunks.insert(new.wrap_chunk(c).0);
            }
        }
        let mut tiles: Vec<Hex> = tiles.into_iter().collect();
        tiles.sort_by_key(|t| (t.y, t.x));
        let mut edited = touched.to_vec();
        edited.sort_by_key(|t| (t.y, t.x));
        edited.dedup();
        let mut chunks: Vec<ChunkCoord> = chunks.into_iter().collect();
        chunks.sort_by_key(|c| (c.z, c.x));
        Self { tiles, edited, chunks }
    }
}

/// What the game setup put on a tile (start, resource, wonder), for comparing two maps.
fn marker(terrain: &Terrain, tile: Hex) -> (Option<u32>, Option<&PlacedResource>, Option<&PlacedWonder>) {
    if terrain.setup().is_none() {
        return (None, None, None);
    }
    (terrain.start(tile), terrain.resource(tile), terrain.wonder(tile))
}
