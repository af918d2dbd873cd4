//! The globe's fine lattice: every tile's hex-in-hex lattice at once, as one lattice over the
//! icosahedron.
//!
//! A tile of `n` steps from center to corner holds the fine points within `n` steps of its
//! center; on the plane the tile centers are the fine lattice's points `n (2, 1)` and `n (-1, 1)`
//! apart, so the fine lattice is the tile lattice subdivided the Goldberg way `(n, n)`. In a
//! diamond's frame at frequency `F = 3 n f` (the tile frame's coordinates times `3 n`), the fine
//! points are the points `(i, j)` with `i + j` a multiple of 3, a tile's center at
//! `(3 n i, 3 n j)`, and the fine steps `(1, -1)`, `(2, 1)`, `(1, 2)` and their opposites. A
//! point is held by the atlas of frequency `F` (`atlas::canonical`): one owner, one direction,
//! so every chunk that needs it computes the same bits.
//!
//! A hexagon's fine triangles lie in its own diamond's frame, beyond one edge of it at most; a
//! pentagon's are gathered from the frames of the three to five diamonds meeting at its corner,
//! each giving the triangles whose centroid lies in it (a triangle never strays two steps from
//! the diamond whose closure holds its centroid, where each edge's map is the true unfolding).
//! Which tiles hold a point, and its ring, come from the tile centers nearest it in its owner's
//! frame.

use super::atlas::{STEPS, Spot, canonical, locate};

/// A fine lattice point: its place in the atlas of frequency `F`.
pub(crate) type Point = Spot;

/// The fine steps as `(x, y)` of the fine lattice's own axes (at 120 degrees, like a
/// diamond's), to the frame of frequency `F`: `(x + y, 2 y - x)`.
fn to_frame(x: i64, y: i64) -> (i64, i64) {
    (x + y, 2 * y - x)
}

/// Fine steps between two points of the frame of frequency `F` (whose difference keeps `i + j`
/// a multiple of 3).
fn steps(di: i64, dj: i64) -> u32 {
    let (y, x) = ((di + dj) / 3, (2 * di - dj) / 3);
    ((x.abs() + y.abs() + (x - y).abs()) / 2) as u32
}

/// The fine steps in a diamond's frame of frequency `F`, going round a point clockwise seen from
/// outside like the atlas' `STEPS` (they are `STEPS` through `to_frame`).
const FINE_STEPS: [(i64, i64); 6] = [(1, -1), (2, 1), (1, 2), (-1, 1), (-2, -1), (-1, -2)];

/// The fine lattice of a globe of frequency `f` whose tiles have `n` steps from center to corner.
#[derive(Debug, Clone)]
pub(crate) struct Fine {
    f: u32,
    n: u32,
    /// A hexagon's points as frame offsets from its center, and its `6 n^2` triangles as
    /// indices into them, counterclockwise seen from outside.
    cells: Vec<Cell>,
    cell_triangles: Vec<[u16; 3]>,
}

/// A point of a hexagon's template: its frame offset from the center, its ring, and for a point
/// inside the tile (ring below `n`) its neighbors as the template's indices, in [`Fine::fan`]'s
/// order.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Cell {
    pub(crate) offset: (i64, i64),
    pub(crate) ring: u32,
    pub(crate) fan: Option<[u16; 6]>,
}

/// A run of points one after another in [`Fine::dense`]'s order: a pole, or row `i` of diamond
/// `d`'s frame.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Row {
    Pole(Spot),
    Frame { d: u8, i: u32 },
}

/// A fine point's neighbors going round it clockwise seen from outside: six, or five at the
/// icosahedron's twelve vertices.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Fan {
    points: [Point; 6],
    len: u8,
}

impl Fan {
    pub(crate) fn points(&self) -> &[Point] {
        &self.points[..usize::from(self.len)]
    }
}

/// The tiles holding a fine point (one inside a tile, two on an edge, three on a corner) and its
/// ring: its steps from the nearest center, `n` on a border.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Holders {
    pub(crate) ring: u32,
    tiles: [Spot; 3],
    len: u8,
}

