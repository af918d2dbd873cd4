//! A map type's targets, measured on the tiles a try classifies: what the generator checks
//! before it keeps a try, and the report a map carries ([`MapTypeReport`]).
//!
//! The numbers follow [`MapStats`](crate::MapStats)' rules on the generated tiles (before
//! lakes and edits): a landmass is land tiles connected through their neighbors, a continent
//! one of at least [`CONTINENT_MIN_SHARE`] of the land and [`CONTINENT_MIN_TILES`] tiles, the
//! strait the fewest tiles between two continents.

use std::collections::VecDeque;

use crate::config::{MapType, MapTypeConfig, SEA_SHARE_TOLERANCE};

pub(crate) use super::graph::TileGraph;
use super::knots::{MAX_BLOB_SHARE, MAX_STRAIGHT_RIDGE, straight_ridge};

/// A landmass is a continent when it holds at least this share of the map's land tiles (and
/// [`CONTINENT_MIN_TILES`]).
pub const CONTINENT_MIN_SHARE: f64 = 0.05;

/// A landmass is a continent when it has at least this many tiles (and
/// [`CONTINENT_MIN_SHARE`] of the land).
pub const CONTINENT_MIN_TILES: u32 = 16;

/// What a map type promises, one number each (see the table on [`MapType`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum MapTypeTarget {
    /// The sea's share of the map's tiles.
    SeaShare,
    /// The mountains' share of the land tiles.
    MountainShare,
    /// How many continents.
    Continents,
    /// The second largest continent's share of the land (0 with fewer than two continents).
    SecondContinentShare,
    /// The largest landmass' share of the land.
    LargestLandmassShare,
    /// How many landmasses (continents and islands).
    Landmasses,
    /// The fewest tiles of sea between two continents (infinite with fewer than two).
    NarrowestStrait,
    /// The largest sea's share of the sea tiles.
    LargestSeaShare,
    /// Tiles of the largest sea on the map's edge (the first or last row, and the first or
    /// last column of a map that does not wrap).
    LargestSeaEdgeTiles,
    /// The rows the continent spanning the fewest spans, as a share of the map's rows (0
    /// without a continent).
    ContinentHeight,
    /// With ranges: the most mountains in a row along one of the hex axes
    /// ([`MapStats::straight_ridge`](crate::MapStats::straight_ridge)).
    StraightRidge,
    /// With ranges: the share of the mountains with 5 or 6 mountain neighbors
    /// ([`MapStats::blob_share`](crate::MapStats::blob_share)).
    MountainBlobShare,
}

impl MapTypeTarget {
    /// The target's name, as the report prints it.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::SeaShare => "sea share",
            Self::MountainShare => "mountain share of the land",
            Self::Continents => "continents",
            Self::SecondContinentShare => "second continent's share of the land",
            Self::LargestLandmassShare => "largest landmass' share of the land",
            Self::Landmasses => "landmasses",
            Self::NarrowestStrait => "narrowest strait (tiles)",
            Self::LargestSeaShare => "largest sea's share of the sea",
            Self::LargestSeaEdgeTiles => "largest sea's tiles on the map's edge",
            Self::ContinentHeight => "least continent's height (share of the rows)",
            Self::StraightRidge => "straightest ridge (mountains in a row)",
            Self::MountainBlobShare => "mountains in blobs",
        }
    }

    /// Whether it measures the mountain ranges' shape (which only another layout changes).
    #[must_use]
    pub fn is_about_ranges(self) -> bool {
        matches!(self, Self::StraightRidge | Self::MountainBlobShare)
    }

    /// Whether it is a share (of the map, the land or the sea; printed in percent) rather than a
    /// count.
    #[must_use]
    pub fn is_share(self) -> bool {
        matches!(
            self,
            Self::SeaShare
                | Self::MountainShare
                | Self::SecondContinentShare
                | Self::LargestLandmassShare
                | Self::LargestSeaShare
                | Self::MountainBlobShare
                | Self::ContinentHeight
        )
    }
}

