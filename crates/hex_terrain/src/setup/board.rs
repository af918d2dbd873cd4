//! Where the setup's tiles lie: a flat map's rectangle of offset coordinates or a whole globe.
//! The survey numbers the tiles `0..n`; the board answers what depends on where they are (the
//! steps between two tiles, the tiles within a radius, a tile's draw key, its coordinates in
//! the report, the grid regions are cut on), so every later step of the setup is the same for
//! both.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, PoisonError};

use hexx::Hex;

use crate::chunk::TileRect;
use crate::geometry::Geometry;
use crate::globe::grid::{GlobeGrid, GlobeTile};

/// A pentagon's missing sixth neighbor in `range`'s scratch (never read past its five).
const NO_TILE: u32 = u32::MAX;

/// The board of a setup (see the module docs).
pub(crate) enum Board<'a> {
    /// A flat map's area.
    Flat(Flat<'a>),
    /// A whole globe.
    Globe(Sphere<'a>),
}

/// A flat map's area: tile `i` is the `i`-th of the rectangle, row by row.
pub(crate) struct Flat<'a> {
    pub geometry: &'a Geometry,
    /// The area, offset coordinates.
    pub rect: TileRect,
    /// Columns of the area.
    pub cols: usize,
    /// Whether the area is a whole wrapping map (its columns continue across the seam).
    pub wraps: bool,
    /// Each tile (map-local axial).
    pub tiles: Vec<Hex>,
}

/// A globe: tile `i` is `GlobeTile(i)`.
pub(crate) struct Sphere<'a> {
    pub grid: &'a GlobeGrid,
    /// Each tile's center direction.
    pub centers: Vec<[f64; 3]>,
    /// The steps from a tile to every tile, for the tiles asked so far (a breadth-first search
    /// each; the setup asks from its starts and, in its exact search, its candidates).
    steps: Mutex<HashMap<u32, Arc<[u16]>>>,
}

impl<'a> Sphere<'a> {
    pub fn new(grid: &'a GlobeGrid) -> Self {
        let centers = grid.tiles().map(|t| grid.center(t).expect("a tile of the grid")).collect();
        Self { grid, centers, steps: Mutex::new(HashMap::new()) }
    }

    /// The steps from tile `from` to every tile.
    fn steps_from(&self, from: u32) -> Arc<[u16]> {
        if let Some(row) = self.steps.lock().unwrap_or_else(PoisonError::into_inner).get(&from) {
            return row.clone();
        }
        let mut steps = vec![u16::MAX; self.centers.len()];
        steps[from as usize] = 0;
        let mut ring = vec![GlobeTile(from)];
        let mut next = Vec::new();
        let mut k = 0u16;
        while !ring.is_empty() {
            k += 1;
            for &t in &ring {
                for &n in &self.grid.neighbors(t).expect("a tile of the grid") {
                    if steps[n.0 as usize] == u16::MAX {
                        steps[n.0 as usize] = k;
                        next.push(n);
                    }
                }
            }
            std::mem::swap(&mut ring, &mut next);
            next.clear();
        }
        let row: Arc<[u16]> = steps.into();
        self.steps.lock().unwrap_or_else(PoisonError::into_inner).insert(from, row.clone());
        row
    }
}

impl Board<'_> {
    /// Steps between tiles `a` and `b`; `None` when no path of tiles joins them.
    pub fn distance(&self, a: usize, b: usize) -> Option<u32> {
        match self {
            Self::Flat(f) => f.geometry.distance(f.tiles[a], f.tiles[b]),
            Self::Globe(s) => Some(u32::from(s.steps_from(a as u32)[b])),
        }
    }

    /// The tiles within `radius` of tile `i` (itself included), each once, in a fixed order.
    pub fn range(&self, i: usize, radius: u32, out: &mut Vec<u32>) {
        out.clear();
        match self {
            Self::Flat(f) => {
                out.extend(f.tiles[i].range(radius).filter_map(|t| f.index(t)).map(|j| j as u32));
                // On a wrapping map narrower than the range, two copies of a tile fall in it.
                if f.wraps && f.cols < 2 * radius as usize + 1 {
                    out.sort_unstable();
                    out.dedup();
                }
            }
            Self::Globe(s) => {
                // Ring by ring: a neighbor of ring `k` lies in ring `k - 1`, `k` or `k + 1`.
                out.push(i as u32);
                let (mut last, mut ring) = (Vec::new(), vec![i as u32]);
                for _ in 0..radius {
                    let mut next: Vec<u32> = ring
                        .iter()
                        .flat_map(|&t| {
                            let around = s.grid.neighbors(GlobeTile(t)).expect("a tile of the grid");
                            let mut ids = [NO_TILE; 6];
                            for (id, n) in ids.iter_mut().zip(&around) {
                                *id = n.0;
                            }
                            ids.into_iter().take(around.len())
                        })
                        .filter(|n| last.binary_search(n).is_err() && ring.binary_search(n).is_err())
                        .collect();
                    next.sort_unstable();
                    next.dedup();
                    if next.is_empty() {
                        break;
                    }
                    out.extend_from_slice(&next);
                    last = std::mem::replace(&mut ring, next);
                }
            }
        }
    }

    /// Tile `i`'s key for the setup's draws.
    pub fn key(&self, i: usize) -> [i64; 2] {
        match self {
            Self::Flat(f) => [i64::from(f.tiles[i].x), i64::from(f.tiles[i].y)],
            Self::Globe(_) => [i as i64, 0],
        }
    }

    /// Tile `i`'s coordinates in the report: a flat map's offset coordinate `[col, row]`, a
    /// globe tile's longitude and latitude rounded to whole degrees.
    pub fn coords(&self, i: usize) -> [i32; 2] {
        match self {
            Self::Flat(f) => [f.rect.min[0] + (i % f.cols) as i32, f.rect.min[1] + (i / f.cols) as i32],
            Self::Globe(s) => {
                let [lon, lat] = lon_lat(s.centers[i]);
                [lon.round() as i32, lat.round() as i32]
            }
        }
    }
}

impl Flat<'_> {
    /// Index of a tile of the area (any copy of it on a wrapping map).
    pub fn index(&self, tile: Hex) -> Option<usize> {
        area_index(self.rect, self.geometry, tile)
    }
}

/// Row-major index in `rect` of a tile (any copy of it on a wrapping map); `None` outside it or
/// past the world. The survey and the placed setup both address tiles by it.
pub(crate) fn area_index(rect: TileRect, geometry: &Geometry, tile: Hex) -> Option<usize> {
    if !geometry.in_world(tile) {
        return None;
    }
    let [c, r] = geometry.offset_of(geometry.wrap_tile(tile));
    rect.index([c, r])
}

/// Longitude (east positive, `(-180, 180]`) and latitude (north positive) in degrees of a unit
/// direction, as [`GlobeTerrain::tile_info`](crate::GlobeTerrain::tile_info) gives them.
pub(crate) fn lon_lat(dir: [f64; 3]) -> [f64; 2] {
    let lon = (-dir[2]).atan2(dir[0]).to_degrees();
    [if lon <= -180.0 { 180.0 } else { lon }, dir[1].clamp(-1.0, 1.0).asin().to_degrees()]
}
