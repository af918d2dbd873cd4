//! The compiled pipeline: a validated config turned into its stage objects, in the order data
//! flows through them. [`Geometry`] (where tiles and points are), [`HeightField`] (the raw height
//! of a point), [`Thresholds`] (a tile's kind), [`ClimateModel`] (temperature, moisture,
//! biomes), the [`TileTable`] of a bounded map with climate or rivers (every tile's kind, biome
//! and the water network, computed once), and [`VertexRules`] (the vertex chain: manipulation,
//! relief, carving). Each stage takes the stages it needs as arguments; the pipeline holds them
//! and answers the questions that combine them (a tile's kind, biome or info, a vertex).
//!
//! The consumers (the mesh job, queries, props, the water surface) read a `&Pipeline`;
//! [`Terrain`](crate::Terrain) is the facade over all of it.

use std::sync::Arc;

use hexx::Hex;

use crate::climate::{ClimateModel, TileSample};
use crate::config::{FeatureEdit, HeightSourceConfig, MAX_WATER_TILES, MapConfig, SetupConfig, TileEdit};
use crate::edits::Edits;
use crate::error::ConfigError;
use crate::geometry::Geometry;
use crate::heights::{HeightField, HeightImage};
use crate::kind::Thresholds;
use crate::ruleset::{FeaturePatches, TerrainRuleset, TileTerrain, TileTerrains};
use crate::setup::{Setup, Stages};
use crate::table::{TileFields, TileTable};
use crate::vertex::{VertexRules, VertexSample};
use crate::vocab::{Biome, TileInfo, TileKind};
use crate::water::channels;

/// A validated config compiled into its stages. Cheap to share between threads.
#[derive(Debug, Clone)]
pub struct Pipeline {
    config: MapConfig,
    geometry: Geometry,
    heights: HeightField,
    thresholds: Thresholds,
    climate: ClimateModel,
    /// Per-tile data of a bounded map with climate or rivers, computed once.
    table: Option<Arc<TileTable>>,
    /// The noise the table is built from, kept for compiling the map again with other edits.
    fields: Option<Arc<TileFields>>,
    vertex: VertexRules,
    /// The game setup of a map whose config asks for one, placed once.
    setup: Option<Arc<Setup>>,
    /// The terrain ruleset (the config's, or the biome table's) and its features' patches.
    terrains: Arc<Terrains>,
}

/// A map's terrain ruleset, ready to answer per tile.
#[derive(Debug)]
struct Terrains {
    ruleset: Arc<TerrainRuleset>,
    patches: FeaturePatches,
    /// Whether the config named it (else it is the biome table's, and meshes keep the biomes'
    /// colors).
    own: bool,
}

impl Terrains {
    fn new(config: &MapConfig, geometry: &Geometry, ruleset: Option<Arc<TerrainRuleset>>) -> Self {
        let own = ruleset.is_some();
        let ruleset = ruleset.unwrap_or_else(|| Arc::new(TerrainRuleset::from_biome_table(&config.climate)));
        let wrap_width = geometry.wrap().map(|w| w.width / geometry.hex_size());
        let patches = FeaturePatches::new(&ruleset, config.seed, wrap_width);
        Self { ruleset, patches, own }
    }
}

impl Pipeline {
    /// Validates `config`, loads the heightmap of an `Image` source and the terrain ruleset
    /// from their paths, and compiles.
    ///
    /// # Errors
    /// The first invalid field of the config, `source.path` when the image cannot be read,
    /// `ruleset` when the ruleset cannot be read or is invalid (its error in the message).
    pub fn new(config: MapConfig) -> Result<Self, ConfigError> {
        config.validate()?;
        let image = match &config.source {
            HeightSourceConfig::Noise => None,
            HeightSourceConfig::Image { path, .. } => {
                Some(Arc::new(HeightImage::load(std::path::Path::new(path)).map_err(|e| {
                    ConfigError::new("source.path", format!("{path:?}"), format!("a readable 8 or 16 bit PNG ({e})"))
                })?))
            }
        };
        let ruleset = match &config.ruleset {
            None => None,
            Some(path) => Some(Arc::new(TerrainRuleset::load(path).map_err(|e| {
                ConfigError::new("ruleset", format!("{path:?}"), format!("a readable, valid terrain ruleset ({e})"))
            })?)),
        };
        Self::compile(config, image, ruleset)
    }