/// One target of a map, measured: the value and the range it must lie in.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct TargetCheck {
    /// Which target.
    pub target: MapTypeTarget,
    /// What the map has.
    pub measured: f64,
    /// The smallest value allowed.
    pub min: f64,
    /// The largest value allowed (infinite when there is no upper bound).
    pub max: f64,
}

impl TargetCheck {
    /// Whether the measured value lies in the range.
    #[must_use]
    pub fn met(&self) -> bool {
        self.measured >= self.min && self.measured <= self.max
    }

    /// How far the measured value lies outside the range (0 when met).
    #[must_use]
    pub fn miss(&self) -> f64 {
        if self.measured < self.min {
            self.min - self.measured
        } else if self.measured > self.max {
            self.measured - self.max
        } else {
            0.0
        }
    }
}

impl std::fmt::Display for TargetCheck {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let value = |v: f64| match v {
            v if v.is_infinite() => "none".to_owned(),
            v if self.target.is_share() => format!("{:.1} %", v * 100.0),
            v => format!("{v}"),
        };
        let range = match (self.min, self.max) {
            (min, max) if max.is_infinite() => format!("at least {}", value(min)),
            (min, max) if min <= 0.0 => format!("at most {}", value(max)),
            (min, max) => format!("{} to {}", value(min), value(max)),
        };
        let verdict = if self.met() { "met".to_owned() } else { format!("MISSED by {}", value(self.miss())) };
        write!(f, "{}: {} ({range}): {verdict}", self.target.name(), value(self.measured))
    }
}

/// What came of a map type: the targets measured on the map kept, and the tries it took. The
/// generator tries layouts drawn from the seed (`0, 1, ...`), each at the level's sea share and
/// then at shares either side of it ([`SEA_STEPS`](crate::SEA_STEPS), within
/// [`SEA_SHARE_TOLERANCE`]), and keeps the first that meets every target,
/// or, when none does after [`MAX_TRIES`](crate::MAX_TRIES), the one that misses fewest (then
/// by least): its report says which target it missed and by how much.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct MapTypeReport {
    /// The type.
    pub kind: MapType,
    /// Tries made, the kept one included (1: the first try met every target).
    pub tries: u32,
    /// The layout kept (0 is the seed's first).
    pub layout: u32,
    /// The sea share the kept try aimed at.
    pub sea_share: f64,
    /// Every target, measured on the map kept.
    pub checks: Vec<TargetCheck>,
}

impl MapTypeReport {
    /// Whether every target is met.
    #[must_use]
    pub fn met(&self) -> bool {
        self.checks.iter().all(TargetCheck::met)
    }

    /// The targets missed.
    pub fn missed(&self) -> impl Iterator<Item = &TargetCheck> {
        self.checks.iter().filter(|c| !c.met())
    }

    /// The check of one target, if the type has it.
    #[must_use]
    pub fn check(&self, target: MapTypeTarget) -> Option<&TargetCheck> {
        self.checks.iter().find(|c| c.target == target)
    }
}

impl std::fmt::Display for MapTypeReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let verdict = if self.met() { "every target met" } else { "targets missed" };
        write!(f, "{}: {verdict} after {} tries (layout {})", self.kind.name(), self.tries, self.layout)?;
        for check in &self.checks {
            write!(f, "\n  {check}")?;
        }
        Ok(())
    }
}

/// Connected components of the tiles a [`components`] search kept.
pub(crate) struct Components {
    /// Each tile's component (`u32::MAX` for a tile not kept).
    pub of: Vec<u32>,
    /// Each component's first tile (in index order: row by row on a map).
    pub first: Vec<usize>,
    /// Each component's size.
    pub sizes: Vec<u32>,
}

