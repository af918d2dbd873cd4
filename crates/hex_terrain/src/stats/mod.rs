//! Map statistics: the numbers players judge a map by (how much land, how many continents and
//! how big, how far apart, where the mountains and rivers are), measured on a compiled bounded
//! map. A pure function of the terrain: the same on any thread count, whatever was streamed.
//!
//! The rules are on [`MapStats`].

use hexx::Hex;

use crate::ruleset::{FeatureId, Landform, TerrainId};
use crate::terrain::Terrain;
use crate::vocab::{Biome, TileKind};

pub use crate::heights::targets::{CONTINENT_MIN_SHARE, CONTINENT_MIN_TILES};

mod display;
mod rivers;
mod shadow;
mod shares;
mod survey;

use crate::heights::targets::{components, nearest_between};
pub use shadow::{RainShadow, SHADOW_REACH};
pub use survey::{SurveyFigure, SurveyTarget, SurveyVerdict, survey_targets};

/// Whether a landmass is a continent or an island (the rule is on [`MapStats`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum LandmassKind {
    /// At least [`CONTINENT_MIN_SHARE`] of the land and [`CONTINENT_MIN_TILES`] tiles.
    Continent,
    /// Any smaller landmass.
    Island,
}

/// Under this mean resultant length a landmass' columns' bearings cancel (it goes all round a
/// wrapping map evenly): its center column is then 0.
const ROUND_THE_MAP: f64 = 1e-6;

/// How near two continents' centers' columns or rows lie for them to count as in line
/// ([`MapStats::continents_in_line`]), in tiles.
pub const IN_LINE: f64 = 1.5;

/// Land tiles connected through their neighbors.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct Landmass {
    /// Its first tile, row by row (the smallest offset `(row, column)`): a name that does not
    /// depend on the order tiles are visited in.
    pub first: Hex,
    /// Its tiles.
    pub tiles: u32,
    /// Its mountain tiles.
    pub mountains: u32,
    /// Its coast, in tile edges to the sea.
    pub coast_edges: u32,
    /// The rows it spans, from its northernmost to its southernmost (both counted).
    pub rows: u32,
    /// The columns it spans: from its westernmost to its easternmost on a map that does not
    /// wrap; on a wrapping map, the fewest columns of an arc round the map that holds it.
    pub columns: u32,
    /// Its tiles on a river ([`RiverStats::tiles`]' rule).
    pub river_tiles: u32,
    /// Its center: the mean column and row of its tiles, counted from the map's first (on a
    /// wrapping map the column is the mean round the map, the circular mean, in `[0, columns)`;
    /// 0 for a landmass that goes all round the map evenly).
    pub center: [f64; 2],
    /// Continent or island.
    pub kind: LandmassKind,
}

/// The rivers of a map, by either river model ([`RiverModel`](crate::RiverModel)).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct RiverStats {
    /// River systems: one a mouth (rivers through tile centers: a river tile whose water leaves
    /// the rivers; rivers on edges: a river's last edge, whose downstream corner no river leaves).
    pub systems: u32,
    /// Tiles on a river: carrying one (through tile centers) or with a river on an edge (on
    /// edges).
    pub tiles: u32,
    /// River edges (rivers on edges; 0 for rivers through tile centers).
    pub edges: u32,
    /// The longest river from a source to its mouth: in tiles through tile centers, in edges on
    /// edges.
    pub longest: u32,
    /// Sources: river tiles no river flows into (through tile centers), river corners no river
    /// flows into (on edges).
    pub sources: u32,
    /// The median length of a river from its source to its mouth (a source's length; tiles or
    /// edges as `longest`); 0 without a river.
    pub median: u32,
    /// Sources within 2 steps over the map of relief (a mountain tile or a tile of the `Hills`
    /// biome; a corner's source by the nearest of its three tiles), where Civilization's rivers
    /// rise.
    pub sources_near_relief: u32,
    /// River systems whose mouth is the map's edge rather than the sea or a lake (through tile
    /// centers: a river tile whose water leaves the map; on edges: a last edge ending at a
    /// corner past the map that touches no water).
    pub mouths_at_edge: u32,
}

