//! The flat map's rules on a globe's tile graph (pentagons included): what a tile is
//! ([`GlobeTerrain::tile_info`]), what entering it costs, cheapest paths, the tiles within a
//! budget, and what a unit sees. Pure functions of the globe: the same answer on any thread, in
//! any order; ties go by tile id, never by hash or thread order.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use super::GlobeTile;
use super::climate::latitude;
use super::project::{self, Dir};
use super::terrain::GlobeTerrain;
use crate::kind::TileKind;
use crate::ruleset::TileTerrain;
use crate::vocab::Biome;

/// What a globe's tile is ([`GlobeTerrain::tile_info`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct GlobeTileInfo {
    /// The tile.
    pub tile: GlobeTile,
    /// Its kind, by its center's height.
    pub kind: TileKind,
    /// What it is under the globe's terrain ruleset ([`GlobeTerrain::ruleset`], the 13 biomes:
    /// read its biome with [`TerrainRuleset::biome`](crate::TerrainRuleset::biome)): its terrain
    /// (a biome set by hand first; else by its climate and the config's biome table on a globe
    /// with a climate, coast or ocean at sea; else by its kind), landform and traits.
    pub terrain: TileTerrain,
    /// Its center's height above the sphere of [`GlobeTerrain::radius`], in world units, on the
    /// manipulated surface.
    pub elevation: f32,
    /// Its center's latitude in degrees, north positive.
    pub latitude: f64,
    /// Its center's longitude in degrees, east positive, in `(-180, 180]`.
    pub longitude: f64,
    /// Whether it is one of the 12 pentagons.
    pub pentagon: bool,
}

/// A cheapest path over a globe ([`GlobeTerrain::path`]): the rules of the flat map's
/// [`Path`](crate::Path), on the globe's tiles.
#[derive(Debug, Clone, PartialEq, Eq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct GlobePath {
    /// The tiles from the start to the goal, both included.
    pub tiles: Vec<GlobeTile>,
    /// What every step costs, added up (the start costs nothing).
    pub cost: u32,
}

impl GlobeTerrain {
    /// What a tile is: its kind, terrain, center elevation, latitude and longitude; `None` for a
    /// tile not of this globe. The one answer to what a globe's tile is.
    #[must_use]
    pub fn tile_info(&self, tile: GlobeTile) -> Option<GlobeTileInfo> {
        let kind = self.tile_kind(tile)?;
        let dir = self.center(tile);
        let longitude = (-dir[2]).atan2(dir[0]).to_degrees();
        Some(GlobeTileInfo {
            tile,
            kind,
            terrain: self.tile_terrain(tile)?,
            elevation: self.center_height(tile) * self.config().terrain.max_elevation,
            latitude: latitude(dir) * 90.0,
            longitude: if longitude <= -180.0 { 180.0 } else { longitude },
            pentagon: self.grid().is_pentagon(tile),
        })
    }

    /// The cost of entering a tile by the movement model
    /// ([`MovementConfig::enter_with`](crate::MovementConfig::enter_with) of its terrain's
    /// traits, embarking on a sea biome; a globe has no rivers yet); `None` when it cannot be
    /// entered, or is not of this globe.
    #[must_use]
    pub fn move_cost(&self, tile: GlobeTile) -> Option<u32> {
        let t = self.tile_terrain(tile)?;
        let sea = matches!(self.tile_biome(tile)?, Biome::Ocean | Biome::Coast);
        self.config().movement.enter_with(t.traits.movement, sea, false)
    }

    /// The sight rule's height of a tile: 2 on a mountain, 1 on a tall biome
    /// ([`SightConfig::tall`](crate::SightConfig::tall)), else 0; `None` for a tile not of this
    /// globe.
    #[must_use]
    pub fn sight_height(&self, tile: GlobeTile) -> Option<u8> {
        Some(if self.tile_kind(tile)? == TileKind::Mountain {
            2
        } else {
            u8::from(self.tile_terrain(tile)?.traits.tall)
        })
    }

    /// A cheapest path from `from` to `to` by [`GlobeTerrain::move_cost`]; `None` when either is
    /// not of this globe or `to` cannot be reached. Of several cheapest paths, the one a search
    /// taking tiles in order of cost, then of id, finds first.
    #[must_use]
    pub fn path(&self, from: GlobeTile, to: GlobeTile) -> Option<GlobePath> {
        self.path_avoiding(from, to, |_| false)
    }

    /// As [`GlobeTerrain::path`], never entering a tile `blocked` says is taken (never asked
    /// about `from`).
    #[must_use]
    pub fn path_avoiding(
        &self,
        from: GlobeTile,
        to: GlobeTile,
        blocked: impl Fn(GlobeTile) -> bool,
    ) -> Option<GlobePath> {
        if !self.grid().contains(from) || !self.grid().contains(to) {
            return None;
        }
        let best = self.search(from, u32::MAX, Some(to), &blocked);
        let cost = best[to.0 as usize].0;
        if cost == UNREACHED {
            return None;
        }
        let mut tiles = vec![to];
        while let Some(&last) = tiles.last().filter(|&&t| t != from) {
            tiles.push(best[last.0 as usize].1);
        }
        tiles.reverse();
        Some(GlobePath { tiles, cost })
    }

    /// Every tile reachable from `from` for at most `budget` movement points, with the cost of
    /// its cheapest path, in order of cost then of id (`from` first, at 0); empty when `from`
    /// is not of this globe.
    #[must_use]
    pub fn reachable(&self, from: GlobeTile, budget: u32) -> Vec<(GlobeTile, u32)> {
        self.reachable_avoiding(from, budget, |_| false)
    }