    /// Validates `config` and compiles it with the heightmap of an `Image` source already
    /// decoded and the terrain ruleset already loaded (from assets, say); `image` is ignored for
    /// a `Noise` source, `ruleset` for a config without one.
    ///
    /// # Errors
    /// The first invalid field of the config, `source.path` when an `Image` source has no
    /// image, `ruleset` when the config names one and none is given.
    pub fn with_sources(
        config: MapConfig,
        image: Option<Arc<HeightImage>>,
        ruleset: Option<Arc<TerrainRuleset>>,
    ) -> Result<Self, ConfigError> {
        config.validate()?;
        if let (Some(path), None) = (&config.ruleset, &ruleset) {
            return Err(ConfigError::new("ruleset", format!("{path:?}"), "a loaded terrain ruleset".to_owned()));
        }
        Self::compile(config, image, ruleset)
    }

    /// Builds the stages of a validated config, each from the ones before it.
    fn compile(
        config: MapConfig,
        image: Option<Arc<HeightImage>>,
        ruleset: Option<Arc<TerrainRuleset>>,
    ) -> Result<Self, ConfigError> {
        if let Some(frequency) = config.size.globe() {
            return Err(ConfigError::new(
                "size",
                format!("Globe {{ frequency: {frequency} }}"),
                "Bounded or Unbounded for a flat map (a globe is generated by GlobeTerrain::new)".to_owned(),
            ));
        }
        let ruleset = match (config.ruleset.is_some(), ruleset) {
            (true, Some(ruleset)) => {
                ruleset.validate()?;
                check_edit_ids(&config, &ruleset)?;
                Some(ruleset)
            }
            _ => None,
        };
        let geometry = Geometry::new(&config);
        let heights = HeightField::new(&config, &geometry, image)?;
        let thresholds = Thresholds::new(&config.terrain, &config.manipulation);
        let climate = ClimateModel::new(&config, &geometry, thresholds);
        // Rivers need the whole map's table; a climate alone uses it on maps up to the size
        // rivers allow, and computes biomes chunk by chunk on larger ones.
        let bounds = geometry.bounds();
        let tiles = bounds.map_or(u64::MAX, |b| b.len() as u64);
        let fields = bounds
            .filter(|_| config.rivers.enabled || (config.climate.enabled && tiles <= MAX_WATER_TILES))
            .map(|rect| Arc::new(TileFields::new(&geometry, &heights, &climate, rect)));
        let vertex = VertexRules::new(&config, thresholds);
        let terrains = Arc::new(Terrains::new(&config, &geometry, ruleset));
        let stages =
            Self { config, geometry, heights, thresholds, climate, table: None, fields, vertex, setup: None, terrains };
        stages.finish()
    }

    /// The same map with other edits (validated like any config): the stages no edit changes
    /// (the geometry, the noise, the climate's fields, the tile table's samples) are reused, so
    /// this costs the edits, the tile table (kinds, rivers, lakes, biomes) and the setup.
    ///
    /// # Errors
    /// The first invalid edit (`edits[i]...`).
    pub fn with_edits(&self, edits: Vec<TileEdit>) -> Result<Self, ConfigError> {
        let config = MapConfig { edits, ..self.config.clone() };
        config.validate()?;
        if self.terrains.own {
            check_edit_ids(&config, &self.terrains.ruleset)?;
        }
        let stages = Self {
            config,
            geometry: self.geometry.clone(),
            heights: self.heights.without_edits(),
            thresholds: self.thresholds,
            climate: self.climate.clone(),
            table: None,
            fields: self.fields.clone(),
            vertex: self.vertex.clone(),
            setup: None,
            terrains: self.terrains.clone(),
        };
        stages.finish()
    }

    /// The same map with another game setup (`None`: none), validated like any config: every
    /// stage of the terrain is reused, so this costs the setup's placement alone (see
    /// [`Setup::build`]).
    ///
    /// # Errors
    /// The first invalid field of the setup (`setup.players`, ...), or `setup.players` or
    /// `setup.min_distance` when its starts do not fit the map.
    pub fn with_setup(&self, setup: Option<SetupConfig>) -> Result<Self, ConfigError> {
        let config = MapConfig { setup, ..self.config.clone() };
        config.validate()?;
        let placed = match &config.setup {
            Some(setup) => Some(Arc::new(Setup::build(self.stages(), setup, config.seed)?)),
            None => None,
        };
        Ok(Self { config, setup: placed, ..self.clone() })
    }

