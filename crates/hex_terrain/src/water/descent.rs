//! How the corners of the edge river network ([`super::edges`]) drain: each corner runs to its
//! lowest neighbor when that is lower than itself (steepest descent), and the corners whose
//! descent does not reach an outlet (those in a depression, or on a flat) are taken by a
//! priority flood from the corners around them (Barnes, Lehman and Mulla's Priority-Flood with
//! its FIFO for depressions), which fills each depression to its spill height. Every corner's
//! water level is then its filled height: the lowest, over the paths to an outlet, of the
//! highest corner on the path. Every path downstream ends at an outlet, never rises in level and
//! never loops.
//!
//! The descent gives most corners their way down without a priority queue (a corner that
//! descends to an outlet is at its own height, which is its filled height), so the flood's queue
//! holds only the depressions' corners and their rims.

use std::collections::VecDeque;

use crate::hash::order_key as key;

/// No corner: an outlet's downstream, an empty list.
pub(super) const NONE: u32 = u32::MAX;

/// What a corner is to the drainage.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Role {
    /// No map tile has it.
    Unused,
    /// Beside water or the map's edge: a river ends there.
    Outlet,
    /// Among land tiles only: it drains into one of its neighbors.
    Drains,
}

/// Where each corner drains, and an order to add flow up in.
pub(super) struct Drainage {
    /// Each corner's downstream corner, one of its links; [`NONE`] for outlets and unused
    /// corners.
    pub(super) down: Vec<u32>,
    /// The outlets and the corners that drain, each after the corner it drains into.
    pub(super) order: Vec<u32>,
}

/// The drainage of corners with these roles, heights (`level`, which become the water levels)
/// and links (the corners across each edge, the corner itself for an edge past the grid; every
/// corner that drains reaches an outlet through the links, and its links are used corners).
/// Any graph of this kind drains the same way: a tile's six neighbors are its links in the
/// tiles' own flood ([`super::hydrology::Hydrology::lakes_only`]).
pub(super) fn drain<const N: usize>(roles: &[Role], level: &mut [f32], links: &[[u32; N]]) -> Drainage {
    let n = roles.len();
    // Steepest descent: to the lowest neighbor lower than the corner (the first in link order
    // among equals).
    let mut down = vec![NONE; n];
    for c in 0..n {
        if roles[c] == Role::Drains {
            let (mut low, mut to) = (level[c], NONE);
            for &j in &links[c] {
                let l = level[j as usize];
                let lower = l < low;
                low = if lower { l } else { low };
                to = if lower { j } else { to };
            }
            down[c] = to;
        }
    }
    // Up the descent from the outlets: every corner whose descent reaches one, each after the
    // corner it drains into. A corner drains into one corner, so it is met once; the order has
    // room for a link written past its end and not counted.
    let mut order: Vec<u32> = Vec::with_capacity(n + 1);
    order.extend((0..n as u32).filter(|&c| roles[c as usize] == Role::Outlet));
    let mut len = order.len();
    order.resize(n + 1, NONE);
    let mut at = 0;
    while at < len {
        let c = order[at];
        at += 1;
        for &j in &links[c as usize] {
            order[len] = j;
            len += usize::from(down[j as usize] == c);
        }
    }
    order.truncate(len);
    // The rest lie in depressions or on flats: flooded from the corners around them, lowest
    // level first.
    let mut taken: Vec<bool> = roles.iter().map(|&r| r == Role::Unused).collect();
    for &c in &order {
        taken[c as usize] = true;
    }
    let (low, high) = level.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &l| (lo.min(l), hi.max(l)));
    let mut queue = LevelQueue::new(n / 4, low, high.max(low));
    let mut rim = vec![false; n];
    for c in 0..n {
        if !taken[c] {
            down[c] = NONE;
            for &j in &links[c] {
                if taken[j as usize] && !rim[j as usize] {
                    rim[j as usize] = true;
                    queue.push(level[j as usize], j);
                }
            }
        }
    }
    // A corner no higher than the level it is reached at fills to that level: it is taken
    // next, from a FIFO, before any corner the level queue holds.
    let mut pit = VecDeque::new();
    loop {
        let c = match pit.pop_front() {
            Some(c) => c,
            None => match queue.pop() {
                Some(c) => c,
                None => break,
            },
        };
        let l = level[c as usize];
        if !rim[c as usize] {
            order.push(c);
        }
        for &j in &links[c as usize] {
            let j = j as usize;
            if !taken[j] {
                taken[j] = true;
                down[j] = c;
                if level[j] <= l {
                    level[j] = l;
                    pit.push_back(j as u32);
                } else {
                    queue.push(level[j], j as u32);
                }
            }
        }
    }
    Drainage { down, order }
}

