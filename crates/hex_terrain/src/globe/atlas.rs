//! The globe's integer atlas: the icosahedron's 20 faces paired into 10 diamonds of `f x f`
//! lattice points, plus the two poles.
//!
//! The icosahedron's vertices are the north pole `N`, five upper vertices `U0..U4` (longitudes
//! 0, 72, ... degrees) and five lower ones `L0..L4` (36, 108, ... degrees), and the south pole `S`.
//! Northern diamond `d` is the faces `N U(d) U(d+1)` and `U(d) L(d) U(d+1)`; southern diamond
//! `d` the faces `U(d+1) L(d) L(d+1)` and `L(d) S L(d+1)`. Each diamond is a parallelogram with
//! its origin `O` at one corner (`U(d)` or `L(d)`), axis `i` toward the corner `B` (`N` or
//! `U(d+1)`) and axis `j` toward the corner `C` (`L(d)` or `S`); the far corner `D` (`U(d+1)` or
//! `L(d+1)`) is at `(f, f)`, and the diagonal `O D` is the edge the diamond's two faces share. A
//! diamond owns its points with `0 <= i, j < f`: its origin, the two edges from it and its inside.
//! The other two edges belong to the neighboring diamonds, so every point of the subdivided
//! icosahedron has one owner, and `T = 10 f^2 + 2`.
//!
//! In every diamond the six lattice directions are `(1, 0)`, `(1, 1)`, `(0, 1)`, `(-1, 0)`,
//! `(-1, -1)` and `(0, -1)` (the axes meet at 120 degrees): seen from outside the globe they go
//! round a point clockwise, in every diamond alike. A step out of a diamond lands in its
//! neighbor's frame by one of four maps (`locate`); the ten corners `(0, 0)` are the pentagons
//! but for the poles: the step `(-1, -1)` from them leads nowhere (five faces meet there, not six).

/// Where a lattice point lies: a pole or a point of a diamond.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Spot {
    /// The north pole.
    North,
    /// The south pole.
    South,
    /// Point `(i, j)` of diamond `d` (0-4 northern, 5-9 southern), `0 <= i, j < f`.
    Diamond { d: u8, i: u32, j: u32 },
}

/// The six lattice steps of a diamond's frame, in the order they go round a point.
pub(crate) const STEPS: [(i64, i64); 6] = [(1, 0), (1, 1), (0, 1), (-1, 0), (-1, -1), (0, -1)];

/// The step that leads nowhere from a diamond's origin (a pentagon).
pub(crate) const MISSING_AT_ORIGIN: usize = 4;

/// The next diamond of the same row (northern or southern), going east.
fn east(d: u8) -> u8 {
    if d < 5 { (d + 1) % 5 } else { 5 + (d - 5 + 1) % 5 }
}

/// The previous diamond of the same row, going west.
fn west(d: u8) -> u8 {
    if d < 5 { (d + 4) % 5 } else { 5 + (d - 5 + 4) % 5 }
}

/// The point `(i, j)` of diamond `d`'s frame, where `-1 <= i, j <= f` (a step out of the
/// diamond at most), as the point its owner holds. `None` for `(-1, -1)`, which is no point (the
/// origin's missing step).
pub(crate) fn locate(f: u32, d: u8, i: i64, j: i64) -> Option<Spot> {
    let n = i64::from(f);
    debug_assert!((-1..=n).contains(&i) && (-1..=n).contains(&j), "({i}, {j}) beyond one step of diamond {d}");
    canonical(f, d, i, j)
}

/// The point `(i, j)` of diamond `d`'s frame of frequency `f`, anywhere in the unfolding of the
/// diamond and the four diamonds across its edges, as the point its owner holds. Each edge's map
/// is the rigid motion that lays the neighbor beside the diamond; a point beyond two edges at
/// once lies near a corner, where five faces meet and the unfolding is no longer one plane:
/// `None` there, but for the origin's sectors that one map reaches (its missing sixth, between
/// the steps `(-1, 0)` and `(-1, -1)`, is no point).
pub(crate) fn canonical(f: u32, d: u8, i: i64, j: i64) -> Option<Spot> {
    let n = i64::from(f);
    let (mut d, mut i, mut j) = (d, i, j);
    // Each map lands nearer the owner; two suffice for any point of the unfolding, a few more
    // are a bound.
    for _ in 0..6 {
        if (0..n).contains(&i) && (0..n).contains(&j) {
            return Some(Spot::Diamond { d, i: i as u32, j: j as u32 });
        }
        let north = d < 5;
        if north && i == n && j == 0 {
            return Some(Spot::North);
        }
        if !north && i == 0 && j == n {
            return Some(Spot::South);
        }
        // A map is chosen by the coordinate strictly outside the diamond's closure; a point on
        // the closure's far edges by the edge it lies on.
        let (out_i, out_j) = (!(0..=n).contains(&i), !(0..=n).contains(&j));
        (d, i, j) = if out_i && out_j {
            // Beyond a corner: only the origin's sectors, by the map that reaches them.
            match (north, i < 0 && j < 0) {
                (true, true) if j <= i => (west(d), j + n, j - i + n),
                (false, true) if i <= j => (west(d), i - j + n, i + n),
                _ => return None,
            }
        } else if north {
            if i > n || (!out_j && i == n) {
                // Across N U(d+1): the next northern diamond, turned about the pole.
                (east(d), i - j, i - n)
            } else if j >= n {
                // Across L(d) U(d+1): the southern diamond below, same frame.
                (d + 5, i, j - n)
            } else if i < 0 {
                // Across U(d) L(d): the southern diamond to the west, same frame.
                (west(d) + 5, i + n, j)
            } else {
                // Across U(d) N: the northern diamond to the west, turned about the pole.
                (west(d), j + n, j - i + n)
            }
        } else if i > n || (!out_j && i == n) {
            // Across U(d+1) L(d+1): the next northern diamond, same frame.
            (east(d) - 5, i - n, j)
        } else if j >= n {
            // Across S L(d+1): the next southern diamond, turned about the pole.
            (east(d), j - n, j - i)
        } else if i < 0 {
            // Across L(d) S: the southern diamond to the west, turned about the pole.
            (west(d), i - j + n, i + n)
        } else {
            // Across L(d) U(d+1): the northern diamond above, same frame.
            (d - 5, i, j + n)
        };
    }
    None
}
