//! River channels and lakes as the mesh sees them: how much water covers a lattice point of a
//! tile. A river tile's channel runs from its center to the middle of each edge its river
//! crosses, as wide as the upstream tile's flow says; a river on an edge runs along the edge,
//! as wide as its flow says, into both tiles; a lake tile is covered whole. The vertex
//! chain ([`crate::vertex`]) carves by it, the mesh colors by it, props stay off it.
//!
//! A point's cover is read from the tiles that hold it, each from its own channels, so the two
//! tiles on either side of a river's edge agree on it whichever chunk evaluates it.

use hexx::Hex;

use crate::geometry::Geometry;
use crate::table::TileTable;

/// How much of a channel or lake covers lattice point `p` of `tile`: 1 on a lake tile and on
/// a channel's middle line, falling smoothly to 0 at the channel's half-width; 0 on a map
/// without rivers.
#[must_use]
pub fn cover(geometry: &Geometry, table: &TileTable, tile: Hex, p: Hex) -> f32 {
    let Some((h, i)) = table.water_at(geometry, tile) else { return 0.0 };
    if h.lake_of(i).is_some() {
        return 1.0;
    }
    if let Some(edges) = table.edge_rivers() {
        return edge_cover(geometry, edges.widths(i), tile, p);
    }
    // A channel toward a neighbor runs from the tile's center to the edge's middle.
    channels_cover(geometry, h.channels(i), tile, p, |m| ([0.0, 0.0], m, (0.0, 1.0)))
}

/// How much of the channels along a tile's edges (`widths`, in lattice steps, 0 where no river
/// runs) covers lattice point `p`: 1 on an edge carrying a river (its border points, which the
/// tile on the other side shares, read the same edge), falling smoothly to 0 at the channel's
/// half-width into the tile.
fn edge_cover(geometry: &Geometry, widths: &[f32; 6], tile: Hex, p: Hex) -> f32 {
    // The edge: through the middle between the centers, square to them, as long as a side of
    // the hexagon (the middle's distance over the square root of 3 either way).
    channels_cover(geometry, widths, tile, p, |[mx, mz]| ([mx, mz], [-mz / 3f64.sqrt(), mx / 3f64.sqrt()], (-1.0, 1.0)))
}

/// How much of a tile's channels covers lattice point `p`: for each neighbor with a channel
/// (`widths[d]` lattice steps wide, 0 for none), the channel's segment, given by `segment` from
/// the middle `m` between the two centers (world offsets from the tile's center) as
/// `from + t * along` for `t` in `range`. 1 on a segment, falling smoothly to 0 at the channel's
/// half-width.
fn channels_cover(
    geometry: &Geometry,
    widths: &[f32; 6],
    tile: Hex,
    p: Hex,
    segment: impl Fn([f64; 2]) -> ([f64; 2], [f64; 2], (f64, f64)),
) -> f32 {
    if widths.iter().all(|&w| w == 0.0) {
        return 0.0;
    }
    let lattice = geometry.lattice();
    let center = lattice.tile_center(tile);
    let step = geometry.step();
    let [px, pz] = lattice.world(p - center);
    let mut best = 0.0_f64;
    for (nb, &w) in tile.all_neighbors().iter().zip(widths) {
        if w == 0.0 {
            continue;
        }
        let [ex, ez] = lattice.world(lattice.tile_center(*nb) - center);
        let ([ax, az], [ux, uz], (lo, hi)) = segment([ex * 0.5, ez * 0.5]);
        let (qx, qz) = (px - ax, pz - az);
        let t = ((qx * ux + qz * uz) / (ux * ux + uz * uz)).clamp(lo, hi);
        let (dx, dz) = (qx - t * ux, qz - t * uz);
        let x = ((dx * dx + dz * dz).sqrt() / (step * f64::from(w))).min(1.0);
        best = best.max(1.0 - x * x * (3.0 - 2.0 * x));
    }
    best as f32
}

/// Whether any water (a lake, or a river channel) lies on a tile: every point of a dry tile has
/// a cover of 0.
#[must_use]
pub fn is_wet(geometry: &Geometry, table: &TileTable, tile: Hex) -> bool {
    let Some((h, i)) = table.water_at(geometry, tile) else { return false };
    let edges = table.edge_rivers().is_some_and(|e| e.edges_of(i) != 0);
    h.lake_of(i).is_some() || edges || h.channels(i).iter().any(|&w| w > 0.0)
}