    /// As [`GlobeTerrain::reachable`], never entering a tile `blocked` says is taken.
    #[must_use]
    pub fn reachable_avoiding(
        &self,
        from: GlobeTile,
        budget: u32,
        blocked: impl Fn(GlobeTile) -> bool,
    ) -> Vec<(GlobeTile, u32)> {
        if !self.grid().contains(from) {
            return Vec::new();
        }
        let best = self.search(from, budget, None, &blocked);
        let mut out: Vec<(GlobeTile, u32)> = self
            .grid()
            .tiles()
            .map(|t| (t, best[t.0 as usize].0))
            .filter(|&(_, c)| c != UNREACHED && c <= budget)
            .collect();
        out.sort_unstable_by_key(|&(t, c)| (c, t));
        out
    }

    /// Dijkstra's search from `from` over the tiles it may enter within `budget`, stopping once
    /// `goal` is settled: each tile's best cost ([`UNREACHED`] unreached) and the tile it came
    /// from. Costs add up saturating: a cost of `u32::MAX` (some `MAX_MOVE_COST` times more steps
    /// than a globe has) counts as unreached.
    fn search(
        &self,
        from: GlobeTile,
        budget: u32,
        goal: Option<GlobeTile>,
        blocked: &dyn Fn(GlobeTile) -> bool,
    ) -> Vec<(u32, GlobeTile)> {
        let mut best = vec![(UNREACHED, from); self.grid().tile_count() as usize];
        best[from.0 as usize] = (0, from);
        let mut open = BinaryHeap::from([Reverse((0u32, from))]);
        while let Some(Reverse((cost, tile))) = open.pop() {
            if cost > best[tile.0 as usize].0 {
                continue;
            }
            if Some(tile) == goal {
                break;
            }
            let neighbors = self.grid().neighbors(tile).expect("a tile of the globe");
            for &next in &neighbors {
                if next == from || blocked(next) {
                    continue;
                }
                let Some(step) = self.move_cost(next) else { continue };
                let total = cost.saturating_add(step);
                if total != UNREACHED && total <= budget && total < best[next.0 as usize].0 {
                    best[next.0 as usize] = (total, tile);
                    open.push(Reverse((total, next)));
                }
            }
        }
        best
    }

    /// The tiles a unit on `from` sees with sight `radius` (plus the bonus of a tall tile or a
    /// mountain, [`SightConfig`](crate::SightConfig)), in order of id; empty for a tile not of
    /// this globe. The flat map's rule on the globe: each tile within reach (in steps over the
    /// tile graph) whose view is not blocked by a higher tile or a mountain strictly between.
    /// The tiles between are those the great circle from `from`'s center to the tile's passes
    /// over, sampled [`GLOBE_SIGHT_SAMPLES`] times a step. `from` is always seen. Any radius: the work
    /// is bounded by the globe's tiles.
    #[must_use]
    pub fn field_of_view(&self, from: GlobeTile, radius: u32) -> Vec<GlobeTile> {
        let Some(own) = self.sight_height(from) else { return Vec::new() };
        let sight = &self.config().sight;
        let reach = radius.saturating_add(match own {
            2 => sight.mountain_bonus,
            1 => sight.tall_bonus,
            _ => 0,
        });
        let mut out: Vec<GlobeTile> = self
            .grid()
            .within(from, reach)
            .into_iter()
            .filter(|&(tile, steps)| {
                self.between(from, tile, steps).all(|t| self.sight_height(t).is_some_and(|h| h <= own && h < 2))
            })
            .map(|(tile, _)| tile)
            .collect();
        out.sort_unstable();
        out
    }

    /// The tiles strictly between two tiles `steps` apart, on the great circle between their
    /// centers.
    fn between(&self, from: GlobeTile, to: GlobeTile, steps: u32) -> impl Iterator<Item = GlobeTile> + '_ {
        let (a, b) = (self.center(from), self.center(to));
        let samples = steps * GLOBE_SIGHT_SAMPLES;
        (1..samples).filter_map(move |k| {
            let t = f64::from(k) / f64::from(samples);
            self.grid().tile_at(slerp(a, b, t)).filter(|&tile| tile != from && tile != to)
        })
    }
}

/// A tile's cost before a search reaches it.
const UNREACHED: u32 = u32::MAX;

/// How many points a step of a line of sight is sampled at.
pub const GLOBE_SIGHT_SAMPLES: u32 = 4;

/// The point a fraction `t` of the way along the great circle from `a` to `b` (unit vectors).
/// Between opposite points, whose great circles are many, the one through the point of the
/// equator (or, from a pole, of the prime meridian) a quarter turn east of `a`.
fn slerp(a: Dir, b: Dir, t: f64) -> Dir {
    let angle = project::dot(a, b).clamp(-1.0, 1.0).acos();
    if angle < 1e-12 {
        return a;
    }
    if angle > std::f64::consts::PI - 1e-9 {
        let side = project::cross(a, [0.0, 1.0, 0.0]);
        let middle = if project::dot(side, side) < 1e-18 { [1.0, 0.0, 0.0] } else { project::normalize(side) };
        return if t <= 0.5 { slerp(a, middle, 2.0 * t) } else { slerp(middle, b, 2.0 * t - 1.0) };
    }
    let (wa, wb) = (((1.0 - t) * angle).sin(), (t * angle).sin());
    project::normalize([wa * a[0] + wb * b[0], wa * a[1] + wb * b[1], wa * a[2] + wb * b[2]])
}