impl Holders {
    pub(crate) fn tiles(&self) -> &[Spot] {
        &self.tiles[..usize::from(self.len)]
    }
}

impl Fine {
    pub(crate) fn new(f: u32, n: u32) -> Self {
        let r = i64::from(n);
        let inside = |x: i64, y: i64| (x.abs() + y.abs() + (x - y).abs()) / 2 <= r;
        let at = |x: i64, y: i64| (x + r) * (2 * r + 1) + y + r;
        let mut slot = vec![u16::MAX; ((2 * r + 1) * (2 * r + 1)) as usize];
        let mut cells = Vec::new();
        for x in -r..=r {
            for y in (-r..=r).filter(|&y| inside(x, y)) {
                slot[at(x, y) as usize] = cells.len() as u16;
                let ring = ((x.abs() + y.abs() + (x - y).abs()) / 2) as u32;
                cells.push(Cell { offset: to_frame(x, y), ring, fan: None });
            }
        }
        for x in -r..=r {
            for y in (-r..=r).filter(|&y| inside(x, y)) {
                let cell = &mut cells[slot[at(x, y) as usize] as usize];
                if cell.ring < n {
                    // The fine axes' steps, which `to_frame` turns into `FINE_STEPS`.
                    cell.fan = Some(STEPS.map(|(dx, dy)| slot[at(x + dx, y + dy) as usize]));
                }
            }
        }
        let cell_triangles = lattice_triangles(r)
            .filter(|t| t.iter().all(|&(x, y)| inside(x, y)))
            .map(|t| t.map(|(x, y)| slot[at(x, y) as usize]))
            .collect();
        Self { f, n, cells, cell_triangles }
    }

    /// The points of the tile at `spot` (of the tile atlas), each once.
    pub(crate) fn tile_points(&self, spot: Spot) -> Vec<Point> {
        match self.hexagon(spot) {
            Some((d, ci, cj)) => {
                self.cells.iter().map(|c| self.hexagon_point(d, ci + c.offset.0, cj + c.offset.1)).collect()
            }
            None => {
                let mut out: Vec<Point> = self.triangles(spot).into_iter().flatten().collect();
                out.sort_unstable_by_key(|&p| self.id(p));
                out.dedup();
                out
            }
        }
    }

    /// A hexagon's diamond and center in its frame of frequency `F`; `None` for a pentagon.
    pub(crate) fn hexagon(&self, spot: Spot) -> Option<(u8, i64, i64)> {
        let m = i64::from(3 * self.n);
        match spot {
            Spot::Diamond { d, i, j } if i != 0 || j != 0 => Some((d, i64::from(i) * m, i64::from(j) * m)),
            _ => None,
        }
    }

    /// The places in [`Fine::dense`]'s order of the points of the hexagon centered at `(ci, cj)`
    /// of diamond `d`'s frame ([`Fine::hexagon`]), in its template's order, into `out`. A
    /// hexagon inside its diamond has them at the same offsets from its center's as every such
    /// hexagon (its center's `j` is a multiple of 3, so a cell's `(di, dj)` moves the place by
    /// `di F / 3` and the `k` of `dj`).
    pub(crate) fn hexagon_dense(&self, (d, ci, cj): (u8, i64, i64), out: &mut Vec<u32>) {
        let (big, reach) = (i64::from(self.big()), i64::from(2 * self.n));
        out.clear();
        if ci >= reach && cj >= reach && ci + reach < big && cj + reach < big {
            let center = self.dense(Spot::Diamond { d, i: ci as u32, j: cj as u32 }) as i64;
            let third = big / 3;
            out.extend(self.cells.iter().map(|c| (center + c.offset.0 * third + c.offset.1.div_euclid(3)) as u32));
        } else {
            out.extend(
                self.cells.iter().map(|c| self.dense(self.hexagon_point(d, ci + c.offset.0, cj + c.offset.1)) as u32),
            );
        }
    }

