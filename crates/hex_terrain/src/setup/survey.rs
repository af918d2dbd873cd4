//! The survey: what the setup needs to know of every tile of its area, read once from the
//! terrain's stages or a globe's tiles (type, biome, river, coast, yields, value, movement cost,
//! neighbors).

use hexx::Hex;
use rayon::prelude::*;

use super::board::{Board, Flat, Sphere};
use crate::chunk::TileRect;
use crate::climate::{ClimateModel, TileSample};
use crate::config::{MovementConfig, SetupConfig, StartOn, Yields};
use crate::geometry::Geometry;
use crate::globe::grid::GlobeGrid;
use crate::heights::HeightField;
use crate::kind::Thresholds;
use crate::ruleset::{TerrainRuleset, TileTerrain, TileTerrains, Traits};
use crate::table::TileTable;
use crate::vocab::{Biome, TileKind};

/// No neighbor (past the area's edge).
pub(crate) const NONE: u32 = u32::MAX;

/// The terrain stages the setup reads: it takes them as arguments, like every stage.
#[derive(Clone, Copy)]
pub struct Stages<'a> {
    /// Where tiles are.
    pub geometry: &'a Geometry,
    /// Raw heights.
    pub heights: &'a HeightField,
    /// Tile types.
    pub thresholds: &'a Thresholds,
    /// Biomes.
    pub climate: &'a ClimateModel,
    /// The per-map table (biomes, rivers and lakes of a bounded map), if the map has one.
    pub table: Option<&'a TileTable>,
    /// The movement model (the map config's), for reach and path costs.
    pub movement: &'a MovementConfig,
    /// On a map with its own terrain ruleset, each tile's terrain and traits: its yields and
    /// its cost of entering come from them (`None`: from the biome).
    pub(crate) terrains: Option<&'a dyn TileTerrains>,
    /// The map's terrain ruleset (its own, or its biome table's), whose ids
    /// [`Place::Terrain`](crate::Place::Terrain) and [`Place::Feature`](crate::Place::Feature)
    /// name.
    pub ruleset: &'a TerrainRuleset,
}

impl Stages<'_> {
    /// A tile's biome by the one rule ([`crate::Terrain::tile_info`]): set by hand, the
    /// table's, the climate's, the kind's.
    fn biome(&self, tile: Hex, kind: TileKind) -> Biome {
        let set = self.heights.edits().and_then(|e| e.biome(self.geometry, tile));
        match set.or_else(|| self.table.and_then(|table| table.biome(self.geometry, tile))) {
            Some(biome) => biome,
            None if self.climate.is_enabled() => {
                let sample = TileSample::of(self.geometry, self.heights, self.thresholds, tile);
                self.climate.biome_of(self.geometry, self.heights, tile, &sample, false)
            }
            None => Biome::of_kind(kind),
        }
    }
}

/// What the setup reads of a globe: its tiles' kinds, biomes, terrains and costs of entering,
/// by id (the globe has them compiled).
pub(crate) struct GlobeStages<'a> {
    /// The globe's grid.
    pub grid: &'a GlobeGrid,
    pub kinds: &'a [TileKind],
    pub biomes: &'a [Biome],
    /// Each tile's terrain and feature under the globe's ruleset.
    pub terrains: Vec<TileTerrain>,
    /// Each tile's cost of entering by the globe's movement rule (`None`: impassable).
    pub costs: Vec<Option<u32>>,
    /// The globe's terrain ruleset.
    pub ruleset: &'a TerrainRuleset,
    /// The movement model (the map config's).
    pub movement: &'a MovementConfig,
}

/// Every tile of the setup's area, by the board's order (a flat area row by row, a globe by id).
pub(crate) struct Survey<'a> {
    /// Where the tiles lie.
    pub board: Board<'a>,
    pub kinds: Vec<TileKind>,
    pub biomes: Vec<Biome>,
    /// A river through it or on one of its edges.
    pub river: Vec<bool>,
    /// Which of its edges carry a river (bit `d`: toward `neighbors[d]`), each crossed for
    /// `river_cost` more.
    pub crossing: Vec<u8>,
    /// The movement model's cost of crossing a river.
    pub river_cost: u32,
    /// Land next to the sea.
    pub coast: Vec<bool>,
    /// Yields of the terrain alone.
    pub yields: Vec<Yields>,
    /// Movement cost of entering it (a river through it included), 0 impassable.
    pub cost: Vec<u32>,
    /// Whether a start may stand on it.
    pub eligible: Vec<bool>,
    /// The neighbors' indices ([`NONE`] past the edge, and a pentagon's sixth).
    pub neighbors: Vec<[u32; 6]>,
    /// Each tile's terrain (an index into `terrain_ids`).
    pub terrain: Vec<u8>,
    /// Each tile's feature (an index into `feature_ids`, [`NO_FEATURE`] for none).
    pub feature: Vec<u8>,
    /// The ruleset's terrain ids.
    pub terrain_ids: Vec<String>,
    /// The ruleset's feature ids.
    pub feature_ids: Vec<String>,
}

