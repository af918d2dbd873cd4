//! Regions of equal fertility, one a player, as Civilization V's and Unciv's map scripts divide
//! the map: a grid of cells (a flat area's tiles; a globe's cells of longitude and latitude) is
//! cut in two along its longer side where the fertility on each side is in proportion to the
//! players each side gets, and so on until every part has one player. On a grid that wraps (a
//! wrapping map, a globe) the grid starts at the column with the least fertility, so no region
//! is cut by the seam where the land is richest.

/// One region: a rectangle of the grid (columns counted from the grid's first column, or from
/// the cut column of a grid that wraps) and its fertility.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Region {
    /// Columns `[first, end)`, shifted by the cut column.
    pub cols: [usize; 2],
    /// Rows `[first, end)` of the area.
    pub rows: [usize; 2],
    /// Sum of its tiles' fertility.
    pub fertility: f32,
}

/// The division of a grid into regions.
#[derive(Debug, Clone)]
pub(crate) struct Division {
    /// The regions, one a player (some may be empty on a tiny area).
    pub regions: Vec<Region>,
    /// The region of each tile (of each cell of the grid, until the globe's setup maps its
    /// tiles to them).
    pub region_of: Vec<u32>,
    /// The column of the grid the regions' column 0 is.
    pub cut: usize,
}

/// Divides a grid of `cols` columns (row by row: `fertility.len() / cols` rows), wrapping
/// east to west or not, into `players` regions of about equal `fertility` (a value a cell).
pub(crate) fn divide(cols: usize, wraps: bool, fertility: &[f32], players: usize) -> Division {
    let rows = fertility.len() / cols.max(1);
    let cut = if wraps {
        // The poorest column, the first of them on a tie.
        let column = |c: usize| (0..rows).map(|r| fertility[r * cols + c]).sum::<f32>();
        (0..cols).map(|c| (c, column(c))).fold((0, f32::INFINITY), |best, x| if x.1 < best.1 { x } else { best }).0
    } else {
        0
    };
    let at = |c: usize, r: usize| fertility[r * cols + (c + cut) % cols];
    let mut regions = Vec::with_capacity(players);
    split(&at, Region { cols: [0, cols], rows: [0, rows], fertility: 0.0 }, players, &mut regions);
    let mut region_of = vec![0; fertility.len()];
    for (k, region) in regions.iter().enumerate() {
        for r in region.rows[0]..region.rows[1] {
            for c in region.cols[0]..region.cols[1] {
                region_of[r * cols + (c + cut) % cols] = k as u32;
            }
        }
    }
    for region in &mut regions {
        region.fertility = sum(&at, region);
    }
    Division { regions, region_of, cut }
}

fn sum(at: &impl Fn(usize, usize) -> f32, region: &Region) -> f32 {
    let mut s = 0.0;
    for r in region.rows[0]..region.rows[1] {
        for c in region.cols[0]..region.cols[1] {
            s += at(c, r);
        }
    }
    s
}

/// Splits `region` for `n` players, pushing the parts.
fn split(at: &impl Fn(usize, usize) -> f32, region: Region, n: usize, out: &mut Vec<Region>) {
    let width = region.cols[1] - region.cols[0];
    let height = region.rows[1] - region.rows[0];
    if n <= 1 {
        out.push(region);
        return;
    }
    // Along the longer side (a row of flat hexes is as long as about 0.87 of a column: near
    // enough), or the other when it is one line thick.
    let along_cols = if width >= height { width >= 2 } else { height < 2 };
    let len = if along_cols { width } else { height };
    if len < 2 {
        // One tile: the first player gets it, the others empty regions (their starts come from
        // the whole area).
        out.push(region.clone());
        for _ in 1..n {
            out.push(Region { cols: [region.cols[0]; 2], rows: [region.rows[0]; 2], fertility: 0.0 });
        }
        return;
    }
    let line = |k: usize| -> f32 {
        if along_cols {
            (region.rows[0]..region.rows[1]).map(|r| at(region.cols[0] + k, r)).sum()
        } else {
            (region.cols[0]..region.cols[1]).map(|c| at(c, region.rows[0] + k)).sum()
        }
    };
    let lines: Vec<f32> = (0..len).map(line).collect();
    let total: f32 = lines.iter().sum();
    let first = n / 2;
    // The cut `k` (lines `..k` on the first side) whose share is nearest the first side's.
    let k = if total > 0.0 {
        let target = total * first as f32 / n as f32;
        let mut acc = 0.0;
        let mut best = (1, f32::INFINITY);
        for (k, l) in lines.iter().enumerate().take(len - 1) {
            acc += l;
            let miss = (acc - target).abs();
            if miss < best.1 {
                best = (k + 1, miss);
            }
        }
        best.0
    } else {
        (len * first / n).clamp(1, len - 1)
    };
    let (a, b) = if along_cols {
        (
            Region { cols: [region.cols[0], region.cols[0] + k], ..region.clone() },
            Region { cols: [region.cols[0] + k, region.cols[1]], ..region.clone() },
        )
    } else {
        (
            Region { rows: [region.rows[0], region.rows[0] + k], ..region.clone() },
            Region { rows: [region.rows[0] + k, region.rows[1]], ..region },
        )
    };
    split(at, a, first, out);
    split(at, b, n - first, out);
}