    /// A hexagon's points as frame offsets from its center ([`Fine::hexagon`]), and its
    /// triangles as indices into them.
    pub(crate) fn template(&self) -> (&[Cell], &[[u16; 3]]) {
        (&self.cells, &self.cell_triangles)
    }

    /// The point at `(i, j)` of diamond `d`'s frame, within a hexagon of the diamond (so within
    /// one edge of it).
    pub(crate) fn hexagon_point(&self, d: u8, i: i64, j: i64) -> Point {
        canonical(self.big(), d, i, j).expect("a hexagon's point lies within one edge of its diamond")
    }

    /// The point's neighbors going round it, each step taken in its owner's frame (the poles
    /// seen from the first northern or southern diamond): a point's ring never reaches beyond
    /// one edge of its owner, and at the twelve vertices the step that leads nowhere is left out.
    pub(crate) fn fan(&self, p: Point) -> Fan {
        let big = i64::from(self.big());
        let (d, i, j) = match p {
            Spot::North => (0, big, 0),
            Spot::South => (5, 0, big),
            Spot::Diamond { d, i, j } => (d, i64::from(i), i64::from(j)),
        };
        let mut out = Fan { points: [p; 6], len: 0 };
        if i >= 2 && j >= 2 && i + 2 < big && j + 2 < big {
            // Well inside the diamond (a step is at most 2 along either axis): every neighbor is
            // in its frame, as `canonical` would find.
            out.points = FINE_STEPS.map(|(di, dj)| Spot::Diamond { d, i: (i + di) as u32, j: (j + dj) as u32 });
            out.len = 6;
            return out;
        }
        for (di, dj) in FINE_STEPS {
            if let Some(q) = canonical(self.big(), d, i + di, j + dj) {
                out.points[usize::from(out.len)] = q;
                out.len += 1;
            }
        }
        out
    }

    /// `n`: the fine steps from a tile's center to its corner.
    pub(crate) fn n(&self) -> u32 {
        self.n
    }

    /// `F = 3 n f`: the frequency of the atlas that holds the fine points.
    pub(crate) fn big(&self) -> u32 {
        3 * self.n * self.f
    }

    /// A dense id of a point, `0..10 F^2 + 2` (only a third of them are points).
    pub(crate) fn id(&self, p: Point) -> u64 {
        let big = u64::from(self.big());
        match p {
            Spot::North => 0,
            Spot::South => 10 * big * big + 1,
            Spot::Diamond { d, i, j } => 1 + u64::from(d) * big * big + u64::from(i) * big + u64::from(j),
        }
    }

    /// How many points there are: `10 F^2 / 3 + 2`.
    #[cfg(test)]
    pub(crate) fn point_count(&self) -> u64 {
        let big = u64::from(self.big());
        10 * big * big / 3 + 2
    }

    /// A point's place among all points, `0..point_count()`: its id with the two thirds of
    /// the frame that are not points left out (`F` is a multiple of 3, and in a row of the frame
    /// the points are every third `j`).
    pub(crate) fn dense(&self, p: Point) -> usize {
        let big = self.big() as usize;
        match p {
            Spot::North => 0,
            Spot::South => 10 * big * big / 3 + 1,
            Spot::Diamond { d, i, j } => 1 + usize::from(d) * big * big / 3 + (i as usize * big) / 3 + j as usize / 3,
        }
    }

    /// Every point, in [`Fine::dense`]'s order.
    #[cfg(any(test, feature = "bench"))]
    pub(crate) fn points(&self) -> Vec<Point> {
        self.rows().into_iter().flat_map(|row| self.row_points(row)).collect()
    }

