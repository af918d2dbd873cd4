//! The shape of a map type's ranges on the tile graph: runs of mountains along the hex axes and
//! the knots (blobs, runs too long) that [`super::map_type`] opens and [`super::targets`]
//! measures.

use super::graph::TileGraph;

/// With ranges, the most mountains in a row along a hex axis a map type keeps.
pub const MAX_STRAIGHT_RIDGE: f64 = 6.0;

/// With ranges, the largest share of the mountains with 5 or 6 mountain neighbors a map type
/// keeps.
pub const MAX_BLOB_SHARE: f64 = 0.05;

/// The knots of a map's ranges: the `mountain` tiles with 5 or 6 mountain neighbors, and the
/// middle tile of each run of mountains along a hex axis longer than [`MAX_STRAIGHT_RIDGE`]
/// (in index order, each once).
pub(crate) fn knots(graph: &TileGraph, mountain: &dyn Fn(usize) -> bool) -> Vec<usize> {
    let n = graph.neighbors.len();
    let around = |i: usize| graph.neighbors[i].iter().flatten().filter(|&&j| mountain(j as usize)).count();
    let mut knot: Vec<bool> = (0..n).map(|i| mountain(i) && around(i) >= 5).collect();
    for run in axis_runs(graph, mountain).filter(|run| run.len() as f64 > MAX_STRAIGHT_RIDGE) {
        knot[run[run.len() / 2]] = true;
    }
    (0..n).filter(|&i| knot[i]).collect()
}

/// The most `mountain` tiles in a row along one of the three hex axes.
pub(super) fn straight_ridge(graph: &TileGraph, mountain: &dyn Fn(usize) -> bool) -> usize {
    axis_runs(graph, mountain).map(|run| run.len()).max().unwrap_or(0)
}

/// Every run of `mountain` tiles along each of the three hex axes (neighbor directions `d` and
/// `d + 3`), from its first tile; a run going all round a wrapping map holds its tiles once.
fn axis_runs<'a>(graph: &'a TileGraph, mountain: &'a dyn Fn(usize) -> bool) -> impl Iterator<Item = Vec<usize>> + 'a {
    let n = graph.neighbors.len();
    let step = move |i: usize, d: usize| graph.neighbors[i][d].map(|j| j as usize).filter(|&j| mountain(j));
    (0..3).flat_map(move |d| {
        let mut seen = vec![false; n];
        let mut runs = Vec::new();
        for start in (0..n).filter(|&i| mountain(i)) {
            if seen[start] {
                continue;
            }
            // Back to the run's first tile (or once round), then forward along it.
            let mut first = start;
            while let Some(j) = step(first, d + 3).filter(|&j| j != start) {
                first = j;
            }
            let mut run = Vec::new();
            let mut at = Some(first);
            while let Some(i) = at.filter(|&i| !seen[i]) {
                seen[i] = true;
                run.push(i);
                at = step(i, d);
            }
            runs.push(run);
        }
        runs
    })
}
