//! Movement over the map by its movement model ([`MovementConfig`](crate::MovementConfig)):
//! cheapest paths (A*), the tiles within a budget of movement points, and a path split into
//! turns. Pure functions of the compiled terrain: the same answer on any thread, in any order.
//!
//! The rules are on [`Path`].

use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap};

use hexx::Hex;

use crate::terrain::Terrain;
use crate::terrain::rules::RuleTable;
use crate::vocab::Biome;

/// Most tiles a path or reach search visits (Civilization VI's Huge map has about 7,000).
pub const MAX_PATH_TILES: usize = 1 << 18;

/// A cheapest path over the map ([`Terrain::path`]).
///
/// The rules, written once:
/// - **A step** costs [`Terrain::step_cost`](crate::Terrain::step_cost): entering the tile
///   ([`Terrain::move_cost`](crate::Terrain::move_cost)), plus the movement model's `river`
///   when a river runs on the edge crossed (`rivers.model: Edges`); the start tile costs
///   nothing; a tile that cannot be entered is never on a path.
/// - **Paths** run between tiles of the map, across the seam of a wrapping map when that is
///   cheaper. Of several cheapest paths, one is chosen by a fixed order (the tile's place in the
///   map's rows), never by thread or hash order.
/// - **The search** visits at most [`MAX_PATH_TILES`] tiles; on an unbounded world a goal farther
///   than that allows is not found (`None`), like an unreachable one.
/// - **Turns** (Civilization V's rule): a unit with any movement points left may enter a tile it
///   can enter; it pays the step's cost, or all the points it has left when the cost is more. A
///   turn ends when no points are left; the next turn starts with the full points. The points
///   left this turn may be more than the full points (a bonus for this turn): they are spent as
///   they are.
/// - **Wrapping maps**: a path walks the map's own tiles, across the seam where that is cheaper;
///   there are no copies to choose between, only paths, and ties between paths go by the fixed
///   order above.
/// - **Any number**: a budget or points up to `u32::MAX` are answered without overflow, and the
///   work is bounded by [`MAX_PATH_TILES`], never by the number.
#[derive(Debug, Clone, PartialEq, Eq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct Path {
    /// The tiles from the start to the goal, both included (the map's own tiles).
    pub tiles: Vec<Hex>,
    /// What every step costs, added up.
    pub cost: u32,
}

/// Where a path's turns end.
#[derive(Debug, Clone, PartialEq, Eq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct Turns {
    /// For each tile of the path, the turn it is reached in (0: this turn).
    pub turn: Vec<u32>,
    /// The turns the path takes (the last tile's turn plus one; 0 for a path of one tile).
    pub count: u32,
    /// The tile each turn ends on (the last is the goal).
    pub ends: Vec<Hex>,
    /// For each tile of the path, the movement points left on reaching it, in its turn (the
    /// first: the points left this turn): what a walk stopped there has not spent.
    pub left: Vec<u32>,
}

/// A search's record of each tile it reached: the best cost so far and the tile it came from.
/// An array in the rules' table's order on a bounded map (its tiles' places in the map's rows),
/// a hash map on an unbounded world.
enum Best<'a> {
    Dense { table: &'a RuleTable, cells: Vec<(u32, Hex)> },
    Sparse(HashMap<Hex, (u32, Hex)>),
}

/// A tile as a search holds it: its slot in [`Best`] (its place in the map's rows as one number,
/// so also the search's order of ties) and what entering it costs.
#[derive(Clone, Copy)]
struct Slot {
    key: i64,
    enter: Option<u32>,
}

impl<'a> Best<'a> {
    fn new(terrain: &'a Terrain) -> Self {
        match terrain.rule_table() {
            Some(table) => Self::Dense { table, cells: vec![(u32::MAX, Hex::ZERO); table.len()] },
            None => Self::Sparse(HashMap::new()),
        }
    }