/// The statistics of a bounded map: [`MapStats::measure`].
///
/// The rules, written once:
/// - **Water** is sea tiles and lake tiles; **land** is every other tile (mountains included).
/// - A **landmass** is a set of land tiles connected through their neighbors (across the seam of
///   a wrapping map). It is a **continent** when it holds at least [`CONTINENT_MIN_SHARE`] of the
///   map's land and at least [`CONTINENT_MIN_TILES`] tiles, an **island** otherwise.
/// - The **coast** is counted in tile edges between a land tile and a sea tile (a lake shore is
///   not coast).
/// - The **narrowest strait** is the fewest tiles between two continents: the smallest hex
///   distance (the short way round on a wrapping map) between tiles of two different continents,
///   less one.
/// - A **mountain range** is a set of three or more mountain tiles connected through their
///   neighbors; a lone mountain or a pair is not one. Its shape shows in how many mountain
///   neighbors a mountain has on average (2 or fewer in a chain, up to 6 inside a massif) and in
///   the longest range's length end to end.
/// - A **river system** ends at one mouth: a river tile whose water leaves the rivers (into the
///   sea, a lake or off the map). A river's length counts its tiles from a source to its mouth.
///   Rivers on tile edges count the same way in edges: a system ends at a last edge, a length is
///   the edges from a source to the mouth, and a tile is on a river when an edge of it is.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct MapStats {
    /// Tiles of the map.
    pub tiles: u32,
    /// Sea tiles.
    pub sea_tiles: u32,
    /// Lake tiles.
    pub lake_tiles: u32,
    /// Land tiles (every tile neither sea nor lake; mountains included).
    pub land_tiles: u32,
    /// Mountain tiles (land).
    pub mountain_tiles: u32,
    /// Mountain tiles in ranges (connected groups of three or more).
    pub range_tiles: u32,
    /// Neighbor pairs of mountain tiles, each pair counted from both sides: over
    /// `mountain_tiles`, how many mountain neighbors a mountain has on average
    /// ([`MapStats::mountain_neighbors`]).
    pub mountain_adjacencies: u32,
    /// The longest range end to end, in tiles: the most tiles a straight hex line crosses
    /// between two tiles of one range (the largest hex distance between them, plus one); 0
    /// without a range.
    pub longest_range: u32,
    /// The longest straight run of mountains: the most mountain tiles in a row along one of the
    /// three hex axes (a wall along the grid shows here); 0 without mountains.
    pub straight_ridge: u32,
    /// Mountains in blobs: mountain tiles with 5 or 6 mountain neighbors.
    pub blob_mountains: u32,
    /// Land tiles in the polar rows: the first and the last tenth of the map's rows (at least a
    /// row each), which Civilization keeps ice or sea.
    pub polar_land_tiles: u32,
    /// The landmasses, largest first (ties: the first tile's row, then column).
    pub landmasses: Vec<Landmass>,
    /// Coast length, in tile edges between land and sea.
    pub coast_edges: u32,
    /// The fewest tiles between two continents; `None` with fewer than two.
    pub narrowest_strait: Option<u32>,
    /// Tiles of each biome present, in [`Biome::ALL`]'s order.
    pub biomes: Vec<(Biome, u32)>,
    /// Under the map's own terrain ruleset ([`MapConfig::ruleset`](crate::MapConfig::ruleset)):
    /// tiles of each of its terrains present, in the ruleset's order, and how many of them lie
    /// on hills (empty on a map without its own ruleset: its terrains are its biomes).
    pub terrains: Vec<(TerrainId, u32, u32)>,
    /// Under the map's own terrain ruleset: tiles with each of its features, in its order
    /// (absent ones too).
    pub features: Vec<(FeatureId, u32)>,
    /// Rivers (all zero on a map without rivers).
    pub rivers: RiverStats,
    /// Lakes.
    pub lakes: u32,
    /// With winds: deserts and land in the lee of mountains (`None` without winds).
    pub rain_shadow: Option<RainShadow>,
    /// With a game setup: the tiles of the landmass each start stands on, in player order.
    pub start_landmass_tiles: Vec<u32>,
    /// The columns round a wrapping map (`None` on a map that does not wrap): how far apart
    /// two columns are ([`MapStats::continents_in_line`]).
    pub wrap_columns: Option<u32>,
}