    /// Applies the edits to the height field, then builds the tile table and the setup.
    fn finish(mut self) -> Result<Self, ConfigError> {
        if !self.config.edits.is_empty() {
            // The edits move tiles relative to their generated centers.
            let (geometry, heights, thresholds) = (&self.geometry, &self.heights, &self.thresholds);
            let generated = |tile| heights.raw_height(geometry, geometry.lattice().tile_center(tile));
            let edits = Edits::new(&self.config.edits, geometry, (thresholds.sea, thresholds.mountain), generated);
            self.heights = self.heights.with_edits(edits);
        }
        self.table = self.fields.as_ref().map(|fields| {
            Arc::new(TileTable::build(
                &self.geometry,
                &self.heights,
                &self.thresholds,
                &self.climate,
                &self.config.rivers,
                fields,
            ))
        });
        if let Some(setup) = &self.config.setup {
            let placed = Setup::build(self.stages(), setup, self.config.seed)?;
            self.setup = Some(Arc::new(placed));
        }
        Ok(self)
    }

    /// The terrain stages a later stage (the game setup) reads.
    #[must_use]
    pub fn stages(&self) -> Stages<'_> {
        Stages {
            geometry: &self.geometry,
            heights: &self.heights,
            thresholds: &self.thresholds,
            climate: &self.climate,
            table: self.table(),
            movement: &self.config.movement,
            terrains: self.terrains.own.then_some(self as &dyn TileTerrains),
            ruleset: &self.terrains.ruleset,
        }
    }

    /// The game setup, when the config asks for one.
    #[must_use]
    pub fn setup(&self) -> Option<&Setup> {
        self.setup.as_deref()
    }

    /// The config it was compiled from.
    #[must_use]
    pub fn config(&self) -> &MapConfig {
        &self.config
    }

    /// Geometry: lattice, layout, bounds, wrap, chunking.
    #[must_use]
    pub fn geometry(&self) -> &Geometry {
        &self.geometry
    }

    /// The height field.
    #[must_use]
    pub fn heights(&self) -> &HeightField {
        &self.heights
    }

    /// The same stages with the height field's fBm on another kernel, or `None` if this CPU does
    /// not run it. Every kernel gives the same bits, so nothing else is compiled again.
    #[must_use]
    pub fn with_kernel(&self, kernel: crate::heights::Kernel) -> Option<Self> {
        Some(Self { heights: self.heights.with_kernel(kernel)?, ..self.clone() })
    }

    /// Thresholds and type ranges in effect.
    #[must_use]
    pub fn thresholds(&self) -> &Thresholds {
        &self.thresholds
    }

    /// The climate.
    #[must_use]
    pub fn climate(&self) -> &ClimateModel {
        &self.climate
    }

    /// The per-tile table of a bounded map with climate or rivers.
    #[must_use]
    pub fn table(&self) -> Option<&TileTable> {
        self.table.as_deref()
    }

    /// The tile table of a map with rivers (what carving reads), `None` on a map without.
    #[must_use]
    #[inline]
    pub fn water_table(&self) -> Option<&TileTable> {
        self.table().filter(|t| t.hydrology().is_some())
    }

    /// The vertex chain.
    #[must_use]
    pub fn vertex_rules(&self) -> &VertexRules {
        &self.vertex
    }

    /// World height of the highest possible surface.
    #[must_use]
    pub fn max_elevation(&self) -> f32 {
        self.config.terrain.max_elevation
    }

    /// Type of a tile (by its center), whether or not it is in the map.
    #[must_use]
    #[inline]
    pub fn tile_kind(&self, tile: Hex) -> TileKind {
        self.thresholds.tile_kind(&self.geometry, &self.heights, tile)
    }

    /// Type of a tile if it belongs to the map.
    #[must_use]
    #[inline]
    pub fn map_tile_kind(&self, tile: Hex) -> Option<TileKind> {
        self.thresholds.map_tile_kind(&self.geometry, &self.heights, tile)
    }

    /// A tile's biome: from the table when the map has one, else from its center sample.
    #[must_use]
    pub fn tile_biome(&self, tile: Hex) -> Biome {
        if let Some(biome) = self.heights.edits().and_then(|e| e.biome(&self.geometry, tile)) {
            return biome;
        }
        if let Some(biome) = self.table().and_then(|t| t.biome(&self.geometry, tile)) {
            return biome;
        }
        self.climate.biome_of(&self.geometry, &self.heights, tile, &self.tile_sample(tile), false)
    }

    /// The map's terrain ruleset: the config's, or the biome table's
    /// ([`TerrainRuleset::from_biome_table`]).
    #[must_use]
    pub fn ruleset(&self) -> &TerrainRuleset {
        &self.terrains.ruleset
    }

    /// Whether the config names its own terrain ruleset (then meshes take its colors).
    #[must_use]
    pub fn has_own_ruleset(&self) -> bool {
        self.terrains.own
    }

    /// What a tile of the map is under its ruleset: its terrain and feature from its landform,
    /// climate, height within its kind's band, latitude, and whether sea, a lake or a river is
    /// beside it. On a map without its own ruleset, the terrain is the tile's generated biome
    /// (a biome painted by hand is [`Pipeline::tile_biome`]'s).
    #[must_use]
    pub fn tile_terrain(&self, tile: Hex) -> TileTerrain {
        let geometry = &self.geometry;
        let sample = self.tile_sample(tile);
        let lake = self.table().is_some_and(|t| t.lake(geometry, tile).is_some());
        // The sample already knows its sea neighbors (their kinds, sampled once); lakes are the
        // table's.
        let lake_beside = |h: Hex| {
            let h = geometry.wrap_tile(h);
            geometry.contains(h) && self.table().is_some_and(|t| t.lake(geometry, h).is_some())
        };
        let near_water = sample.next_to_sea || tile.all_neighbors().into_iter().any(lake_beside);
        let near_river =
            self.table().is_some_and(|t| t.river_flow(geometry, tile) > 0.0 || t.river_edge_mask(geometry, tile) != 0);
        let climate = (self.climate.is_enabled() && !lake && sample.kind != TileKind::Sea).then(|| {
            self.table()
                .and_then(|t| t.climate(geometry, tile))
                .unwrap_or_else(|| self.climate.climate_of(geometry, &self.heights, tile, &sample))
        });
        let facts = self.climate.facts(geometry, tile, &sample, lake, climate, (near_water, near_river));
        let ruleset = &self.terrains.ruleset;
        // Set by hand (ids the compile checked), else by the rules.
        let (painted, grown) = self.heights.edits().map_or((None, None), |e| e.terrain(geometry, tile));
        let terrain =
            painted.and_then(|id| ruleset.terrain_id(id.as_str())).unwrap_or_else(|| ruleset.terrain_for(&facts));
        let feature = match grown {
            Some(FeatureEdit::Grow(id)) => ruleset.feature_id(id.as_str()),
            Some(FeatureEdit::Clear) => None,
            None => {
                let [x, z] = geometry.lattice().unit(geometry.lattice().tile_center(tile));
                self.terrains.patches.feature_for(ruleset, terrain, &facts, (x, z))
            }
        };
        TileTerrain {
            terrain,
            landform: facts.landform,
            feature,
            traits: ruleset.traits(terrain, facts.landform, feature),
        }
    }

    /// A tile's color in the meshes: its biome's, or, under the map's own ruleset, its
    /// feature's (else its terrain's).
    #[must_use]
    pub fn tile_color(&self, tile: Hex) -> [u8; 3] {
        self.tile_look(tile).0
    }

    /// A tile's color and texture layer in the meshes: its biome's (the default ruleset's
    /// terrain of that biome), or, under the map's own ruleset, its feature's (else its
    /// terrain's).
    #[must_use]
    pub fn tile_look(&self, tile: Hex) -> ([u8; 3], u8) {
        if !self.terrains.own {
            let biome = self.tile_biome(tile);
            return (biome.color(), self.biome_texture(biome));
        }
        let t = self.tile_terrain(tile);
        let ruleset = &self.terrains.ruleset;
        let look = t.feature.map_or(&ruleset.terrain(t.terrain).look, |f| &ruleset.feature(f).look);
        (look.color, look.texture)
    }

    /// The texture layer of a biome: its terrain's in the default ruleset (sea, grass or rock).
    #[must_use]
    pub fn biome_texture(&self, biome: Biome) -> u8 {
        crate::ruleset::biome_texture(biome)
    }

    /// The center sample of a tile and its neighbors' kinds.
    #[must_use]
    pub fn tile_sample(&self, tile: Hex) -> TileSample {
        TileSample::of(&self.geometry, &self.heights, &self.thresholds, tile)
    }

    /// Evaluates one lattice vertex, computing the kinds of the tiles around it.
    #[must_use]
    pub fn vertex(&self, p: Hex) -> VertexSample {
        self.vertex.evaluate(&self.geometry, &self.heights, self.water_table(), p, |t| self.map_tile_kind(t))
    }

    /// World height of the finished surface at a lattice point.
    #[must_use]
    pub fn vertex_elevation(&self, p: Hex) -> f32 {
        self.vertex(p).height * self.max_elevation()
    }

    /// Type, center elevation, membership, biome, river and lake of a tile.
    #[must_use]
    pub fn tile_info(&self, tile: Hex) -> TileInfo {
        let sample = self.vertex(self.geometry.lattice().tile_center(tile));
        self.info_of(tile, self.thresholds.classify(sample.raw), sample.height * self.max_elevation())
    }

    /// A tile's info from its kind and center elevation.
    #[must_use]
    pub fn info_of(&self, tile: Hex, kind: TileKind, elevation: f32) -> TileInfo {
        let table = self.table();
        TileInfo {
            hex: tile,
            kind,
            elevation,
            in_map: self.geometry.contains(tile),
            biome: self.tile_biome(tile),
            river_flow: table.map_or(0.0, |t| t.river_flow(&self.geometry, tile)),
            lake: table.and_then(|t| t.lake(&self.geometry, tile)),
        }
    }

    /// Whether any water (a lake, or a river channel) lies on a tile.
    #[must_use]
    #[inline]
    pub fn tile_is_wet(&self, tile: Hex) -> bool {
        self.water_table().is_some_and(|t| channels::is_wet(&self.geometry, t, tile))
    }

    /// How much of a channel or lake covers lattice point `p` of `tile` (see
    /// `channels::cover`).
    #[must_use]
    pub fn water_cover(&self, tile: Hex, p: Hex) -> f32 {
        self.water_table().map_or(0.0, |t| channels::cover(&self.geometry, t, tile, p))
    }

    /// Whether meshes carry a color per vertex (climate or rivers on).
    #[must_use]
    pub fn has_vertex_colors(&self) -> bool {
        self.config.climate.enabled || self.config.rivers.enabled
    }

    /// World height of the sea surface: the sea threshold times the maximum elevation (the
    /// height of every border vertex between sea and land tiles).
    #[must_use]
    pub fn sea_level(&self) -> f32 {
        self.thresholds.sea * self.max_elevation()
    }
}

