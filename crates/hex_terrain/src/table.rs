//! The per-map tile table, a stage of bounded maps with climate or rivers: each tile's center
//! height and kind, the water network and every tile's biome, computed once when the map is
//! compiled. Chunks read it, so a non-local feature (a river drains a whole basin) is the same in
//! every chunk and in the whole map.

use hexx::Hex;

use crate::chunk::TileRect;
use crate::climate::winds::{self, RainInput};
use crate::climate::{Climate, ClimateModel, TileSample};
use crate::config::{RiverConfig, RiverEdit, RiverModel, RiverSources};
use crate::geometry::Geometry;
use crate::heights::HeightField;
use crate::kind::Thresholds;
use crate::vocab::{Biome, TileKind};
use crate::water::edges::{EdgeInput, EdgeRivers, RiverEdge};
use crate::water::hydrology::{Hydrology, RiverTile, tile_links};

/// Per-tile data of a bounded map, row by row.
#[derive(Debug, Clone)]
pub struct TileTable {
    rect: TileRect,
    raw: Vec<f32>,
    kinds: Vec<TileKind>,
    biomes: Vec<Biome>,
    /// Each tile's climate; empty on a map without one.
    climates: Vec<Climate>,
    hydrology: Option<Hydrology>,
    /// The rivers on tile edges of a map whose rivers run there.
    edge_rivers: Option<EdgeRivers>,
}

/// What the tile table is built from that no edit changes: each tile center's source height (the
/// fBm or the heightmap, before shaping) and the climate's noise there, sampled once for the
/// tiles of a rectangle. The world builder compiles an edited map again from them, so an edit
/// costs the table's own work, not the noise's.
#[derive(Debug, Clone)]
pub struct TileFields {
    rect: TileRect,
    source: Vec<f64>,
    /// `[temperature field, moisture]` of each tile; `None` without a climate.
    climate: Vec<Option<[f64; 2]>>,
}

impl TileFields {
    /// Samples the tiles of `rect`.
    #[must_use]
    pub fn new(geometry: &Geometry, heights: &HeightField, climate: &ClimateModel, rect: TileRect) -> Self {
        let tiles: Vec<Hex> = rect.iter().map(|oc| geometry.tile_from_offset(oc)).collect();
        let centers: Vec<Hex> = tiles.iter().map(|&t| geometry.lattice().tile_center(t)).collect();
        let mut source = vec![0.0; centers.len()];
        heights.source_heights(geometry, &centers, &mut source);
        let climate = tiles.iter().map(|&t| climate.fields_at(geometry, heights, t)).collect();
        Self { rect, source, climate }
    }

    /// The tiles it holds.
    #[must_use]
    pub fn rect(&self) -> TileRect {
        self.rect
    }
}

impl TileTable {
    /// Row-major index of an in-map tile (any copy of it on a wrapping map).
    #[must_use]
    #[inline]
    pub fn index(&self, geometry: &Geometry, tile: Hex) -> Option<usize> {
        self.index_of(geometry.offset_of(geometry.wrap_tile(tile)))
    }

    /// Row-major index of an offset coordinate in the map.
    #[must_use]
    #[inline]
    pub fn index_of(&self, [c, r]: [i32; 2]) -> Option<usize> {
        self.rect.index([c, r])
    }