    /// A tile of the map's slot.
    #[inline]
    fn slot(&self, terrain: &Terrain, tile: Hex) -> Slot {
        let [col, row] = terrain.offset_of(tile);
        match self {
            Self::Dense { table, .. } => {
                let index = table.index([col, row]).expect("a tile of the map");
                Slot { key: index as i64, enter: table.cost(index) }
            }
            // Rows and columns are within `MAX_WORLD_TILE`, so this order is the rows' order.
            Self::Sparse(_) => Slot {
                key: (i64::from(row) << 32) + i64::from(col),
                enter: crate::terrain::rules::evaluate_cost(terrain, tile),
            },
        }
    }

    /// What crossing the edge of the tile in `slot` toward its neighbor `d` adds to the step:
    /// a river on it (rivers on edges are on bounded maps, which have a rule table).
    #[inline]
    fn crossing(&self, slot: Slot, d: usize) -> u32 {
        match self {
            Self::Dense { table, .. } => table.crossing(slot.key as usize, d),
            Self::Sparse(_) => 0,
        }
    }

    #[inline]
    fn get(&self, tile: Hex, slot: Slot) -> Option<(u32, Hex)> {
        match self {
            Self::Dense { cells, .. } => Some(cells[slot.key as usize]).filter(|c| c.0 != u32::MAX),
            Self::Sparse(map) => map.get(&tile).copied(),
        }
    }

    #[inline]
    fn set(&mut self, tile: Hex, slot: Slot, best: (u32, Hex)) {
        match self {
            Self::Dense { cells, .. } => cells[slot.key as usize] = best,
            Self::Sparse(map) => {
                map.insert(tile, best);
            }
        }
    }
}

impl Terrain {
    /// The cheapest path from `from` to `to` by the map's movement model (A*, its estimate the
    /// hex distance times the cheapest tile, so never above the true cost); `None` when either
    /// is off the map, `to` cannot be entered, or no path exists within [`MAX_PATH_TILES`]. See
    /// the rules on [`Path`].
    #[must_use]
    pub fn path(&self, from: Hex, to: Hex) -> Option<Path> {
        self.path_avoiding(from, to, |_| false)
    }

    /// As [`Terrain::path`], never entering a tile `blocked` says is taken (another unit, a
    /// city): it is asked about the map's own tiles, never about `from`; a blocked goal has no
    /// path.
    #[must_use]
    pub fn path_avoiding(&self, from: Hex, to: Hex, blocked: impl Fn(Hex) -> bool) -> Option<Path> {
        let (from, to) = (self.wrap_tile(from)?, self.wrap_tile(to)?);
        if from == to {
            return Some(Path { tiles: vec![from], cost: 0 });
        }
        if blocked(to) {
            return None;
        }
        self.move_cost(to)?;
        let cheapest = self.cheapest_move();
        let estimate = |tile: Hex| self.distance(tile, to).map_or(u32::MAX, |d| d.saturating_mul(cheapest));
        let mut best = Best::new(self);
        let start = best.slot(self, from);
        best.set(from, start, (0, from));
        let mut open = BinaryHeap::from([Reverse((estimate(from), 0u32, start.key, from.x, from.y))]);
        let mut visited = 0usize;
        while let Some(Reverse((_, cost, key, x, y))) = open.pop() {
            let tile = Hex::new(x, y);
            let slot = Slot { key, enter: None };
            if best.get(tile, slot).is_some_and(|(c, _)| c < cost) {
                continue;
            }
            if tile == to {
                let mut tiles = vec![to];
                let mut at = to;
                while at != from {
                    at = best.get(at, best.slot(self, at)).expect("a reached tile").1;
                    tiles.push(at);
                }
                tiles.reverse();
                return Some(Path { tiles, cost });
            }
            visited += 1;
            if visited > MAX_PATH_TILES {
                return None;
            }
            for (d, next) in self.neighbors(tile)?.into_iter().enumerate() {
                let Some(next) = next.filter(|&n| n != from) else { continue };
                let slot = best.slot(self, next);
                let Some(step) = slot.enter.filter(|_| !blocked(next)) else { continue };
                let total = cost + step + best.crossing(Slot { key, enter: None }, d);
                if best.get(next, slot).is_none_or(|(c, _)| total < c) {
                    best.set(next, slot, (total, tile));
                    open.push(Reverse((total.saturating_add(estimate(next)), total, slot.key, next.x, next.y)));
                }
            }
        }
        None
    }

