//! The globe's grid: its tiles, their neighbors in order, their centers on the unit sphere,
//! the tile a direction falls in and the steps between two tiles.

use super::atlas::{MISSING_AT_ORIGIN, STEPS, Spot, locate};
use super::project::{self, Projection};
use crate::ConfigError;

/// The largest frequency a globe accepts: 655,362 tiles.
pub const MAX_GLOBE_FREQUENCY: u32 = 256;

/// A tile of a globe: its dense id, `0..GlobeGrid::tile_count()`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[serde(transparent)]
pub struct GlobeTile(pub u32);

impl GlobeTile {
    /// The tile as a map file's edits ([`TileEdit::at`](crate::TileEdit::at)) and a tile state
    /// save ([`SavedTile::at`](crate::save::SavedTile::at)) name it on a globe: `(id, 0)`, the
    /// globe's tiles in one row of ids.
    #[must_use]
    pub fn at(self) -> (i32, i32) {
        (i32::try_from(self.0).expect("at most 655,362 tiles"), 0)
    }

    /// The tile an `at` of a globe names (`(id, 0)`, see [`GlobeTile::at`]); `None` for a
    /// negative id or another row. Whether the globe has that tile is
    /// [`GlobeGrid::contains`]'s to say.
    #[must_use]
    pub fn from_at((id, row): (i32, i32)) -> Option<Self> {
        (row == 0).then(|| u32::try_from(id).ok().map(Self)).flatten()
    }
}

/// The globe sizes named after Civilization VI's map sizes, by tile count (a Civ6 map of that
/// size has about as many hexes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum GlobeSize {
    /// Frequency 11: 1,212 tiles (Civ6 Duel, 44x26 = 1,144).
    Duel,
    /// Frequency 15: 2,252 tiles (Tiny, 60x38 = 2,280).
    Tiny,
    /// Frequency 18: 3,242 tiles (Small, 74x46 = 3,404).
    Small,
    /// Frequency 21: 4,412 tiles (Standard, 84x54 = 4,536).
    Standard,
    /// Frequency 24: 5,762 tiles (Large, 96x60 = 5,760).
    Large,
    /// Frequency 26: 6,762 tiles (Huge, 106x66 = 6,996).
    Huge,
}

impl GlobeSize {
    /// Every size, smallest first.
    pub const ALL: [Self; 6] = [Self::Duel, Self::Tiny, Self::Small, Self::Standard, Self::Large, Self::Huge];

    /// The size's frequency.
    #[must_use]
    pub fn frequency(self) -> u32 {
        match self {
            Self::Duel => 11,
            Self::Tiny => 15,
            Self::Small => 18,
            Self::Standard => 21,
            Self::Large => 24,
            Self::Huge => 26,
        }
    }
}

/// A tile's neighbors, going round it counterclockwise seen from outside the globe: six for a
/// hexagon, five for a pentagon.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GlobeNeighbors {
    tiles: [GlobeTile; 6],
    len: u8,
}

impl GlobeNeighbors {
    /// The neighbors, in order.
    #[must_use]
    pub fn as_slice(&self) -> &[GlobeTile] {
        &self.tiles[..usize::from(self.len)]
    }

    /// How many: 5 or 6.
    #[must_use]
    pub fn len(&self) -> usize {
        usize::from(self.len)
    }

    /// Never: every tile has neighbors (for clippy's `len_without_is_empty`).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

impl<'a> IntoIterator for &'a GlobeNeighbors {
    type Item = &'a GlobeTile;
    type IntoIter = std::slice::Iter<'a, GlobeTile>;

    fn into_iter(self) -> Self::IntoIter {
        self.as_slice().iter()
    }
}

/// The grid of a hex globe of frequency `f`: its tiles, their neighbors and their places on the
/// unit sphere (`y` is the axis, north up).
#[derive(Debug, Clone)]
pub struct GlobeGrid {
    frequency: u32,
    pub(super) projection: Projection,
}

impl GlobeGrid {
    /// The grid of frequency `frequency`, 1 to [`MAX_GLOBE_FREQUENCY`]; anything else is refused
    /// by the field's name, `size.Globe.frequency`.
    pub fn new(frequency: u32) -> Result<Self, ConfigError> {
        if !(1..=MAX_GLOBE_FREQUENCY).contains(&frequency) {
            return Err(ConfigError::new(
                "size.Globe.frequency",
                frequency.to_string(),
                format!("1 to {MAX_GLOBE_FREQUENCY}"),
            ));
        }
        Ok(Self { frequency, projection: Projection::new() })
    }

    /// The grid of a named size.
    #[must_use]
    pub fn of_size(size: GlobeSize) -> Self {
        Self { frequency: size.frequency(), projection: Projection::new() }
    }

    /// The frequency `f`: tiles along an edge of the icosahedron.
    #[must_use]
    pub fn frequency(&self) -> u32 {
        self.frequency
    }

    /// How many tiles: `10 f^2 + 2`.
    #[must_use]
    pub fn tile_count(&self) -> u32 {
        10 * self.frequency * self.frequency + 2
    }

    /// Every tile, by id.
    pub fn tiles(&self) -> impl Iterator<Item = GlobeTile> + use<> {
        (0..self.tile_count()).map(GlobeTile)
    }

    /// Whether `tile` is one of the grid's.
    #[must_use]
    pub fn contains(&self, tile: GlobeTile) -> bool {
        tile.0 < self.tile_count()
    }

    /// Whether `tile` is one of the 12 pentagons (the icosahedron's vertices).
    #[must_use]
    pub fn is_pentagon(&self, tile: GlobeTile) -> bool {
        match self.spot(tile) {
            Some(Spot::North | Spot::South) => true,
            Some(Spot::Diamond { i, j, .. }) => i == 0 && j == 0,
            None => false,
        }
    }