    /// Builds the table of the tiles of `fields`' rectangle from their noise (one height sample
    /// and the climate's noise a tile, `TileFields`): the kinds, then the water network (when
    /// `rivers` is on) and the biomes.
    #[must_use]
    pub fn build(
        geometry: &Geometry,
        heights: &HeightField,
        thresholds: &Thresholds,
        climate: &ClimateModel,
        rivers: &RiverConfig,
        fields: &TileFields,
    ) -> Self {
        let rect = fields.rect;
        let tiles: Vec<Hex> = rect.iter().map(|oc| geometry.tile_from_offset(oc)).collect();
        let centers: Vec<Hex> = tiles.iter().map(|&t| geometry.lattice().tile_center(t)).collect();
        let raw: Vec<f32> = fields.source.iter().zip(&centers).map(|(&n, &p)| heights.shaped(geometry, n, p)).collect();
        let kinds: Vec<TileKind> = raw.iter().map(|&h| thresholds.classify(h)).collect();
        let mut table =
            Self { rect, raw, kinds, biomes: Vec::new(), climates: Vec::new(), hydrology: None, edge_rivers: None };
        let samples: Vec<TileSample> = tiles.iter().enumerate().map(|(i, &t)| table.sample(geometry, i, t)).collect();
        // Each tile's neighbors, for the winds and the water network.
        let links = if climate.winds().is_some() || rivers.enabled { tile_links(geometry, rect) } else { Vec::new() };
        let neighbor = |i: usize, d: usize| Some(links[i][d] as usize).filter(|&j| j != i);
        // Each tile's climate, once: rain and biome both read it.
        let winds = climate.winds().map(|winds| {
            let input = RainInput {
                rect,
                tiles: &tiles,
                raw: &table.raw,
                kinds: &table.kinds,
                sea: thresholds.sea,
                latitudes: climate.latitudes(),
            };
            winds::rainfall(winds, geometry, &input, neighbor)
        });
        table.climates = tiles
            .iter()
            .zip(&samples)
            .zip(&fields.climate)
            .enumerate()
            .filter_map(|(i, ((&t, s), noise))| {
                let noise = (*noise)?;
                Some(match &winds {
                    Some(rain) => climate.climate_with_rain(geometry, t, s, noise, rain[i]),
                    None => climate.climate_with(geometry, t, s, noise),
                })
            })
            .collect();
        let climates: Vec<Option<Climate>> = (0..tiles.len())
            .map(|i| table.climates.get(i).copied().filter(|_| samples[i].kind != TileKind::Sea))
            .collect();
        // Each tile's biome, given which tiles are lakes: a biome set by hand stays, the others
        // follow the edited heights.
        let biomes_of = |lake: &dyn Fn(usize) -> bool| -> Vec<Biome> {
            let by_hand = |t: Hex| heights.edits().and_then(|e| e.biome(geometry, t));
            (0..tiles.len())
                .map(|i| by_hand(tiles[i]).unwrap_or_else(|| climate.biome_from(&samples[i], lake(i), climates[i])))
                .collect()
        };
        if rivers.enabled {
            let sea = thresholds.sea;
            let rain: Vec<f32> = samples
                .iter()
                .zip(&climates)
                .map(|(s, c)| {
                    // Wetter and higher tiles get more rain (air rising over relief rains out), so
                    // rivers rise on high, wet ground; the floor makes every land tile add water,
                    // so flow grows strictly downstream.
                    let relief = 0.5 + ((s.raw - sea) / (1.0 - sea).max(f32::EPSILON)).clamp(0.0, 1.0);
                    match (s.kind, c) {
                        (TileKind::Sea, _) => 0.0,
                        (_, Some(c)) => (0.05 + 0.95 * c.moisture) * relief,
                        (_, None) => relief,
                    }
                })
                .collect();
            let by_hand: Vec<Option<RiverEdit>> = match heights.edits() {
                Some(edits) => tiles.iter().map(|&t| edits.river(geometry, t)).collect(),
                None => Vec::new(),
            };
            if rivers.model == RiverModel::Centers {
                table.hydrology = Some(Hydrology::build(rivers, &table.raw, &table.kinds, &rain, &by_hand, neighbor));
            } else {
                // The tiles' network gives the lakes (and the water levels); its rivers run on the
                // edges instead.
                let hydrology = Hydrology::lakes_only(rivers, &links, (&table.raw, &table.kinds, &rain));
                let lakes: Vec<bool> = (0..tiles.len()).map(|i| hydrology.lake_of(i).is_some()).collect();
                // Hills and mountains, for rivers rising in them: the biomes are known here.
                let relief: Vec<bool> = match rivers.sources {
                    RiverSources::Flow => Vec::new(),
                    RiverSources::Relief { .. } => {
                        table.biomes = biomes_of(&|i| lakes[i]);
                        (0..tiles.len())
                            .map(|i| {
                                table.biomes[i] == Biome::Hills || (samples[i].kind == TileKind::Mountain && !lakes[i])
                            })
                            .collect()
                    }
                };
                let input = EdgeInput {
                    rect,
                    links: &links,
                    raw: &table.raw,
                    kinds: &table.kinds,
                    lakes: &lakes,
                    rain: &rain,
                    by_hand: &by_hand,
                    relief: &relief,
                };
                table.edge_rivers = Some(EdgeRivers::build(rivers, geometry, &input));
                table.hydrology = Some(hydrology);
            }
        }
        if table.biomes.is_empty() {
            let hydrology = table.hydrology.as_ref();
            table.biomes = biomes_of(&|i| hydrology.is_some_and(|h| h.lake_of(i).is_some()));
        }
        table
    }

    /// Whether tile `i` (row-major) has the same center height, kind, biome and water in `self`
    /// and `other`, two tables of one map (the world builder's comparison; lake ids aside).
    #[must_use]
    pub fn same_tile(&self, other: &Self, i: usize) -> bool {
        self.raw[i].to_bits() == other.raw[i].to_bits()
            && self.kinds[i] == other.kinds[i]
            && self.biomes[i] == other.biomes[i]
            && match (&self.hydrology, &other.hydrology) {
                (Some(a), Some(b)) => a.same_tile(b, i),
                (None, None) => true,
                _ => false,
            }
            && match (&self.edge_rivers, &other.edge_rivers) {
                (Some(a), Some(b)) => a.same_tile(b, i),
                (None, None) => true,
                _ => false,
            }
    }