    /// Every tile reachable from `from` for at most `budget` movement points, with the cost of
    /// its cheapest path, in order of cost then of the map's rows (`from` first, at 0); empty
    /// when `from` is off the map. At most [`MAX_PATH_TILES`] tiles.
    #[must_use]
    pub fn reachable(&self, from: Hex, budget: u32) -> Vec<(Hex, u32)> {
        self.reachable_avoiding(from, budget, |_| false)
    }

    /// As [`Terrain::reachable`], never entering a tile `blocked` says is taken (asked about the
    /// map's own tiles, never about `from`).
    #[must_use]
    pub fn reachable_avoiding(&self, from: Hex, budget: u32, blocked: impl Fn(Hex) -> bool) -> Vec<(Hex, u32)> {
        let Some(from) = self.wrap_tile(from) else { return Vec::new() };
        let mut best = Best::new(self);
        let start = best.slot(self, from);
        best.set(from, start, (0, from));
        let mut open = BinaryHeap::from([Reverse((0u32, start.key, from.x, from.y))]);
        let mut out = Vec::new();
        while let Some(Reverse((cost, key, x, y))) = open.pop() {
            let tile = Hex::new(x, y);
            if best.get(tile, Slot { key, enter: None }).is_some_and(|(c, _)| c < cost) {
                continue;
            }
            out.push((tile, cost));
            if out.len() >= MAX_PATH_TILES {
                break;
            }
            let Some(neighbors) = self.neighbors(tile) else { continue };
            for (d, next) in neighbors.into_iter().enumerate() {
                let Some(next) = next.filter(|&n| n != from) else { continue };
                let slot = best.slot(self, next);
                let Some(step) = slot.enter.filter(|_| !blocked(next)) else { continue };
                let total = cost + step + best.crossing(Slot { key, enter: None }, d);
                if total <= budget && best.get(next, slot).is_none_or(|(c, _)| total < c) {
                    best.set(next, slot, (total, tile));
                    open.push(Reverse((total, slot.key, next.x, next.y)));
                }
            }
        }
        out
    }

    /// A path split into turns for a unit with `points` movement points a turn and `left` this
    /// turn (Civilization V's rule, on [`Path`]; `left` may be more than `points`, a bonus spent
    /// this turn); `None` when the path has a step and neither `left` nor `points` can pay for
    /// it (both 0, or `points` 0 once `left` is spent), or a tile of it cannot be entered.
    #[must_use]
    pub fn turns(&self, path: &Path, points: u32, left: u32) -> Option<Turns> {
        let mut turn = 0u32;
        let mut remaining = left;
        let mut turns = Turns { turn: vec![0], count: 0, ends: Vec::new(), left: vec![left] };
        for (i, &tile) in path.tiles.iter().enumerate().skip(1) {
            if remaining == 0 {
                if points == 0 {
                    return None;
                }
                turns.ends.push(path.tiles[i - 1]);
                turn += 1;
                remaining = points;
            }
            let cost = self.step_cost(path.tiles[i - 1], tile)?;
            remaining -= cost.min(remaining);
            turns.turn.push(turn);
            turns.left.push(remaining);
        }
        if path.tiles.len() > 1 {
            turns.ends.push(*path.tiles.last().expect("a step"));
            turns.count = turn + 1;
        }
        Some(turns)
    }

    /// What the step from `from` to its neighbor `to` costs by the map's movement model:
    /// entering `to` ([`Terrain::move_cost`]), plus the model's `river` when a river runs on the
    /// edge between them ([`Terrain::crosses_river`]); `None` when `to` cannot be entered or
    /// they are not neighbors on the map.
    #[must_use]
    pub fn step_cost(&self, from: Hex, to: Hex) -> Option<u32> {
        self.step_direction(from, to)?;
        let across = if self.crosses_river(from, to) { self.config().movement.river } else { 0 };
        Some(self.move_cost(to)? + across)
    }

    /// The least a tile can cost to enter by the map's movement model (at least 1).
    fn cheapest_move(&self) -> u32 {
        Biome::ALL.into_iter().filter_map(|b| self.config().movement.enter(b, false)).min().unwrap_or(1).max(1)
    }
}
