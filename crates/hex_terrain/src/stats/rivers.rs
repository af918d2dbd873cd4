//! The rivers of a map as [`MapStats`](super::MapStats) counts them, for both river models:
//! systems, tiles on a river, lengths from each source to its mouth, sources near relief, and
//! the mouths at the map's edge.

use std::collections::HashMap;

use hexx::Hex;

use super::RiverStats;
use crate::info::TileInfo;
use crate::terrain::Terrain;
use crate::vocab::{Biome, TileKind};

/// The river systems, river tiles, the longest river, its sources and mouths; and whether each
/// map tile (row by row) is on a river.
pub(super) fn rivers(
    terrain: &Terrain,
    tiles: &[Hex],
    neighbors: &[[Option<u32>; 6]],
    infos: &[TileInfo],
    biomes: &[Biome],
) -> (RiverStats, Vec<bool>) {
    let water = |i: usize| infos[i].kind == TileKind::Sea || infos[i].lake.is_some();
    // Tiles within 2 steps of relief (a mountain or a hill).
    let relief =
        |i: usize| (infos[i].kind == TileKind::Mountain && infos[i].lake.is_none()) || biomes[i] == Biome::Hills;
    let mut near = vec![u8::MAX; tiles.len()];
    let mut queue: std::collections::VecDeque<usize> = (0..tiles.len()).filter(|&i| relief(i)).collect();
    for &i in &queue {
        near[i] = 0;
    }
    while let Some(i) = queue.pop_front() {
        if near[i] >= 2 {
            continue;
        }
        for n in neighbors[i].iter().flatten().map(|&n| n as usize) {
            if near[n] == u8::MAX {
                near[n] = near[i] + 1;
                queue.push_back(n);
            }
        }
    }
    let median = |mut lengths: Vec<u32>| {
        lengths.sort_unstable();
        lengths.get(lengths.len().saturating_sub(1) / 2).copied().unwrap_or(0)
    };
    if let Some(network) = terrain.pipeline().table().and_then(|t| t.edge_rivers()) {
        let f = network.figures();
        // A mouth at the map's edge: a corner past the map touching no water.
        let at_edge = |m: &[Option<usize>; 3]| m.iter().any(Option::is_none) && !m.iter().flatten().any(|&t| water(t));
        let stats = RiverStats {
            systems: f.systems,
            tiles: f.tiles,
            edges: f.edges,
            longest: f.longest,
            sources: f.sources.len() as u32,
            median: median(f.sources.iter().map(|s| s.0).collect()),
            sources_near_relief: f.sources.iter().filter(|s| s.1.iter().any(|&t| near[t] <= 2)).count() as u32,
            mouths_at_edge: f.mouths.iter().filter(|m| at_edge(m)).count() as u32,
        };
        return (stats, (0..tiles.len()).map(|i| network.edges_of(i) != 0).collect());
    }
    let rivers = terrain.rivers();
    let by_tile: HashMap<Hex, usize> = rivers.iter().enumerate().map(|(i, r)| (r.hex, i)).collect();
    let tile_index: HashMap<Hex, usize> = tiles.iter().enumerate().map(|(i, &h)| (h, i)).collect();
    let next = |i: usize| rivers[i].downstream.and_then(|d| by_tile.get(&d).copied());
    // Tiles from each river tile to its mouth, computed from the mouths up (rivers never rise,
    // so following downstream ends).
    let to_mouth = crate::water::steps_to_mouth(rivers.len(), 0..rivers.len(), next);
    let sources: Vec<usize> = (0..rivers.len()).filter(|&i| rivers[i].upstream.is_empty()).collect();
    let mut on_river = vec![false; tiles.len()];
    for r in &rivers {
        on_river[tile_index[&r.hex]] = true;
    }
    let stats = RiverStats {
        systems: (0..rivers.len()).filter(|&i| next(i).is_none()).count() as u32,
        tiles: rivers.len() as u32,
        edges: 0,
        longest: to_mouth.iter().copied().max().unwrap_or(0),
        sources: sources.len() as u32,
        median: median(sources.iter().map(|&i| to_mouth[i]).collect()),
        sources_near_relief: sources
            .iter()
            .filter(|&&i| tile_index.get(&rivers[i].hex).is_some_and(|&t| near[t] <= 2))
            .count() as u32,
        mouths_at_edge: rivers.iter().filter(|r| r.downstream.is_none()).count() as u32,
    };
    (stats, on_river)
}