/// No entry in a bucket's list.
const END: u32 = NONE;

/// The flood's priority queue, for levels that never fall below the last one taken (a priority
/// flood's levels only rise): corners (or any `u32` names) lowest level first, ties by name; the
/// tiles' flood names its pushes in the order made, so its ties go first pushed, first taken. The level range
/// is cut into buckets, each a list of entries; the lowest bucket with entries is sorted when
/// reached and taken in order, a corner pushed into it meanwhile put in its place. A push costs
/// an entry, a take a short sort.
pub(super) struct LevelQueue {
    low: f32,
    scale: f32,
    /// The first entry of each bucket's list, [`END`] when empty.
    heads: Vec<u32>,
    /// Each entry's key (`order_key` of its level and corner) and the next entry in its list.
    entries: Vec<(u64, u32)>,
    /// How many entries the lists hold.
    listed: usize,
    /// The bucket being taken.
    at: usize,
    /// Its keys, largest first (taken from the end).
    current: Vec<u64>,
}

impl LevelQueue {
    /// A queue with `buckets` buckets over the levels `low..=high`.
    pub(super) fn new(buckets: usize, low: f32, high: f32) -> Self {
        let buckets = buckets.clamp(16, 1 << 16);
        let span = high - low;
        let scale = if span > 0.0 { (buckets - 1) as f32 / span } else { 0.0 };
        Self { low, scale, heads: vec![END; buckets], entries: Vec::new(), listed: 0, at: 0, current: Vec::new() }
    }

    /// The bucket of a level: rounding keeps it monotone in the level.
    #[inline]
    fn bucket(&self, level: f32) -> usize {
        (((level - self.low) * self.scale) as usize).min(self.heads.len() - 1)
    }

    pub(super) fn push(&mut self, level: f32, corner: u32) {
        let b = self.bucket(level);
        debug_assert!(b >= self.at, "a level below the last one taken");
        let k = key(level, corner);
        if b == self.at {
            let at = self.current.partition_point(|&x| x > k);
            self.current.insert(at, k);
        } else {
            self.entries.push((k, self.heads[b]));
            self.heads[b] = (self.entries.len() - 1) as u32;
            self.listed += 1;
        }
    }

    /// The next corner.
    pub(super) fn pop(&mut self) -> Option<u32> {
        while self.current.is_empty() {
            if self.listed == 0 {
                return None;
            }
            self.at += 1;
            let mut e = std::mem::replace(&mut self.heads[self.at], END);
            while e != END {
                let (k, next) = self.entries[e as usize];
                self.current.push(k);
                e = next;
                self.listed -= 1;
            }
            self.current.sort_unstable_by(|a, b| b.cmp(a));
        }
        self.current.pop().map(|k| k as u32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small random generator for the tests.
    fn generator(mut seed: u64) -> impl FnMut() -> u32 {
        move || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 33) as u32
        }
    }