    /// The runs of points one after another in [`Fine::dense`]'s order: the north pole, each
    /// diamond's rows of its frame, the south pole.
    pub(crate) fn rows(&self) -> Vec<Row> {
        let mut rows = Vec::with_capacity(10 * self.big() as usize + 2);
        rows.push(Row::Pole(Spot::North));
        rows.extend((0..10).flat_map(|d| (0..self.big()).map(move |i| Row::Frame { d, i })));
        rows.push(Row::Pole(Spot::South));
        rows
    }

    /// A row's points, in order.
    pub(crate) fn row_points(&self, row: Row) -> impl Iterator<Item = Point> + use<> {
        let (columns, d, i, pole) = match row {
            Row::Pole(pole) => (0..1, 0, 0, Some(pole)),
            // The points of a row are every third `j` with `i + j` a multiple of 3.
            Row::Frame { d, i } => ((3 - i % 3) % 3..self.big(), d, i, None),
        };
        columns.step_by(3).map(move |j| pole.unwrap_or(Spot::Diamond { d, i, j }))
    }

    /// How many points a row has.
    pub(crate) fn row_len(&self, row: Row) -> usize {
        match row {
            Row::Pole(_) => 1,
            Row::Frame { i, .. } => (self.big() - (3 - i % 3) % 3).div_ceil(3) as usize,
        }
    }

    /// The offsets in [`Fine::dense`]'s order from a row's points to their six neighbors, in
    /// [`Fine::walk`]'s order, and the columns of the row whose points they hold for (those well
    /// inside the diamond, where the walk is the six steps in the frame); `None` for a pole or a
    /// row near the diamond's edges.
    pub(crate) fn row_steps(&self, row: Row) -> Option<([isize; 6], std::ops::Range<u32>)> {
        let (big, reach) = (self.big(), self.reach());
        let Row::Frame { i, .. } = row else { return None };
        if i < reach || i + reach >= big {
            return None;
        }
        // A row's points are `j = r + 3 k` (`r` the row's first column), `(i F + j) / 3` apart
        // from the diamond's first point: a step `(di, dj)` moves that by `di F / 3` and the
        // `k` of `r + dj`.
        let r = i64::from((3 - i % 3) % 3);
        let third = i64::from(big / 3);
        let steps = FINE_STEPS.map(|(di, dj)| (di * third + (r + dj).div_euclid(3)) as isize);
        Some((steps, reach..big - reach))
    }

    /// How near a diamond's edges a point may lie and still have a walk and a fan of the six
    /// steps in its frame: a hexagon's points lie within `2 n` of its center in the frame, and a
    /// step is at most 2 along either axis.
    fn reach(&self) -> u32 {
        2 * self.n + 2
    }

    /// The point's neighbors in the order its normal goes round them (a chunk's mesh and the
    /// whole globe's alike): a point inside a hexagon in its hexagon's frame (its template's
    /// order), any other in its owner's ([`Fine::fan`]). The two differ only for a point inside
    /// a hexagon whose center lies in another diamond, which only a point within `2 n` of its
    /// diamond's edges can be.
    pub(crate) fn walk(&self, p: Point) -> Fan {
        let (big, reach) = (self.big(), self.reach());
        let Spot::Diamond { d, i, j } = p else { return self.fan(p) };
        if i >= reach && j >= reach && i + reach < big && j + reach < big {
            return self.fan(p);
        }
        let holders = self.holders(p);
        let &[tile] = holders.tiles() else { return self.fan(p) };
        match self.hexagon(tile) {
            Some((e, ci, cj)) if e != d && holders.ring < self.n => {
                // The point's place in its hexagon's frame: a cell beyond the hexagon's diamond.
                let outside = |v: i64| !(0..i64::from(big)).contains(&v);
                let (qi, qj) = self
                    .cells
                    .iter()
                    .filter(|c| c.ring < self.n)
                    .map(|c| (ci + c.offset.0, cj + c.offset.1))
                    .find(|&(qi, qj)| (outside(qi) || outside(qj)) && self.hexagon_point(e, qi, qj) == p)
                    .expect("a point inside a hexagon is one of its cells");
                Fan { points: FINE_STEPS.map(|(di, dj)| self.hexagon_point(e, qi + di, qj + dj)), len: 6 }
            }
            _ => self.fan(p),
        }
    }

