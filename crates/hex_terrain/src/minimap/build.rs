//! Building a picture: which tile each pixel shows, its tile's nearest edge and its color
//! before any state (biome or type, rivers, lakes).

use hexx::Hex;

use super::{Minimap, MinimapStyle, NONE, index_in};
use crate::chunk::TileRect;
use crate::terrain::Terrain;
use crate::vocab::TileKind;

impl Minimap {
    /// The picture of `region` (offset coordinates; clipped to a bounded map's tiles), at most
    /// `max_size` pixels (each side at least 1): the largest that fits with square pixels. On a
    /// wrapping map a region spanning the map's width is drawn over exactly one period. `None`
    /// when no tile of the region is on the map.
    #[must_use]
    pub fn new(terrain: &Terrain, region: TileRect, max_size: [u32; 2], style: MinimapStyle) -> Option<Self> {
        let region = clip(region, terrain.bounds())?;
        let geometry = terrain.geometry();
        let lattice = geometry.lattice();
        let center = |tile: Hex| lattice.world(lattice.tile_center(tile));
        let s = geometry.hex_size();
        let half = match terrain.layout().orientation {
            hexx::HexOrientation::Flat => [s, s * 3f64.sqrt() / 2.0],
            hexx::HexOrientation::Pointy => [s * 3f64.sqrt() / 2.0, s],
        };
        // The world box of the region: its edge tiles' centers, grown by a tile's half extents.
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        let [w, h] = [region.max[0] - region.min[0], region.max[1] - region.min[1]];
        // The band of the two outer rows and columns (odd columns or rows are shoved half a
        // tile): the tiles whose extents can reach the box's edges.
        let edge = |v: i32, min: i32, max: i32| v < min + 2 || v >= max - 2;
        for [col, row] in region.iter() {
            if !edge(col, region.min[0], region.max[0]) && !edge(row, region.min[1], region.max[1]) {
                continue;
            }
            for (axis, c) in center(terrain.tile_from_offset([col, row])).into_iter().enumerate() {
                lo[axis] = lo[axis].min(c - half[axis]);
                hi[axis] = hi[axis].max(c + half[axis]);
            }
        }
        let period = terrain.wrap().filter(|wrap| w >= wrap.columns).map(|wrap| wrap.width);
        let [mw, mh] = max_size.map(|m| f64::from(m.clamp(1, 1 << 14)));
        let extent = [period.unwrap_or(hi[0] - lo[0]), hi[1] - lo[1]];
        let mut step = (extent[0] / mw).max(extent[1] / mh);
        let mut width = (extent[0] / step).ceil().clamp(1.0, mw);
        if let Some(period) = period {
            // Exactly one period across, so the picture wraps as the map does: the strip starts
            // half a column west of the first column's center.
            width = (period / step).round().clamp(1.0, mw);
            step = period / width;
            let first = center(terrain.tile_from_offset([region.min[0], region.min[1]]))[0];
            let column = period / f64::from(w);
            lo[0] = first - column / 2.0;
        }
        let height = (extent[1] / step).ceil().clamp(1.0, mh);
        let size = [width as u32, height as u32];
        let directions = neighbor_directions(terrain);
        let apothem = directions[0].1;

        let index = |tile: Hex| index_in(terrain, region, tile);
        let tiles: Vec<Hex> =
            (0..w * h).map(|i| terrain.tile_from_offset([region.min[0] + i % w, region.min[1] + i / w])).collect();
        let neighbors: Vec<[u32; 6]> = tiles
            .iter()
            .map(|&t| t.all_neighbors().map(|n| terrain.wrap_tile(n).and_then(index).unwrap_or(NONE)))
            .collect();
        let colors: Vec<[u8; 3]> = tiles.iter().map(|&t| tile_color(terrain, &style, t)).collect();
        let rivers: Vec<Vec<usize>> = tiles.iter().map(|&t| river_slots(terrain, t)).collect();
        // Rivers on edges: which edges of each tile carry one.
        let edge_rivers: Vec<u8> = tiles
            .iter()
            .map(|&t| terrain.river_edges(t).iter().fold(0, |m, r| m | 1 << r.edge.direction.index()))
            .collect();
        let river_half = (style.river_width * s / 2.0).max(0.6 * step).min(0.5 * apothem);

        let pixels = (size[0] * size[1]) as usize;
        let (mut pixel_tile, mut pixel_edge, mut base) =
            (vec![NONE; pixels], vec![(0u8, 0f32); pixels], vec![style.background; pixels]);
        for py in 0..size[1] {
            for px in 0..size[0] {
                let i = (py * size[0] + px) as usize;
                let x = lo[0] + (f64::from(px) + 0.5) * step;
                let z = lo[1] + (f64::from(py) + 0.5) * step;
                let (Some(tile), Some(own)) = (geometry.unwrapped_tile_at(x, z), geometry.tile_at(x, z)) else {
                    continue;
                };
                let Some(t) = index(own).filter(|_| terrain.contains(own)) else { continue };
                let c = center(tile);
                let d = [x - c[0], z - c[1]];
                let (slot, distance) = directions
                    .iter()
                    .enumerate()
                    .map(|(k, &(n, a))| (k, a - (d[0] * n[0] + d[1] * n[1])))
                    .fold((0, f64::INFINITY), |best, e| if e.1 < best.1 { e } else { best });
                pixel_tile[i] = t;
                pixel_edge[i] = (slot as u8, (distance / s) as f32);
                let mut color = colors[t as usize];
                let on_edge = edge_rivers[t as usize] & (1 << slot) != 0 && distance < river_half;
                if on_edge
                    || rivers[t as usize]
                        .iter()
                        .any(|&k| segment_distance(d, directions[k].0, directions[k].1) < river_half)
                {
                    color = style.water_color;
                }
                base[i] = [color[0], color[1], color[2], 255];
            }
        }
        let mut tile_start = vec![0u32; tiles.len() + 1];
        for &t in pixel_tile.iter().filter(|&&t| t != NONE) {
            tile_start[t as usize + 1] += 1;
        }
        for k in 1..tile_start.len() {
            tile_start[k] += tile_start[k - 1];
        }
        let mut fill = tile_start.clone();
        let mut tile_pixels = vec![0u32; *tile_start.last().unwrap_or(&0) as usize];
        for (i, &t) in pixel_tile.iter().enumerate().filter(|(_, t)| **t != NONE) {
            tile_pixels[fill[t as usize] as usize] = i as u32;
            fill[t as usize] += 1;
        }
        Some(Self {
            terrain: terrain.clone(),
            style,
            region,
            size,
            origin: lo,
            step,
            wraps: period.is_some(),
            pixel_tile,
            pixel_edge,
            base,
            neighbors,
            tile_start,
            tile_pixels,
        })
    }
}

