//! A real landscape: the Jacksboro fault area's elevation (U.S. Geological Survey data, see
//! `assets/dem/README.md`) tiled with rivers on the tile edges. Its rivers follow the valleys that
//! an independent flow model finds in the elevation itself: steepest descent (D8) over the
//! image averaged to about the tiles' resolution, each cell passing what it collects to its
//! lowest neighbor, computed here.

use hex_terrain::hexx::Hex;
use hex_terrain::{HeightImage, MapConfig, Terrain};

fn assets() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../bevy_hex_terrain/assets")
}

/// How many pixels drain through each pixel of the image averaged over blocks of `block` x
/// `block` pixels (each block's count in pixels), by steepest descent to one of its eight
/// neighbors; a block with no lower neighbor keeps what it collects. Returns the grid's width,
/// height and counts.
fn d8(image: &HeightImage, block: usize) -> (usize, usize, Vec<f64>) {
    let (iw, ih) = image.size();
    let (w, h) = (iw / block, ih / block);
    let at = |x: usize, y: usize| image.sample(x as f64 / (iw - 1) as f64, y as f64 / (ih - 1) as f64);
    let height: Vec<f64> = (0..w * h)
        .map(|i| {
            let (bx, by) = (i % w * block, i / w * block);
            let sum: f64 = (0..block * block).map(|k| at(bx + k % block, by + k / block)).sum();
            sum / (block * block) as f64
        })
        .collect();
    let mut order: Vec<usize> = (0..w * h).collect();
    order.sort_by(|&a, &b| height[b].total_cmp(&height[a]).then(a.cmp(&b)));
    let mut flow = vec![(block * block) as f64; w * h];
    for i in order {
        let (x, y) = ((i % w) as i64, (i / w) as i64);
        let mut best: Option<(f64, usize)> = None;
        for (dx, dy) in [(-1, -1), (0, -1), (1, -1), (-1, 0), (1, 0), (-1, 1), (0, 1), (1, 1)] {
            let (nx, ny) = (x + dx, y + dy);
            if nx < 0 || ny < 0 || nx >= w as i64 || ny >= h as i64 {
                continue;
            }
            let j = ny as usize * w + nx as usize;
            let slope = (height[i] - height[j]) / f64::hypot(dx as f64, dy as f64);
            if slope > 0.0 && best.is_none_or(|(s, _)| slope > s) {
                best = Some((slope, j));
            }
        }
        if let Some((_, j)) = best {
            flow[j] += flow[i];
        }
    }
    (w, h, flow)
}

#[test]
fn edge_rivers_follow_the_valleys_of_a_real_landscape() {
    let config = MapConfig::load(assets().join("maps/jacksboro.map.ron")).unwrap();
    let image = HeightImage::load(&assets().join("dem/jacksboro.png")).unwrap();
    let t = Terrain::new(config).unwrap();
    // The flow model at about the tiles' resolution: blocks of 6 x 6 pixels (the map's 64 x 52
    // tiles are 6.3 x 6.6 pixels of the 403 x 344 image).
    let block = 6;
    let (w, h, flow) = d8(&image, block);
    // Where a world position falls on the image (it spans the tile centers' extent).
    let centers: Vec<[f64; 3]> = t.tiles().map(|h| t.tile_center(h).unwrap()).collect();
    let span = |axis: usize| {
        let lo = centers.iter().map(|c| c[axis]).fold(f64::MAX, f64::min);
        let hi = centers.iter().map(|c| c[axis]).fold(f64::MIN, f64::max);
        (lo, hi)
    };
    let ((x0, x1), (z0, z1)) = (span(0), span(2));
    // What drains through the block a world position falls in: how big a stream the flow model
    // finds there.
    let drained = |x: f64, z: f64| {
        let (iw, ih) = image.size();
        let px = ((x - x0) / (x1 - x0) * (iw - 1) as f64 / block as f64).floor() as i64;
        let py = ((z - z0) / (z1 - z0) * (ih - 1) as f64 / block as f64).floor() as i64;
        let (x, y) = (px.clamp(0, w as i64 - 1) as usize, py.clamp(0, h as i64 - 1) as usize);
        flow[y * w + x]
    };
    // Every edge between two tiles of the map, what the flow model drains past its middle, and
    // whether a river runs on it.
    let (mut at_rivers, mut at_edges) = (Vec::new(), Vec::new());
    for tile in t.tiles() {
        let river_toward: Vec<Hex> = t.river_edges(tile).iter().map(|r| r.edge.destination()).collect();
        for nb in tile.all_neighbors() {
            // Each edge once, from the tile with the smaller coordinates.
            if !t.contains(nb) || (nb.x, nb.y) < (tile.x, tile.y) {
                continue;
            }
            let (a, b) = (t.tile_center(tile).unwrap(), t.tile_center(nb).unwrap());
            let here = drained((a[0] + b[0]) / 2.0, (a[2] + b[2]) / 2.0);
            at_edges.push(here);
            if river_toward.contains(&nb) {
                at_rivers.push(here);
            }
        }
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    // A valley floor: 300 pixels (about 2 km², some seven tiles, the rivers' threshold) or more
    // drain through it.
    let share = |v: &[f64]| v.iter().filter(|&&f| f >= 300.0).count() as f64 / v.len() as f64;
    let (river_share, edge_share) = (share(&at_rivers), share(&at_edges));
    let (river_median, edge_median) = (median(&mut at_rivers), median(&mut at_edges));
    println!(
        "Jacksboro: {} river edges of {} edges. Pixels draining past an edge's middle (D8 over 6 x 6 blocks), \
         median: {river_median} at river edges, {edge_median} at all edges; on a valley floor (300 or more): \
         {:.1} % of river edges, {:.1} % of all edges",
        at_rivers.len(),
        at_edges.len(),
        river_share * 100.0,
        edge_share * 100.0
    );
    assert!(at_rivers.len() > 100, "{} river edges", at_rivers.len());
    assert!(river_median >= 3.0 * edge_median, "medians: rivers {river_median}, all edges {edge_median}");
    assert!(river_share >= 2.5 * edge_share, "valley floors: rivers {river_share}, all edges {edge_share}");
}