    /// The center of the tile at `spot` (of the tile atlas) as a point.
    pub(crate) fn center(&self, spot: Spot) -> Point {
        let m = 3 * self.n;
        match spot {
            Spot::Diamond { d, i, j } => Spot::Diamond { d, i: i * m, j: j * m },
            pole => pole,
        }
    }

    /// The tiles holding point `p`, and its ring.
    pub(crate) fn holders(&self, p: Point) -> Holders {
        let Spot::Diamond { d, i, j } = p else {
            return Holders { ring: 0, tiles: [p; 3], len: 1 };
        };
        let m = i64::from(3 * self.n);
        let (i, j) = (i64::from(i), i64::from(j));
        let (a, b) = (i / m, j / m);
        // The tiles beyond `len` are a constant, not the point: filling them from the point's
        // pieces on the stack cost a stalled load, a fifth of the call.
        let mut out = Holders { ring: self.n, tiles: [Spot::North; 3], len: 0 };
        // The tile lattice's rhombus around the point holds every center within a tile's
        // circumradius of it.
        for (da, db) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            let (ta, tb) = (a + da, b + db);
            let s = steps(i - ta * m, j - tb * m);
            if s <= self.n {
                let tile = locate(self.f, d, ta, tb).expect("a corner of the diamond's closure");
                if s < self.n {
                    // Inside the tile: every other center is at least `2 n - s` away.
                    return Holders { ring: s, tiles: [tile; 3], len: 1 };
                }
                if !out.tiles().contains(&tile) {
                    out.tiles[usize::from(out.len)] = tile;
                    out.len += 1;
                }
                out.ring = out.ring.min(s);
            }
        }
        debug_assert!(out.len >= 1, "a point no tile holds: {p:?}");
        out
    }

    /// The fine triangles of the tile at `spot` (of the tile atlas), each counterclockwise seen
    /// from outside the globe: `6 n^2` for a hexagon, `5 n^2` for a pentagon.
    pub(crate) fn triangles(&self, spot: Spot) -> Vec<[Point; 3]> {
        let big = i64::from(self.big());
        let m = i64::from(3 * self.n);
        match spot {
            Spot::Diamond { d, i, j } if i != 0 || j != 0 => {
                let (ci, cj) = (i64::from(i) * m, i64::from(j) * m);
                self.ball_triangles(d, (ci, cj), |_| true)
            }
            _ => {
                let mut out: Vec<[Point; 3]> = Vec::with_capacity(5 * (self.n * self.n) as usize);
                for (d, corner) in charts(spot, big) {
                    // The triangles whose centroid lies in this diamond's closure: this frame
                    // unfolds them truly.
                    let inside = |sum: (i64, i64)| (0..=3 * big).contains(&sum.0) && (0..=3 * big).contains(&sum.1);
                    for t in self.ball_triangles(d, corner, inside) {
                        let key = self.key(&t);
                        if !out.iter().any(|o| self.key(o) == key) {
                            out.push(t);
                        }
                    }
                }
                out
            }
        }
    }

    /// A triangle's ids rotated so that the smallest comes first (the winding kept): the same
    /// triangle from any tile or chart has the same key.
    pub(crate) fn key(&self, t: &[Point; 3]) -> [u64; 3] {
        let ids = t.map(|p| self.id(p));
        let k = (0..3).min_by_key(|&k| ids[k]).unwrap_or(0);
        [ids[k], ids[(k + 1) % 3], ids[(k + 2) % 3]]
    }

    /// The fine triangles within `n` steps of `center` in diamond `d`'s frame whose three corners'
    /// sum (three times the centroid) passes `keep`, their corners at their owners.
    fn ball_triangles(&self, d: u8, center: (i64, i64), keep: impl Fn((i64, i64)) -> bool) -> Vec<[Point; 3]> {
        let n = i64::from(self.n);
        let big = self.big();
        let inside = |x: i64, y: i64| (x.abs() + y.abs() + (x - y).abs()) / 2 <= n;
        let mut out = Vec::with_capacity(6 * (n * n) as usize);
        for t in lattice_triangles(n).filter(|t| t.iter().all(|&(x, y)| inside(x, y))) {
            let frame = t.map(|(x, y)| {
                let (u, v) = to_frame(x, y);
                (center.0 + u, center.1 + v)
            });
            let sum = (frame[0].0 + frame[1].0 + frame[2].0, frame[0].1 + frame[1].1 + frame[2].1);
            if !keep(sum) {
                continue;
            }
            let points = frame.map(|(i, j)| canonical(big, d, i, j));
            if let [Some(a), Some(b), Some(c)] = points {
                out.push([a, b, c]);
            } else {
                debug_assert!(false, "a kept triangle beyond the unfolding: {frame:?} in diamond {d}");
            }
        }
        out
    }
}