/// [`Survey::feature`] of a tile without a feature.
pub(crate) const NO_FEATURE: u8 = u8::MAX;

impl<'a> Survey<'a> {
    /// Surveys `rect` (in the map) with the setup's tables.
    pub fn new(stages: Stages<'a>, config: &SetupConfig, rect: TileRect) -> Self {
        let geometry = stages.geometry;
        let cols = (rect.max[0] - rect.min[0]) as usize;
        let wraps = geometry.wrap().is_some() && geometry.bounds() == Some(rect);
        let tiles: Vec<Hex> = rect.iter().map(|oc| geometry.tile_from_offset(oc)).collect();
        // One tile type a tile; the heavy part (an fBm sample each), on all cores in tile order.
        let kinds: Vec<TileKind> = tiles
            .par_iter()
            .map(|&t| stages.thresholds.map_tile_kind(geometry, stages.heights, t).unwrap_or(TileKind::Sea))
            .collect();
        let biomes: Vec<Biome> = tiles.par_iter().zip(&kinds).map(|(&t, &kind)| stages.biome(t, kind)).collect();
        // A river through the tile, or on one of its edges.
        let center_river: Vec<bool> =
            tiles.iter().map(|&t| stages.table.is_some_and(|table| table.river_flow(geometry, t) > 0.0)).collect();
        let crossing: Vec<u8> =
            tiles.iter().map(|&t| stages.table.map_or(0, |table| table.river_edge_mask(geometry, t))).collect();
        let river: Vec<bool> = center_river.iter().zip(&crossing).map(|(&c, &e)| c || e != 0).collect();
        let flat = Flat { geometry, rect, cols, wraps, tiles };
        let neighbors: Vec<[u32; 6]> =
            flat.tiles.iter().map(|&t| t.all_neighbors().map(|n| flat.index(n).map_or(NONE, |j| j as u32))).collect();
        // A land tile next to the sea, wherever the sea lies: a neighbor on the map outside
        // the area counts too (read from the stages: only the area's edge tiles have one).
        let coast = (0..flat.tiles.len())
            .map(|i| {
                kinds[i] != TileKind::Sea
                    && neighbors[i].iter().zip(flat.tiles[i].all_neighbors()).any(|(&j, n)| {
                        if j != NONE {
                            return sea(kinds[j as usize], biomes[j as usize]);
                        }
                        stages
                            .thresholds
                            .map_tile_kind(geometry, stages.heights, n)
                            .is_some_and(|kind| sea(kind, stages.biome(n, kind)))
                    })
            })
            .collect();
        let ruled: Option<Vec<TileTerrain>> =
            stages.terrains.map(|terrains| flat.tiles.par_iter().map(|&t| terrains.tile_terrain(t)).collect());
        // Without its own ruleset a map's terrains are its biomes (the biome table's ruleset
        // lists them in their order).
        let (terrain, feature) = match &ruled {
            Some(ruled) => ruled.iter().map(|t| (t.terrain.0, t.feature.map_or(NO_FEATURE, |f| f.0))).unzip(),
            None => biomes.iter().map(|&b| (b as u8, NO_FEATURE)).unzip(),
        };
        let traits: Option<Vec<Traits>> = ruled.map(|ruled| ruled.into_iter().map(|t| t.traits).collect());
        let cost = (0..flat.tiles.len())
            .map(|i| {
                let cost = match &traits {
                    Some(traits) => {
                        let sea = kinds[i] == TileKind::Sea && biomes[i] != Biome::Lake;
                        stages.movement.enter_with(traits[i].movement, sea, center_river[i])
                    }
                    None => stages.movement.enter(biomes[i], center_river[i]),
                };
                cost.unwrap_or(0)
            })
            .collect();
        let survey = Self {
            board: Board::Flat(flat),
            kinds,
            biomes,
            river,
            crossing,
            river_cost: stages.movement.river,
            coast,
            yields: Vec::new(),
            cost,
            eligible: Vec::new(),
            neighbors,
            terrain,
            feature,
            terrain_ids: Vec::new(),
            feature_ids: Vec::new(),
        };
        survey.finish(config, stages.ruleset, traits.as_deref())
    }