impl MapStats {
    /// Measures a bounded map; `None` for an unbounded world (it has no whole to measure).
    #[must_use]
    pub fn measure(terrain: &Terrain) -> Option<Self> {
        let bounds = terrain.bounds()?;
        let width = (bounds.max[0] - bounds.min[0]) as usize;
        let index = |tile: Hex| {
            let [col, row] = terrain.offset_of(tile);
            (row - bounds.min[1]) as usize * width + (col - bounds.min[0]) as usize
        };
        let tiles: Vec<Hex> = terrain.tiles().collect();
        let infos: Vec<_> = tiles.iter().map(|&t| terrain.tile_info(t).expect("a tile of the map")).collect();
        // Each tile's biome: its terrain under the default ruleset; under the map's own, the
        // climate's biome beneath it (what the map type's measures are made of).
        let tile_biomes: Vec<Biome> = if terrain.has_own_ruleset() {
            tiles.iter().map(|&t| terrain.pipeline().tile_biome(t)).collect()
        } else {
            infos.iter().map(|i| Biome::ALL[usize::from(i.terrain.terrain.0)]).collect()
        };
        let neighbors: Vec<[Option<u32>; 6]> = tiles
            .iter()
            .map(|&t| terrain.neighbors(t).expect("a tile of the map").map(|n| n.map(|n| index(n) as u32)))
            .collect();
        let around = |i: usize| neighbors[i].iter().flatten().map(|&n| n as usize);
        let water = |i: usize| infos[i].kind == TileKind::Sea || infos[i].lake.is_some();
        let sea = |i: usize| infos[i].kind == TileKind::Sea;
        let mountain = |i: usize| !water(i) && infos[i].kind == TileKind::Mountain;

        let land_tiles = (0..tiles.len()).filter(|&i| !water(i)).count() as u32;
        let sea_tiles = (0..tiles.len()).filter(|&i| sea(i)).count() as u32;
        let lake_tiles = (0..tiles.len()).filter(|&i| !sea(i) && infos[i].lake.is_some()).count() as u32;
        let mountain_tiles = (0..tiles.len()).filter(|&i| mountain(i)).count() as u32;
        let coast = |i: usize| around(i).filter(|&n| sea(n)).count() as u32;

        // Landmasses and mountain groups: flood fills in row order, so the first tile visited is
        // a component's first tile.
        let land = components(&neighbors, |i| !water(i));
        let ranges = components(&neighbors, mountain);
        let range_tiles = ranges.sizes.iter().filter(|&&s| s >= 3).sum::<u32>();
        let mountain_adjacencies =
            (0..tiles.len()).filter(|&i| mountain(i)).map(|i| around(i).filter(|&n| mountain(n)).count() as u32).sum();
        // Each range's length: the largest distance between two of its tiles.
        let mut members: Vec<Vec<usize>> = vec![Vec::new(); ranges.sizes.len()];
        for i in (0..tiles.len()).filter(|&i| mountain(i)) {
            members[ranges.of[i] as usize].push(i);
        }
        let longest_range = members
            .iter()
            .filter(|m| m.len() >= 3)
            .map(|m| {
                let mut far = 0;
                for (k, &a) in m.iter().enumerate() {
                    for &b in &m[k + 1..] {
                        far = far.max(terrain.distance(tiles[a], tiles[b]).expect("tiles of the map"));
                    }
                }
                far + 1
            })
            .max()
            .unwrap_or(0);
        let mountain_neighbors = |i: usize| around(i).filter(|&n| mountain(n)).count();
        let blob_mountains = (0..tiles.len()).filter(|&i| mountain(i) && mountain_neighbors(i) >= 5).count() as u32;
        let straight_ridge = straight_ridge(terrain, &tiles, &index, &mountain);
        let (columns, rows) = (width, (bounds.max[1] - bounds.min[1]) as usize);
        let band = rows.div_ceil(10) as i32;
        let polar = |i: usize| {
            let row = terrain.offset_of(tiles[i])[1];
            row - bounds.min[1] < band || bounds.max[1] - 1 - row < band
        };
        let polar_land_tiles = (0..tiles.len()).filter(|&i| !water(i) && polar(i)).count() as u32;
        let mut landmasses: Vec<Landmass> = land
            .first
            .iter()
            .zip(&land.sizes)
            .map(|(&first, &size)| Landmass {
                first: tiles[first],
                tiles: size,
                mountains: 0,
                coast_edges: 0,
                rows: 0,
                columns: 0,
                river_tiles: 0,
                center: [0.0; 2],
                kind: LandmassKind::Island,
            })
            .collect();
        let (river_stats, on_river) = rivers::rivers(terrain, &tiles, &neighbors, &infos, &tile_biomes);
        // Each landmass' rows and columns, as flags over the map's.
        let mut spans = vec![(vec![false; rows], vec![false; columns]); landmasses.len()];
        // Each landmass' sums for its center: rows, and columns (or their bearings round a
        // wrapping map, as a cosine and a sine).
        let mut sums = vec![[0.0_f64; 3]; landmasses.len()];
        let bearing = |col: i32| f64::from(col) / columns as f64 * std::f64::consts::TAU;
        for i in (0..tiles.len()).filter(|&i| !water(i)) {
            let mass = &mut landmasses[land.of[i] as usize];
            mass.mountains += u32::from(mountain(i));
            mass.river_tiles += u32::from(on_river[i]);
            mass.coast_edges += coast(i);
            let [col, row] = terrain.offset_of(tiles[i]);
            let span = &mut spans[land.of[i] as usize];
            span.0[(row - bounds.min[1]) as usize] = true;
            span.1[(col - bounds.min[0]) as usize] = true;
            let (col, row) = (col - bounds.min[0], row - bounds.min[1]);
            let sum = &mut sums[land.of[i] as usize];
            sum[0] += f64::from(row);
            if terrain.wrap().is_some() {
                sum[1] += libm::cos(bearing(col));
                sum[2] += libm::sin(bearing(col));
            } else {
                sum[1] += f64::from(col);
            }
        }
        for ((mass, (in_rows, in_columns)), sum) in landmasses.iter_mut().zip(&spans).zip(&sums) {
            mass.rows = extent(in_rows, false);
            mass.columns = extent(in_columns, terrain.wrap().is_some());
            let n = f64::from(mass.tiles.max(1));
            let column = if terrain.wrap().is_some() {
                // All round the map, the bearings cancel: column 0.
                if libm::hypot(sum[1], sum[2]) < ROUND_THE_MAP * n {
                    0.0
                } else {
                    let w = columns as f64;
                    // A bearing a hair under 0 turns to `w` itself: that is column 0.
                    let column = (libm::atan2(sum[2], sum[1]) / std::f64::consts::TAU * w).rem_euclid(w);
                    if column >= w { 0.0 } else { column }
                }
            } else {
                sum[1] / n
            };
            mass.center = [column, sum[0] / n];
        }
        for mass in &mut landmasses {
            let share = f64::from(mass.tiles) / f64::from(land_tiles.max(1));
            if share >= CONTINENT_MIN_SHARE && mass.tiles >= CONTINENT_MIN_TILES {
                mass.kind = LandmassKind::Continent;
            }
        }

        // The narrowest strait: a search from every continent's tiles at once.
        let continent: Vec<u32> = land
            .of
            .iter()
            .map(|&m| match landmasses.get(m as usize) {
                Some(mass) if mass.kind == LandmassKind::Continent => m,
                _ => u32::MAX,
            })
            .collect();
        let narrowest = nearest_between(&neighbors, &continent);

        let mut order: Vec<usize> = (0..landmasses.len()).collect();
        order.sort_by_key(|&m| {
            let [col, row] = terrain.offset_of(landmasses[m].first);
            (std::cmp::Reverse(landmasses[m].tiles), row, col)
        });
        let start_landmass_tiles = terrain.setup().map_or_else(Vec::new, |setup| {
            setup.starts().iter().map(|&s| landmasses[land.of[index(s)] as usize].tiles).collect()
        });
        let landmasses: Vec<Landmass> = order.iter().map(|&m| landmasses[m].clone()).collect();

        let biomes = Biome::ALL
            .into_iter()
            .map(|b| (b, tile_biomes.iter().filter(|&&t| t == b).count() as u32))
            .filter(|&(_, n)| n > 0)
            .collect();
        let (terrains, features) = if terrain.has_own_ruleset() {
            let ruleset = terrain.ruleset();
            let mut counts = vec![(0_u32, 0_u32); ruleset.terrains.len()];
            let mut featured = vec![0_u32; ruleset.features.len()];
            for t in infos.iter().map(|i| i.terrain) {
                let c = &mut counts[usize::from(t.terrain.0)];
                c.0 += 1;
                c.1 += u32::from(t.landform == Landform::Hills);
                if let Some(f) = t.feature {
                    featured[usize::from(f.0)] += 1;
                }
            }
            let terrains = counts
                .into_iter()
                .enumerate()
                .filter(|&(_, (n, _))| n > 0)
                .map(|(i, (n, hills))| (TerrainId(i as u8), n, hills))
                .collect();
            (terrains, featured.into_iter().enumerate().map(|(i, n)| (FeatureId(i as u8), n)).collect())
        } else {
            (Vec::new(), Vec::new())
        };

        Some(Self {
            tiles: tiles.len() as u32,
            sea_tiles,
            lake_tiles,
            land_tiles,
            mountain_tiles,
            range_tiles,
            mountain_adjacencies,
            longest_range,
            straight_ridge,
            blob_mountains,
            polar_land_tiles,
            coast_edges: (0..tiles.len()).filter(|&i| !water(i)).map(coast).sum(),
            landmasses,
            narrowest_strait: narrowest,
            biomes,
            terrains,
            features,
            rivers: river_stats,
            rain_shadow: shadow::rain_shadow(terrain, &tiles, &neighbors, &infos, &tile_biomes),
            lakes: terrain.hydrology().map_or(0, |h| h.lake_count() as u32),
            start_landmass_tiles,
            wrap_columns: terrain.wrap().is_some().then_some(columns as u32),
        })
    }
}