/// `region` inside a bounded map's tiles; `None` when nothing is left.
fn clip(region: TileRect, bounds: Option<TileRect>) -> Option<TileRect> {
    let r = match bounds {
        Some(b) => TileRect {
            min: [region.min[0].max(b.min[0]), region.min[1].max(b.min[1])],
            max: [region.max[0].min(b.max[0]), region.max[1].min(b.max[1])],
        },
        None => region,
    };
    (r.max[0] > r.min[0] && r.max[1] > r.min[1]).then_some(r)
}

/// The unit vector toward each neighbor's center (in [`Hex::all_neighbors`] order) and the
/// distance from a tile's center to that edge.
fn neighbor_directions(terrain: &Terrain) -> [([f64; 2], f64); 6] {
    let lattice = terrain.lattice();
    let center = lattice.world(lattice.tile_center(Hex::ZERO));
    Hex::ZERO.all_neighbors().map(|n| {
        let c = lattice.world(lattice.tile_center(n));
        let d = [c[0] - center[0], c[1] - center[1]];
        let len = d[0].hypot(d[1]);
        ([d[0] / len, d[1] / len], len / 2.0)
    })
}

/// Distance of local point `d` to the segment from the tile's center to the midpoint of the edge
/// in direction `n` (`length` away).
fn segment_distance(d: [f64; 2], n: [f64; 2], length: f64) -> f64 {
    let along = (d[0] * n[0] + d[1] * n[1]).clamp(0.0, length);
    (d[0] - n[0] * along).hypot(d[1] - n[1] * along)
}

/// The tile's color before any state: lakes in water; on a map with its own terrain ruleset its
/// feature's (else its terrain's) minimap color; a biome's color on maps with climate or
/// rivers; the tile type's color otherwise.
fn tile_color(terrain: &Terrain, style: &MinimapStyle, tile: Hex) -> [u8; 3] {
    if terrain.lake(tile).is_some() {
        return style.water_color;
    }
    if terrain.has_own_ruleset() {
        let t = terrain.pipeline().tile_terrain(tile);
        let ruleset = terrain.ruleset();
        let look = t.feature.map_or(&ruleset.terrain(t.terrain).look, |f| &ruleset.feature(f).look);
        return look.minimap.unwrap_or(look.color);
    }
    if terrain.has_vertex_colors() {
        return terrain.pipeline().tile_biome(tile).color();
    }
    style.kind_colors[terrain.tile_kind(tile).unwrap_or(TileKind::Sea) as usize]
}

/// The neighbor slots a tile's river runs to: downstream and every upstream neighbor.
fn river_slots(terrain: &Terrain, tile: Hex) -> Vec<usize> {
    let Some(river) = terrain.river(tile) else { return Vec::new() };
    let neighbors = tile.all_neighbors().map(|n| terrain.wrap_tile(n));
    river
        .downstream
        .into_iter()
        .chain(river.upstream.iter().copied())
        .filter_map(|to| neighbors.iter().position(|&n| n == terrain.wrap_tile(to)))
        .collect()
}