    /// Surveys a whole globe with the setup's tables.
    pub fn globe(stages: GlobeStages<'a>, config: &SetupConfig) -> Self {
        let n = stages.kinds.len();
        let neighbors: Vec<[u32; 6]> = stages
            .grid
            .tiles()
            .map(|t| {
                let mut out = [NONE; 6];
                for (slot, n) in out.iter_mut().zip(&stages.grid.neighbors(t).expect("a tile of the grid")) {
                    *slot = n.0;
                }
                out
            })
            .collect();
        let (kinds, biomes) = (stages.kinds, stages.biomes);
        let coast = (0..n)
            .map(|i| {
                kinds[i] != TileKind::Sea
                    && neighbors[i].iter().any(|&j| j != NONE && sea(kinds[j as usize], biomes[j as usize]))
            })
            .collect();
        let survey = Self {
            board: Board::Globe(Sphere::new(stages.grid)),
            kinds: kinds.to_vec(),
            biomes: biomes.to_vec(),
            // A globe has no rivers yet.
            river: vec![false; n],
            crossing: vec![0; n],
            river_cost: stages.movement.river,
            coast,
            yields: Vec::new(),
            cost: stages.costs.iter().map(|c| c.unwrap_or(0)).collect(),
            eligible: Vec::new(),
            neighbors,
            terrain: stages.terrains.iter().map(|t| t.terrain.0).collect(),
            feature: stages.terrains.iter().map(|t| t.feature.map_or(NO_FEATURE, |f| f.0)).collect(),
            terrain_ids: Vec::new(),
            feature_ids: Vec::new(),
        };
        // A globe's terrains are its biomes (the biome table's ruleset): yields by the table.
        survey.finish(config, stages.ruleset, None)
    }

    /// The ruleset's ids, each tile's yields (its traits', or the setup's table by biome, with
    /// the kind's, river's and coast's bonus) and whether a start may stand on it.
    fn finish(mut self, config: &SetupConfig, ruleset: &TerrainRuleset, traits: Option<&[Traits]>) -> Self {
        self.terrain_ids = ruleset.terrains.iter().map(|t| t.id.clone()).collect();
        self.feature_ids = ruleset.features.iter().map(|f| f.id.clone()).collect();
        let table = &config.yields;
        self.yields = (0..self.len())
            .map(|i| {
                let mut y = traits.map_or_else(|| table.biome(self.biomes[i]), |traits| traits[i].yields);
                if let Some(k) = table.kinds.get(&self.kinds[i]) {
                    y += *k;
                }
                if self.river[i] {
                    y += table.river;
                }
                if self.coast[i] {
                    y += table.coast;
                }
                y
            })
            .collect();
        self.eligible = (0..self.len())
            .map(|i| {
                let land = self.kinds[i] == TileKind::Land && !self.biomes[i].is_water() && self.cost[i] > 0;
                land && match config.start_on {
                    StartOn::Land => true,
                    StartOn::Coast => self.coast[i],
                    StartOn::River => self.river[i],
                    StartOn::CoastOrRiver => self.coast[i] || self.river[i],
                }
            })
            .collect();
        self
    }

    /// Whether tile `i`'s terrain has this id.
    pub fn terrain_is(&self, i: usize, id: &str) -> bool {
        self.terrain_ids.get(usize::from(self.terrain[i])).is_some_and(|t| t == id)
    }

    /// Whether tile `i` has the feature of this id.
    pub fn feature_is(&self, i: usize, id: &str) -> bool {
        self.feature_ids.get(usize::from(self.feature[i])).is_some_and(|f| f == id)
    }

    /// Number of tiles.
    pub fn len(&self) -> usize {
        self.kinds.len()
    }

    /// The tiles within `radius` of tile `i` (itself included), each once, in a fixed order.
    pub fn range(&self, i: usize, radius: u32, out: &mut Vec<u32>) {
        self.board.range(i, radius, out);
    }

    /// Steps between tiles `a` and `b`; `None` when no path of tiles joins them.
    pub fn distance(&self, a: usize, b: usize) -> Option<u32> {
        self.board.distance(a, b)
    }
}

/// Sea a coast is next to: sea tiles but lakes.
fn sea(kind: TileKind, biome: Biome) -> bool {
    kind == TileKind::Sea && biome != Biome::Lake
}