/// The connected components of the tiles `member` keeps, over `neighbors` (each tile's
/// neighbors by index), found in index order: a component's first tile is its lowest index.
pub(crate) fn components(neighbors: &[[Option<u32>; 6]], member: impl Fn(usize) -> bool) -> Components {
    let n = neighbors.len();
    let mut out = Components { of: vec![u32::MAX; n], first: Vec::new(), sizes: Vec::new() };
    let mut queue = VecDeque::new();
    for start in 0..n {
        if out.of[start] != u32::MAX || !member(start) {
            continue;
        }
        let id = out.sizes.len() as u32;
        out.of[start] = id;
        out.first.push(start);
        queue.push_back(start);
        let mut size = 0;
        while let Some(i) = queue.pop_front() {
            size += 1;
            for nb in neighbors[i].iter().flatten().map(|&nb| nb as usize) {
                if out.of[nb] == u32::MAX && member(nb) {
                    out.of[nb] = id;
                    queue.push_back(nb);
                }
            }
        }
        out.sizes.push(size);
    }
    out
}

/// The fewest tiles between two different labelled groups (`label[i]`, `u32::MAX` for a tile in
/// none), over `neighbors`: a breadth-first search from every
/// labelled tile at once, each tile taking the label that reaches it first; two groups are
/// nearest across an edge between tiles of different labels. `None` with fewer than two labels.
pub(crate) fn nearest_between(neighbors: &[[Option<u32>; 6]], label: &[u32]) -> Option<u32> {
    let n = label.len();
    let (mut dist, mut owner) = (vec![u32::MAX; n], vec![u32::MAX; n]);
    let mut queue = VecDeque::new();
    for i in 0..n {
        if label[i] != u32::MAX {
            (dist[i], owner[i]) = (0, label[i]);
            queue.push_back(i);
        }
    }
    let mut best: Option<u32> = None;
    while let Some(i) = queue.pop_front() {
        for nb in neighbors[i].iter().flatten().map(|&nb| nb as usize) {
            if owner[nb] == u32::MAX {
                (dist[nb], owner[nb]) = (dist[i] + 1, owner[i]);
                queue.push_back(nb);
            } else if owner[nb] != owner[i] {
                // Tiles between the two groups along this edge: the steps less one.
                let between = dist[i] + dist[nb];
                best = Some(best.map_or(between, |b| b.min(between)));
            }
        }
    }
    best
}