    /// The level queue takes corners in the order of their keys (level, then corner) among
    /// those pushed and not yet taken, as a sorted set does, while pushes never go below the
    /// last level taken (as in a flood), ties and levels at the range's ends included.
    #[test]
    fn the_level_queue_takes_corners_lowest_level_first() {
        let mut seed = 12345_u64;
        let mut next = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 33) as u32
        };
        for (corners, high) in [(5000_usize, 11.0_f32), (40, 0.5), (3000, 0.0)] {
            let mut levels = vec![0.0_f32; corners];
            let mut queue = LevelQueue::new(corners / 4, -1.0_f32.min(high), high);
            let mut waiting = std::collections::BTreeSet::new();
            let (mut pushed, mut taken, mut last) = (0_usize, 0_usize, -1.0_f32.min(high));
            while taken < corners {
                for _ in 0..next() % 4 {
                    if pushed == corners {
                        break;
                    }
                    // Some at the last level taken, some at the top of the range.
                    let level = match next() % 5 {
                        0 => last,
                        1 => high,
                        _ => (last + (next() % 1000) as f32 / 300.0).min(high),
                    };
                    levels[pushed] = level;
                    queue.push(level, pushed as u32);
                    waiting.insert(key(level, pushed as u32));
                    pushed += 1;
                }
                if next() % 3 > 0 || pushed == corners {
                    let expected = waiting.pop_first().map(|k| k as u32);
                    assert_eq!(queue.pop(), expected, "corners {corners}, taken {taken}");
                    if let Some(c) = expected {
                        last = levels[c as usize];
                        taken += 1;
                    }
                }
            }
            assert_eq!(queue.pop(), None);
        }
    }

    /// On honeycomb graphs of random heights (a corner's three links as on a hex map's corners,
    /// outlets round the edge and scattered in, many ties), the water levels are the filled
    /// heights a brute-force relaxation finds (`level = max(height, lowest neighbor level)`
    /// until nothing changes), and every corner that drains runs to a neighbor no higher in
    /// level, comes after it in the order, and reaches an outlet.
    #[test]
    fn corners_drain_to_outlets_at_their_filled_levels() {
        let mut next = generator(99);
        for round in 0..60 {
            let (w, h) = (3 + next() as usize % 20, 3 + next() as usize % 20);
            // A brick-wall honeycomb: corner (x, y) links left and right, and up or down by
            // the parity of x + y.
            let at = |x: usize, y: usize| (y * w + x) as u32;
            let n = w * h;
            let levels = 1 + next() % if round % 3 == 0 { 4 } else { 1000 };
            let height: Vec<f32> = (0..n).map(|_| (next() % levels) as f32 / 7.0).collect();
            let roles: Vec<Role> = (0..n)
                .map(|c| {
                    let (x, y) = (c % w, c / w);
                    if x == 0 || y == 0 || x == w - 1 || y == h - 1 || next().is_multiple_of(25) {
                        Role::Outlet
                    } else if next().is_multiple_of(40) {
                        Role::Unused
                    } else {
                        Role::Drains
                    }
                })
                .collect();
            // Unused corners are no corner's links (as on a map, where a corner that drains has
            // three corners of map tiles round it).
            let links: Vec<[u32; 3]> = (0..n)
                .map(|c| {
                    let (x, y) = (c % w, c / w);
                    let side = |dx: isize| x.checked_add_signed(dx).filter(|&x| x < w).map_or(c as u32, |x| at(x, y));
                    let vertical = if (x + y) % 2 == 0 { y.checked_sub(1) } else { Some(y + 1).filter(|&y| y < h) };
                    [side(-1), side(1), vertical.map_or(c as u32, |y| at(x, y))]
                        .map(|j| if roles[j as usize] == Role::Unused { c as u32 } else { j })
                })
                .collect();
            // Unused corners cut the graph: a corner that drains with no way out is not one a
            // map has (its links reach an outlet), so keep only those reaching one.
            let mut reach = roles.iter().map(|&r| r == Role::Outlet).collect::<Vec<_>>();
            let mut changed = true;
            while changed {
                changed = false;
                for c in 0..n {
                    if roles[c] == Role::Drains && !reach[c] && links[c].iter().any(|&j| reach[j as usize]) {
                        reach[c] = true;
                        changed = true;
                    }
                }
            }
            let roles: Vec<Role> = roles
                .iter()
                .enumerate()
                .map(|(c, &r)| if r == Role::Drains && !reach[c] { Role::Unused } else { r })
                .collect();
            let mut level = height.clone();
            let Drainage { down, order } = drain(&roles, &mut level, &links);
            // The filled heights, by relaxation.
            let mut filled: Vec<f32> =
                (0..n).map(|c| if roles[c] == Role::Drains { f32::INFINITY } else { height[c] }).collect();
            let mut changed = true;
            while changed {
                changed = false;
                for c in (0..n).filter(|&c| roles[c] == Role::Drains) {
                    let low = links[c].iter().map(|&j| filled[j as usize]).fold(f32::INFINITY, f32::min);
                    let f = height[c].max(low);
                    if f < filled[c] {
                        filled[c] = f;
                        changed = true;
                    }
                }
            }
            let mut place = vec![usize::MAX; n];
            for (k, &c) in order.iter().enumerate() {
                assert_eq!(place[c as usize], usize::MAX, "corner {c} twice in the order");
                place[c as usize] = k;
            }
            for c in 0..n {
                match roles[c] {
                    Role::Drains => {
                        assert_eq!(level[c], filled[c], "round {round}: corner {c}'s level");
                        let d = down[c];
                        assert!(
                            links[c].contains(&d) && d != c as u32,
                            "round {round}: corner {c} drains to a neighbor"
                        );
                        assert!(level[d as usize] <= level[c], "round {round}: corner {c} drains uphill");
                        assert!(place[d as usize] < place[c], "round {round}: corner {c} before its downstream");
                        let mut at = c;
                        for _ in 0..=n {
                            if roles[at] != Role::Drains {
                                break;
                            }
                            at = down[at] as usize;
                        }
                        assert_eq!(roles[at], Role::Outlet, "round {round}: corner {c} reaches an outlet");
                    }
                    Role::Outlet => assert!(down[c] == NONE && place[c] != usize::MAX),
                    Role::Unused => assert!(down[c] == NONE && place[c] == usize::MAX),
                }
            }
        }
    }
}