    /// Tile `i`'s sample, its neighbors' kinds read from the table.
    fn sample(&self, geometry: &Geometry, i: usize, tile: Hex) -> TileSample {
        let neighbors = tile.all_neighbors().map(|nb| self.index(geometry, nb).map(|j| self.kinds[j]));
        TileSample::new(self.raw[i], self.kinds[i], neighbors)
    }

    /// The sample of an in-map tile (its center's raw height and kind, its neighbors' kinds),
    /// read from the table: what [`TileSample::of`] computes from the height field.
    #[must_use]
    pub(crate) fn tile_sample(&self, geometry: &Geometry, tile: Hex) -> Option<TileSample> {
        self.index(geometry, tile).map(|i| self.sample(geometry, i, tile))
    }

    /// The biome of an in-map tile.
    #[must_use]
    pub fn biome(&self, geometry: &Geometry, tile: Hex) -> Option<Biome> {
        self.index(geometry, tile).map(|i| self.biomes[i])
    }

    /// The climate of an in-map tile, `None` on a map without one.
    #[must_use]
    pub fn climate(&self, geometry: &Geometry, tile: Hex) -> Option<Climate> {
        self.climates.get(self.index(geometry, tile)?).copied()
    }

    /// The rivers on tile edges: `None` on a map whose rivers run through tile centers, or
    /// without rivers.
    #[must_use]
    pub fn edge_rivers(&self) -> Option<&EdgeRivers> {
        self.edge_rivers.as_ref()
    }

    /// The river edges of an in-map tile, from its side (empty without edge rivers).
    #[must_use]
    pub fn river_edges(&self, geometry: &Geometry, tile: Hex) -> Vec<RiverEdge> {
        match (&self.edge_rivers, self.index(geometry, tile)) {
            (Some(rivers), Some(i)) => rivers.river_edges(geometry.wrap_tile(tile), i),
            _ => Vec::new(),
        }
    }

    /// Which of an in-map tile's edges carry a river: bit `d` for the edge toward
    /// `all_neighbors()[d]` (0 without edge rivers).
    #[must_use]
    #[inline]
    pub fn river_edge_mask(&self, geometry: &Geometry, tile: Hex) -> u8 {
        match (&self.edge_rivers, self.index(geometry, tile)) {
            (Some(rivers), Some(i)) => rivers.edges_of(i),
            _ => 0,
        }
    }

    /// The map's water network: `None` on a map without rivers.
    #[must_use]
    pub fn hydrology(&self) -> Option<&Hydrology> {
        self.hydrology.as_ref()
    }

    /// The water network and the index of an in-map tile in it.
    #[must_use]
    #[inline]
    pub fn water_at(&self, geometry: &Geometry, tile: Hex) -> Option<(&Hydrology, usize)> {
        Some((self.hydrology.as_ref()?, self.index(geometry, tile)?))
    }

    /// The river on a tile, if one runs through it.
    #[must_use]
    pub fn river(&self, geometry: &Geometry, tile: Hex) -> Option<RiverTile> {
        let (h, i) = self.water_at(geometry, tile)?;
        if !h.river_at(i) {
            return None;
        }
        let tile = geometry.wrap_tile(tile);
        let neighbors = geometry.wrapped_neighbors(tile);
        let downstream = h.down(i).map(|d| neighbors[d]).filter(|&nb| geometry.contains(nb));
        let upstream = (0..6)
            .filter(|&d| {
                self.index(geometry, neighbors[d]).is_some_and(|j| h.river_at(j) && h.down(j) == Some((d + 3) % 6))
            })
            .map(|d| neighbors[d])
            .collect();
        Some(RiverTile { hex: tile, flow: h.flow(i), level: h.level(i), downstream, upstream })
    }

    /// Water a river on a tile carries, 0 when no river runs through it.
    #[must_use]
    pub fn river_flow(&self, geometry: &Geometry, tile: Hex) -> f32 {
        match self.water_at(geometry, tile) {
            Some((h, i)) if h.river_at(i) => h.flow(i),
            _ => 0.0,
        }
    }

    /// The lake a tile belongs to (an id, 0 for the first lake), if it is a lake tile.
    #[must_use]
    pub fn lake(&self, geometry: &Geometry, tile: Hex) -> Option<u32> {
        let (h, i) = self.water_at(geometry, tile)?;
        h.lake_of(i)
    }

    /// Water level of a tile (the filled surface, normalised), on a map with rivers.
    #[must_use]
    pub fn water_level(&self, geometry: &Geometry, tile: Hex) -> Option<f32> {
        let (h, i) = self.water_at(geometry, tile)?;
        Some(h.level(i))
    }
}