/// Measures every target of `config`'s type on a classification (`sea[i]`, `mountain[i]`)
/// of the graph's tiles.
pub(crate) fn measure(config: &MapTypeConfig, graph: &TileGraph, sea: &[bool], mountain: &[bool]) -> Vec<TargetCheck> {
    let n = sea.len();
    let land: Vec<bool> = sea.iter().map(|s| !s).collect();
    let land_tiles = land.iter().filter(|&&l| l).count();
    let share = |part: usize, whole: usize| part as f64 / whole.max(1) as f64;
    let check = |target, measured, min, max| TargetCheck { target, measured, min, max };
    let level = config.sea_share();
    let wanted_mountains = (f64::from(config.mountains) * land_tiles as f64).round();
    let mountains = mountain.iter().zip(&land).filter(|&(&m, &l)| m && l).count();
    let mut checks = vec![
        check(
            MapTypeTarget::SeaShare,
            share(n - land_tiles, n),
            level - SEA_SHARE_TOLERANCE,
            level + SEA_SHARE_TOLERANCE,
        ),
        check(
            MapTypeTarget::MountainShare,
            share(mountains, land_tiles),
            share((wanted_mountains - 1.0).max(0.0) as usize, land_tiles),
            share(wanted_mountains as usize + 1, land_tiles),
        ),
    ];

    let Components { of: mass_of, sizes: masses, .. } = components(&graph.neighbors, |i| land[i]);
    let mut sorted = masses.clone();
    sorted.sort_unstable_by(|a, b| b.cmp(a));
    let largest = share(sorted.first().copied().unwrap_or(0) as usize, land_tiles);
    let continent = |size: u32| size >= CONTINENT_MIN_TILES && share(size as usize, land_tiles) >= CONTINENT_MIN_SHARE;
    let continents = sorted.iter().filter(|&&s| continent(s)).count();
    let strait = || {
        let label: Vec<u32> = mass_of
            .iter()
            .map(|&m| if m != u32::MAX && continent(masses[m as usize]) { m } else { u32::MAX })
            .collect();
        nearest_between(&graph.neighbors, &label).map_or(f64::INFINITY, f64::from)
    };
    match config.kind {
        MapType::Pangaea => checks.push(check(MapTypeTarget::LargestLandmassShare, largest, 0.8, 1.0)),
        MapType::Continents => {
            checks.push(check(MapTypeTarget::Continents, continents as f64, 2.0, 3.0));
            // The second continent, not the second landmass: an island is no continent.
            let second = sorted.get(1).copied().filter(|&s| continent(s)).unwrap_or(0);
            let second = share(second as usize, land_tiles);
            checks.push(check(MapTypeTarget::SecondContinentShare, second, 0.25, 1.0));
            checks.push(check(MapTypeTarget::NarrowestStrait, strait(), 2.0, f64::INFINITY));
            // Each continent spans most of the map north to south, as the Americas do.
            let mut span = vec![(u32::MAX, 0u32); masses.len()];
            for (i, &m) in mass_of.iter().enumerate().filter(|&(_, &m)| m != u32::MAX) {
                let s = &mut span[m as usize];
                *s = (s.0.min(graph.row[i]), s.1.max(graph.row[i]));
            }
            let least = (0..masses.len())
                .filter(|&m| continent(masses[m]))
                .map(|m| f64::from(span[m].1 - span[m].0 + 1) / f64::from(graph.rows.max(1)))
                .fold(f64::INFINITY, f64::min);
            checks.push(check(MapTypeTarget::ContinentHeight, if least.is_finite() { least } else { 0.0 }, 0.55, 1.0));
        }
        MapType::SmallContinents => {
            checks.push(check(MapTypeTarget::Continents, continents as f64, 4.0, 8.0));
            checks.push(check(MapTypeTarget::LargestLandmassShare, largest, 0.0, 0.4));
            checks.push(check(MapTypeTarget::NarrowestStrait, strait(), 2.0, f64::INFINITY));
        }
        MapType::Archipelago => {
            checks.push(check(MapTypeTarget::Landmasses, masses.len() as f64, 10.0, f64::INFINITY));
            checks.push(check(MapTypeTarget::LargestLandmassShare, largest, 0.0, 0.15));
        }
        MapType::Fractal => {}
        MapType::InlandSea => {
            let Components { of: sea_of, sizes: seas, .. } = components(&graph.neighbors, |i| sea[i]);
            let sea_tiles = n - land_tiles;
            let (biggest, size) = seas
                .iter()
                .enumerate()
                .max_by_key(|&(i, &s)| (s, std::cmp::Reverse(i)))
                .map_or((u32::MAX, 0), |(i, &s)| (i as u32, s));
            let on_edge = (0..n).filter(|&i| graph.edge[i] && sea_of[i] == biggest && biggest != u32::MAX).count();
            checks.push(check(MapTypeTarget::LargestSeaShare, share(size as usize, sea_tiles), 0.8, 1.0));
            checks.push(check(MapTypeTarget::LargestSeaEdgeTiles, on_edge as f64, 0.0, 0.0));
            checks.push(check(MapTypeTarget::LargestLandmassShare, largest, 0.9, 1.0));
        }
    }
    if config.ranges {
        let mountain = |i: usize| land[i] && mountain[i];
        let around = |i: usize| graph.neighbors[i].iter().flatten().filter(|&&j| mountain(j as usize)).count();
        let blobs = (0..n).filter(|&i| mountain(i) && around(i) >= 5).count();
        checks.push(check(
            MapTypeTarget::StraightRidge,
            straight_ridge(graph, &mountain) as f64,
            0.0,
            MAX_STRAIGHT_RIDGE,
        ));
        checks.push(check(MapTypeTarget::MountainBlobShare, share(blobs, mountains), 0.0, MAX_BLOB_SHARE));
    }
    checks
}