impl TileTerrains for Pipeline {
    fn tile_terrain(&self, tile: Hex) -> TileTerrain {
        Pipeline::tile_terrain(self, tile)
    }
}

/// Every terrain and feature an edit sets is one of the ruleset's: a save whose ruleset lost an
/// id it needs is refused, naming the edit and the ids the ruleset has.
fn check_edit_ids(config: &MapConfig, ruleset: &TerrainRuleset) -> Result<(), ConfigError> {
    for (i, edit) in config.edits.iter().enumerate() {
        if let Some(id) = edit.terrain.filter(|id| ruleset.terrain_id(id.as_str()).is_none()) {
            let ids: Vec<&str> = ruleset.terrains.iter().map(|t| t.id.as_str()).collect();
            return Err(ConfigError::new(
                &format!("edits[{i}].terrain"),
                format!("{id:?}"),
                format!("a terrain of the ruleset {:?}: {}", ruleset.name, ids.join(", ")),
            ));
        }
        if let Some(FeatureEdit::Grow(id)) = edit.feature.filter(|f| match f {
            FeatureEdit::Grow(id) => ruleset.feature_id(id.as_str()).is_none(),
            FeatureEdit::Clear => false,
        }) {
            let ids: Vec<&str> = ruleset.features.iter().map(|f| f.id.as_str()).collect();
            return Err(ConfigError::new(
                &format!("edits[{i}].feature"),
                format!("{id:?}"),
                format!("a feature of the ruleset {:?}: {}", ruleset.name, ids.join(", ")),
            ));
        }
    }
    Ok(())
}