/// The up and down triangles from every `(x, y)` of `-n..=n` squared, in the fine lattice's own
/// axes, wound counterclockwise seen from outside (the lattice's steps `(1, 0)`, `(1, 1)`,
/// `(0, 1)` go round clockwise).
fn lattice_triangles(n: i64) -> impl Iterator<Item = [(i64, i64); 3]> {
    (-n..=n).flat_map(move |x| {
        (-n..=n).flat_map(move |y| [[(x, y), (x + 1, y + 1), (x + 1, y)], [(x, y), (x, y + 1), (x + 1, y + 1)]])
    })
}

/// The diamonds meeting at a pentagon's corner and where the corner lies in each one's frame of
/// frequency `big` (the icosahedron vertex `U(k)` is the origin of northern diamond `k`, the far
/// corner of northern `k - 1` and the corner `B` of southern `k - 1`; `L(k)` the origin of
/// southern `k`, the corner `C` of northern `k` and the far corner of southern `k - 1`; the poles
/// the corner `B` of every northern diamond and `C` of every southern one).
fn charts(spot: Spot, big: i64) -> Vec<(u8, (i64, i64))> {
    match spot {
        Spot::North => (0..5).map(|d| (d, (big, 0))).collect(),
        Spot::South => (5..10).map(|d| (d, (0, big))).collect(),
        Spot::Diamond { d, .. } if d < 5 => vec![(d, (0, 0)), ((d + 4) % 5, (big, big)), (5 + (d + 4) % 5, (big, 0))],
        Spot::Diamond { d, .. } => {
            let k = d - 5;
            vec![(d, (0, 0)), (k, (0, big)), (5 + (k + 4) % 5, (big, big))]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every fine point (each frame position with `i + j` a multiple of 3, found here by
    /// filtering the whole frame) has its own dense index, below the count, and is the point
    /// `Fine::points` lists at that index (the whole globe's mesh has its vertices in that
    /// order, row by row: each row as long as `row_len` says).
    #[test]
    fn dense_indices_are_a_bijection_in_the_order_points_lists() {
        for (f, n) in [(1, 1), (2, 3), (5, 2), (7, 4)] {
            let fine = Fine::new(f, n);
            let big = fine.big();
            let mut points = vec![Spot::North, Spot::South];
            for d in 0..10 {
                for i in 0..big {
                    points.extend((0..big).filter(|j| (i + j) % 3 == 0).map(|j| Spot::Diamond { d, i, j }));
                }
            }
            assert_eq!(points.len() as u64, fine.point_count());
            let listed = fine.points();
            assert_eq!(listed.len(), points.len());
            let mut seen = vec![false; points.len()];
            for p in points {
                let k = fine.dense(p);
                assert!(!std::mem::replace(&mut seen[k], true), "{p:?} shares {k} (f {f}, n {n})");
                assert_eq!(listed[k], p, "dense index {k} (f {f}, n {n})");
            }
            for row in fine.rows() {
                assert_eq!(fine.row_points(row).count(), fine.row_len(row), "{row:?} (f {f}, n {n})");
            }
        }
    }

    /// Every hexagon of a globe as [`Fine::hexagon`] gives it: its diamond and center.
    fn hexagons(fine: &Fine) -> Vec<(u8, i64, i64)> {
        let f = fine.f;
        (0..10)
            .flat_map(|d| (0..f).flat_map(move |i| (0..f).map(move |j| Spot::Diamond { d, i, j })))
            .filter_map(|spot| fine.hexagon(spot))
            .collect()
    }

    const SIZES: [(u32, u32); 4] = [(2, 3), (3, 2), (5, 2), (4, 4)];

    /// The walk round a point inside a hexagon is its hexagon's template order (the six steps in
    /// the hexagon's frame, found here by going through every hexagon's points), and round any
    /// other point its fan in its owner's frame; the two differ for some points (those inside a
    /// hexagon across its diamond's edge), so the test tells them apart.
    #[test]
    fn the_walk_round_a_point_inside_a_hexagon_is_its_hexagons() {
        for (f, n) in SIZES {
            let fine = Fine::new(f, n);
            let mut inside: std::collections::HashMap<u64, [Point; 6]> = std::collections::HashMap::new();
            for (e, ci, cj) in hexagons(&fine) {
                for c in fine.cells.iter().filter(|c| c.ring < n) {
                    let (qi, qj) = (ci + c.offset.0, cj + c.offset.1);
                    let around = FINE_STEPS.map(|(di, dj)| fine.hexagon_point(e, qi + di, qj + dj));
                    let p = fine.hexagon_point(e, qi, qj);
                    assert!(inside.insert(fine.id(p), around).is_none(), "{p:?} in two hexagons");
                }
            }
            let mut turned = 0;
            for p in fine.points() {
                let walk = fine.walk(p);
                match inside.get(&fine.id(p)) {
                    Some(around) => {
                        assert_eq!(walk.points(), around, "{p:?} (f {f}, n {n})");
                        turned += usize::from(fine.fan(p).points() != around);
                    }
                    None => assert_eq!(walk.points(), fine.fan(p).points(), "{p:?} (f {f}, n {n})"),
                }
            }
            assert!(turned > 0, "f {f}, n {n}: no hexagon's order differs from its points' owners'");
        }
    }

    /// A row's constant offsets reach, from each point of the columns they are for, the places
    /// of its walk's points in order.
    #[test]
    fn a_rows_steps_reach_its_points_walks() {
        for (f, n) in SIZES {
            let fine = Fine::new(f, n);
            for row in fine.rows() {
                let Some((steps, columns)) = fine.row_steps(row) else { continue };
                for p in fine.row_points(row) {
                    let Spot::Diamond { j, .. } = p else { unreachable!("a pole has no row steps") };
                    if columns.contains(&j) {
                        let dense = fine.walk(p).points().iter().map(|&q| fine.dense(q) as isize).collect::<Vec<_>>();
                        let stepped = steps.map(|s| fine.dense(p) as isize + s);
                        assert_eq!(dense, stepped, "{p:?} (f {f}, n {n})");
                    }
                }
            }
        }
    }

    /// A hexagon's places are its cells' own places, whether found by the constant offsets or
    /// point by point.
    #[test]
    fn a_hexagons_places_are_its_cells_places() {
        for (f, n) in SIZES {
            let fine = Fine::new(f, n);
            let mut dense = Vec::new();
            for (e, ci, cj) in hexagons(&fine) {
                fine.hexagon_dense((e, ci, cj), &mut dense);
                let expected: Vec<u32> = fine
                    .cells
                    .iter()
                    .map(|c| fine.dense(fine.hexagon_point(e, ci + c.offset.0, cj + c.offset.1)) as u32)
                    .collect();
                assert_eq!(dense, expected, "hexagon ({e}, {ci}, {cj}) (f {f}, n {n})");
            }
        }
    }
}