/// The most flags in a row that are set, the row read round when it `wraps`: 0 with none set.
fn extent(set: &[bool], wraps: bool) -> u32 {
    let (first, last) = match (set.iter().position(|&s| s), set.iter().rposition(|&s| s)) {
        (Some(first), Some(last)) => (first, last),
        _ => return 0,
    };
    if !wraps {
        return (last - first + 1) as u32;
    }
    // Round the map: all the columns less the longest run of empty ones (the run past the east
    // edge goes on at the west edge).
    let mut longest_gap = first + (set.len() - 1 - last);
    let mut gap = 0;
    for &s in &set[first..=last] {
        gap = if s { 0 } else { gap + 1 };
        longest_gap = longest_gap.max(gap);
    }
    (set.len() - longest_gap) as u32
}

/// The most mountain tiles in a row along one of the three hex axes (on a wrapping map a row of
/// them may go all round: then it is as long as the round).
fn straight_ridge(
    terrain: &Terrain,
    tiles: &[Hex],
    index: &dyn Fn(Hex) -> usize,
    mountain: &dyn Fn(usize) -> bool,
) -> u32 {
    let step = |tile: Hex, axis: Hex| terrain.wrap_tile(tile + axis).filter(|&t| terrain.contains(t)).map(index);
    let mut longest = 0;
    for axis in [Hex::new(1, 0), Hex::new(0, 1), Hex::new(1, -1)] {
        let mut seen = vec![false; tiles.len()];
        // Runs from their first tile, then what is left: rounds, which have no first tile.
        let firsts = (0..tiles.len()).filter(|&i| mountain(i) && !step(tiles[i], -axis).is_some_and(mountain));
        let rest: Vec<usize> = (0..tiles.len()).filter(|&i| mountain(i)).collect();
        for start in firsts.chain(rest) {
            if seen[start] {
                continue;
            }
            let mut run = 0;
            let mut at = Some(start);
            while let Some(i) = at.filter(|&i| mountain(i) && !seen[i]) {
                seen[i] = true;
                run += 1;
                at = step(tiles[i], axis);
            }
            longest = longest.max(run);
        }
    }
    longest
}
