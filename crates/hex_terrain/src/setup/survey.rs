//! The survey: what the setup needs to know of every tile of its area, read once from the
//! terrain's stages (type, biome, river, coast, yields, value, movement cost, neighbors).

use hexx::Hex;
use rayon::prelude::*;

use crate::chunk::TileRect;
use crate::climate::{ClimateModel, TileSample};
use crate::config::{MovementConfig, SetupConfig, StartOn, Yields};
use crate::geometry::Geometry;
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

/// Every tile of the setup's area, row by row.
#[derive(Debug, Clone)]
pub(crate) struct Survey {
    /// The area, offset coordinates.
    pub rect: TileRect,
    /// Columns of the area.
    pub cols: usize,
    /// Whether the area is a whole wrapping map (its columns continue across the seam).
    pub wraps: bool,
    /// Each tile (map-local axial).
    pub tiles: Vec<Hex>,
    pub kinds: Vec<TileKind>,
    pub biomes: Vec<Biome>,
    /// A river through it or on one of its edges.
    pub river: Vec<bool>,
    /// Which of its edges carry a river (bit `d`: toward `all_neighbors()[d]`), each crossed for
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
    /// The six neighbors' indices ([`NONE`] past the edge).
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

impl Survey {
    /// Surveys `rect` (in the map) with the setup's tables.
    pub fn new(stages: Stages, config: &SetupConfig, rect: TileRect) -> Self {
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
        let mut survey = Self {
            rect,
            cols,
            wraps,
            tiles,
            kinds,
            biomes,
            river,
            crossing,
            river_cost: stages.movement.river,
            coast: Vec::new(),
            yields: Vec::new(),
            cost: Vec::new(),
            eligible: Vec::new(),
            neighbors: Vec::new(),
            terrain: Vec::new(),
            feature: Vec::new(),
            terrain_ids: Vec::new(),
            feature_ids: Vec::new(),
        };
        survey.neighbors = survey
            .tiles
            .iter()
            .map(|&t| t.all_neighbors().map(|n| survey.index(geometry, n).map_or(NONE, |j| j as u32)))
            .collect();
        // A land tile next to the sea, wherever the sea lies: a neighbor on the map outside
        // the area counts too (read from the stages: only the area's edge tiles have one).
        let sea = |kind: TileKind, biome: Biome| kind == TileKind::Sea && biome != Biome::Lake;
        survey.coast = (0..survey.len())
            .map(|i| {
                survey.kinds[i] != TileKind::Sea
                    && survey.neighbors[i].iter().zip(survey.tiles[i].all_neighbors()).any(|(&j, n)| {
                        if j != NONE {
                            return sea(survey.kinds[j as usize], survey.biomes[j as usize]);
                        }
                        stages
                            .thresholds
                            .map_tile_kind(geometry, stages.heights, n)
                            .is_some_and(|kind| sea(kind, stages.biome(n, kind)))
                    })
            })
            .collect();
        let table = &config.yields;
        let ruled: Option<Vec<TileTerrain>> =
            stages.terrains.map(|terrains| survey.tiles.par_iter().map(|&t| terrains.tile_terrain(t)).collect());
        // Without its own ruleset a map's terrains are its biomes (the biome table's ruleset
        // lists them in their order).
        (survey.terrain, survey.feature) = match &ruled {
            Some(ruled) => ruled.iter().map(|t| (t.terrain.0, t.feature.map_or(NO_FEATURE, |f| f.0))).unzip(),
            None => survey.biomes.iter().map(|&b| (b as u8, NO_FEATURE)).unzip(),
        };
        survey.terrain_ids = stages.ruleset.terrains.iter().map(|t| t.id.clone()).collect();
        survey.feature_ids = stages.ruleset.features.iter().map(|f| f.id.clone()).collect();
        let traits: Option<Vec<Traits>> = ruled.map(|ruled| ruled.into_iter().map(|t| t.traits).collect());
        survey.yields = (0..survey.len())
            .map(|i| {
                let mut y = traits.as_ref().map_or_else(|| table.biome(survey.biomes[i]), |traits| traits[i].yields);
                if let Some(k) = table.kinds.get(&survey.kinds[i]) {
                    y += *k;
                }
                if survey.river[i] {
                    y += table.river;
                }
                if survey.coast[i] {
                    y += table.coast;
                }
                y
            })
            .collect();
        survey.cost = (0..survey.len())
            .map(|i| {
                let cost = match &traits {
                    Some(traits) => {
                        let sea = survey.kinds[i] == TileKind::Sea && survey.biomes[i] != Biome::Lake;
                        stages.movement.enter_with(traits[i].movement, sea, center_river[i])
                    }
                    None => stages.movement.enter(survey.biomes[i], center_river[i]),
                };
                cost.unwrap_or(0)
            })
            .collect();
        survey.eligible = (0..survey.len())
            .map(|i| {
                let land = survey.kinds[i] == TileKind::Land && !survey.biomes[i].is_water() && survey.cost[i] > 0;
                land && match config.start_on {
                    StartOn::Land => true,
                    StartOn::Coast => survey.coast[i],
                    StartOn::River => survey.river[i],
                    StartOn::CoastOrRiver => survey.coast[i] || survey.river[i],
                }
            })
            .collect();
        survey
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
        self.tiles.len()
    }

    /// Index of a tile of the area (any copy of it on a wrapping map).
    pub fn index(&self, geometry: &Geometry, tile: Hex) -> Option<usize> {
        area_index(self.rect, geometry, tile)
    }

    /// Offset coordinate of tile `i`.
    pub fn offset(&self, i: usize) -> [i32; 2] {
        [self.rect.min[0] + (i % self.cols) as i32, self.rect.min[1] + (i / self.cols) as i32]
    }

    /// The tiles within `radius` of tile `i` (itself included), each once, in a fixed order.
    pub fn range(&self, geometry: &Geometry, i: usize, radius: u32, out: &mut Vec<u32>) {
        out.clear();
        out.extend(self.tiles[i].range(radius).filter_map(|t| self.index(geometry, t)).map(|j| j as u32));
        // On a wrapping map narrower than the range, two copies of a tile fall in it.
        if self.wraps && self.cols < 2 * radius as usize + 1 {
            out.sort_unstable();
            out.dedup();
        }
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