    /// `tile`'s neighbors going round it, counterclockwise seen from outside; `None` for a tile
    /// not of this grid.
    #[must_use]
    pub fn neighbors(&self, tile: GlobeTile) -> Option<GlobeNeighbors> {
        let f = self.frequency;
        let mut out = GlobeNeighbors { tiles: [GlobeTile(0); 6], len: 0 };
        let mut push = |t: GlobeTile| {
            out.tiles[usize::from(out.len)] = t;
            out.len += 1;
        };
        match self.spot(tile)? {
            Spot::North => (0..5).for_each(|d| push(self.id(Spot::Diamond { d, i: f - 1, j: 0 }))),
            Spot::South => (5..10).rev().for_each(|d| push(self.id(Spot::Diamond { d, i: 0, j: f - 1 }))),
            Spot::Diamond { d, i, j } => {
                // The steps go round clockwise seen from outside: take them backwards.
                for (k, (di, dj)) in STEPS.iter().enumerate().rev() {
                    if i == 0 && j == 0 && k == MISSING_AT_ORIGIN {
                        continue;
                    }
                    let spot = locate(f, d, i64::from(i) + di, i64::from(j) + dj)
                        .expect("only the origin's missing step leads nowhere");
                    push(self.id(spot));
                }
            }
        }
        Some(out)
    }

    /// The direction from the globe's center to `tile`'s center, a unit vector; `None` for a
    /// tile not of this grid.
    #[must_use]
    pub fn center(&self, tile: GlobeTile) -> Option<[f64; 3]> {
        let (d, u, v) = project::spot_uv(self.frequency, self.spot(tile)?);
        Some(self.projection.direction(d, u, v))
    }

    /// The tile a direction falls in (any length but zero); `None` for a zero or non-finite
    /// vector.
    #[must_use]
    pub fn tile_at(&self, direction: [f64; 3]) -> Option<GlobeTile> {
        let len = project::dot(direction, direction).sqrt();
        if !len.is_finite() || len == 0.0 {
            return None;
        }
        let (d, u, v) = self.projection.locate(project::normalize(direction));
        let n = f64::from(self.frequency);
        // The lattice point nearest: the diamond's steps are `(1, 0)`, `(0, 1)` and `(1, 1)`,
        // axial hex coordinates with `q = i`, `r = -j`.
        let nearest = crate::lattice::cube_round(u * n, -v * n);
        let (i, j) = (i64::from(nearest.x), -i64::from(nearest.y));
        let f = i64::from(self.frequency);
        // The face's point lies in the diamond's closure: its nearest lattice point too, or on
        // the diamond's far edges, which `locate` hands to their owners.
        let spot = locate(self.frequency, d, i.clamp(0, f), j.clamp(0, f)).expect("a point of the diamond's closure");
        Some(self.id(spot))
    }

    /// The fewest steps from `a` to `b` over the tile graph; `None` if either is not of this
    /// grid. A breadth-first search from `a`, stopping at `b`.
    #[must_use]
    pub fn distance(&self, a: GlobeTile, b: GlobeTile) -> Option<u32> {
        if !self.contains(a) || !self.contains(b) {
            return None;
        }
        let mut seen = vec![false; self.tile_count() as usize];
        let mut frontier = vec![a];
        seen[a.0 as usize] = true;
        let mut steps = 0;
        while !frontier.is_empty() {
            if frontier.contains(&b) {
                return Some(steps);
            }
            let mut next = Vec::new();
            for t in frontier {
                for &n in &self.neighbors(t)? {
                    if !std::mem::replace(&mut seen[n.0 as usize], true) {
                        next.push(n);
                    }
                }
            }
            frontier = next;
            steps += 1;
        }
        None
    }

    /// Every tile within `steps` of `from` over the tile graph, with its steps, nearest first
    /// then by id (`from` first, at 0); empty for a tile not of this grid. Any number of steps:
    /// the work is bounded by the grid's tiles.
    #[must_use]
    pub fn within(&self, from: GlobeTile, steps: u32) -> Vec<(GlobeTile, u32)> {
        if !self.contains(from) {
            return Vec::new();
        }
        let mut seen = vec![false; self.tile_count() as usize];
        seen[from.0 as usize] = true;
        let mut out = vec![(from, 0)];
        let mut ring = vec![from];
        for step in 1..=steps {
            let mut next = Vec::new();
            for t in ring {
                for &n in &self.neighbors(t).expect("a tile of the grid") {
                    if !std::mem::replace(&mut seen[n.0 as usize], true) {
                        next.push(n);
                    }
                }
            }
            if next.is_empty() {
                break;
            }
            next.sort_unstable();
            out.extend(next.iter().map(|&t| (t, step)));
            ring = next;
        }
        out
    }

    pub(super) fn spot(&self, tile: GlobeTile) -> Option<Spot> {
        let f = self.frequency;
        let per = f * f;
        match tile.0 {
            0 => Some(Spot::North),
            t if t == 10 * per + 1 => Some(Spot::South),
            t if t <= 10 * per => {
                let k = t - 1;
                Some(Spot::Diamond { d: (k / per) as u8, i: (k % per) / f, j: k % f })
            }
            _ => None,
        }
    }

    pub(super) fn id(&self, spot: Spot) -> GlobeTile {
        let f = self.frequency;
        GlobeTile(match spot {
            Spot::North => 0,
            Spot::South => 10 * f * f + 1,
            Spot::Diamond { d, i, j } => 1 + u32::from(d) * f * f + i * f + j,
        })
    }
}
