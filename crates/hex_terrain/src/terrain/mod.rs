//! [`Terrain`]: the facade games, the CLI and the plugin call. It holds the compiled
//! [`Pipeline`] and answers from its stages; this folder holds all of its methods, by topic:
//! `mod.rs` (compiling, the stages, tiles), `water.rs` (rivers, lakes, the water surface),
//! `generate.rs` (meshes, props), `surface.rs` (positions, heights, rays), `setup.rs` (the game
//! setup: starts, resources, wonders).
//!
//! # How queries answer
//!
//! One rule for every query of [`Terrain`] (tested over random tiles, points and positions
//! inside and outside the world in `tests/edges.rs`, with overflow checks on):
//!
//! - **The terrain at a place** ([`tile_kind`](Terrain::tile_kind),
//!   [`tile_info`](Terrain::tile_info),
//!   [`tile_climate`](Terrain::tile_climate), [`tile_center`](Terrain::tile_center),
//!   [`vertex`](Terrain::vertex), [`vertex_elevation`](Terrain::vertex_elevation),
//!   [`raw_height`](Terrain::raw_height), [`source_height`](Terrain::source_height),
//!   [`noise_position`](Terrain::noise_position), [`point_color`](Terrain::point_color),
//!   [`tile_at`](Terrain::tile_at), [`surface_height`](Terrain::surface_height),
//!   [`surface_normal`](Terrain::surface_normal), [`raycast`](Terrain::raycast),
//!   [`distance`](Terrain::distance)) answers `None` past the world
//!   ([`in_world`](Terrain::in_world), [`MAX_WORLD_TILE`](crate::MAX_WORLD_TILE)). The generated
//!   terrain goes on past a bounded map's edge, so these answer there too
//!   ([`TileInfo::in_map`] says whether the tile is the map's).
//! - **The map** ([`wrap_tile`](Terrain::wrap_tile), [`neighbors`](Terrain::neighbors),
//!   [`chunk_of`](Terrain::chunk_of), [`map_tile_kind`](Terrain::map_tile_kind),
//!   [`river`](Terrain::river), [`river_flow`](Terrain::river_flow), [`lake`](Terrain::lake),
//!   [`water_level`](Terrain::water_level), [`water_cover`](Terrain::water_cover),
//!   [`tile_setup`](Terrain::tile_setup), [`resource`](Terrain::resource),
//!   [`wonder`](Terrain::wonder), [`start`](Terrain::start)) answers `None` for a tile that is
//!   not on the map ([`contains`](Terrain::contains)). On the map, an amount that is nothing is
//!   `Some(0.0)` (a dry tile's `river_flow`, `water_cover`); a thing that is not there is
//!   `None` (`river`, `lake`, `resource`). [`neighbors`](Terrain::neighbors) answers each of
//!   the six directions: `None` where that neighbor is off the map.
//! - **Predicates** ([`contains`](Terrain::contains), [`in_world`](Terrain::in_world),
//!   [`tile_is_wet`](Terrain::tile_is_wet)) answer `false` wherever they are not true.
//! - **Conversions between coordinates** ([`tile_from_offset`](Terrain::tile_from_offset),
//!   [`offset_of`](Terrain::offset_of), [`wrap_point`](Terrain::wrap_point),
//!   [`wrap_chunk`](Terrain::wrap_chunk), [`tile_near`](Terrain::tile_near),
//!   [`rect_origin`](Terrain::rect_origin)) are arithmetic on coordinates: they answer every
//!   input, never panic, and say nothing of the terrain.
//! - **Nothing clamps silently, nothing panics**: a value a caller chose (a config, an edit, a
//!   stroke, a save) out of its range is refused with an error naming it
//!   ([`ConfigError`], [`EditError`](crate::EditError), [`SaveError`](crate::SaveError));
//!   queries never return errors.

mod generate;
pub(crate) mod rules;
mod setup;
mod surface;
mod water;

use std::sync::{Arc, OnceLock};

use hexx::{Hex, HexLayout};

pub use crate::geometry::{OFFSET_MODE, hex_orientation};
pub use crate::info::TileInfo;

use self::rules::RuleTable;
use crate::chunk::{ChunkCoord, TileRect};
use crate::climate::{Climate, ClimateModel};
use crate::config::MapConfig;
use crate::error::ConfigError;
use crate::geometry::Geometry;
use crate::heights::{Fbm, HeightField, HeightImage};
use crate::kind::{Thresholds, TileKind};
use crate::lattice::Lattice;
use crate::pipeline::Pipeline;
use crate::vertex::VertexSample;
use crate::wrap::Wrap;

/// A map config compiled into pure functions of position. Cheap to share between threads.
///
/// ```
/// use hex_terrain::{MapConfig, Terrain, TileKind};
///
/// let terrain = Terrain::new(MapConfig::default()).unwrap();
/// let tile = terrain.tile_at(3.0, 2.0).unwrap();
/// let info = terrain.tile_info(tile).unwrap();
/// let (lo, hi) = terrain.thresholds().range(info.kind);
/// let max = terrain.config().terrain.max_elevation;
/// assert!(info.elevation >= lo * max - 1e-4 && info.elevation <= hi * max + 1e-4);
/// ```
#[derive(Debug, Clone)]
pub struct Terrain {
    pipeline: Arc<Pipeline>,
    /// The rules' table of a bounded map, made on first use and shared by clones.
    rules: Arc<OnceLock<Option<RuleTable>>>,
}

impl Terrain {
    /// Validates `config` and prepares the generator (loading the heightmap of an `Image`
    /// source from its path).
    ///
    /// # Errors
    /// The first invalid field of the config; `setup.players` or `setup.min_distance` when the
    /// game setup does not fit the generated map.
    pub fn new(config: MapConfig) -> Result<Self, ConfigError> {
        Ok(Self::of(Pipeline::new(config)?))
    }

    /// Like [`Terrain::new`], with the heightmap of an `Image` source already decoded and the
    /// terrain ruleset already loaded (from assets, say); `image` is ignored for a `Noise`
    /// source, `ruleset` for a config without one.
    ///
    /// # Errors
    /// The first invalid field of the config, `source.path` when an `Image` source has no
    /// image, `ruleset` when the config names one and none is given (or it is invalid).
    pub fn with_sources(
        config: MapConfig,
        image: Option<Arc<HeightImage>>,
        ruleset: Option<Arc<crate::ruleset::TerrainRuleset>>,
    ) -> Result<Self, ConfigError> {
        Ok(Self::of(Pipeline::with_sources(config, image, ruleset)?))
    }

    /// The same map with other edits, compiled again from the stages no edit changes (the
    /// world builder's step; see [`Pipeline::with_edits`]).
    ///
    /// # Errors
    /// The first invalid edit.
    pub fn with_edits(&self, edits: Vec<crate::config::TileEdit>) -> Result<Self, ConfigError> {
        Ok(Self::of(self.pipeline.with_edits(edits)?))
    }

    /// The same map with a game setup placed on it (or none, `None`): a game set up on a map
    /// loaded without one, or set up again. Only the setup is placed (about 16 ms for 12
    /// players on Civilization VI's Huge size); the terrain is the same, bit for bit. The same
    /// as compiling the config with that `setup`.
    ///
    /// ```
    /// use hex_terrain::{MapConfig, MapSize, SetupConfig, Terrain};
    ///
    /// let config = MapConfig { seed: 3, size: MapSize::Bounded { x: 32, z: 24 }, ..MapConfig::default() };
    /// let terrain = Terrain::new(config.clone())?;
    /// assert!(terrain.setup().is_none());
    /// let setup = SetupConfig { players: 2, min_distance: 5, ..SetupConfig::default() };
    /// let game = terrain.with_setup(Some(setup.clone()))?;
    /// assert_eq!(game.setup().unwrap().starts().len(), 2);
    /// let compiled = Terrain::new(MapConfig { setup: Some(setup), ..config })?;
    /// assert_eq!(game.setup().unwrap().starts(), compiled.setup().unwrap().starts());
    /// # Ok::<(), hex_terrain::ConfigError>(())
    /// ```
    ///
    /// # Errors
    /// The first invalid field of the setup, or `setup.players` or `setup.min_distance` when
    /// its starts do not fit the map.
    pub fn with_setup(&self, setup: Option<crate::config::SetupConfig>) -> Result<Self, ConfigError> {
        // The rules (costs, sight) do not read the setup: the table is shared.
        Ok(Self { pipeline: Arc::new(self.pipeline.with_setup(setup)?), rules: self.rules.clone() })
    }

    /// The same map with its fBm, and generation's vector loops, on another kernel
    /// ([`Kernel`](crate::heights::Kernel)), or `None` if this CPU does not run it: for comparing
    /// kernels (every kernel gives the same bits, so the map is the same).
    #[must_use]
    pub fn with_kernel(&self, kernel: crate::heights::Kernel) -> Option<Self> {
        Some(Self::of(self.pipeline.with_kernel(kernel)?))
    }

    /// A compiled pipeline as a terrain (its rules' table not made yet).
    fn of(pipeline: Pipeline) -> Self {
        Self { pipeline: Arc::new(pipeline), rules: Arc::default() }
    }

    /// The rules' table of a bounded map (made on the first call), `None` for an unbounded
    /// world.
    pub(crate) fn rule_table(&self) -> Option<&RuleTable> {
        self.rules.get_or_init(|| self.bounds().map(|rect| RuleTable::new(self, rect))).as_ref()
    }

    /// The compiled stages, for code that composes them itself (a new stage takes the ones it
    /// needs as arguments).
    #[must_use]
    pub fn pipeline(&self) -> &Pipeline {
        &self.pipeline
    }

    /// The config it was built from.
    #[must_use]
    pub fn config(&self) -> &MapConfig {
        self.pipeline.config()
    }

    /// The geometry stage: lattice, layout, bounds, wrap, chunking.
    #[must_use]
    pub fn geometry(&self) -> &Geometry {
        self.pipeline.geometry()
    }

    /// The height field stage.
    #[must_use]
    pub fn heights(&self) -> &HeightField {
        self.pipeline.heights()
    }

    /// What came of the map's type: every target measured and the tries it took; `None` for a
    /// map without a type.
    ///
    /// ```
    /// use hex_terrain::{MapConfig, Terrain};
    ///
    /// let config = MapConfig::from_ron("(size: Bounded(x: 44, z: 26), wrap: true, map_type: Some((kind: Pangaea)))").unwrap();
    /// let terrain = Terrain::new(config).unwrap();
    /// let report = terrain.map_type().unwrap();
    /// assert!(report.met(), "{report}");
    /// ```
    #[must_use]
    pub fn map_type(&self) -> Option<&crate::MapTypeReport> {
        self.pipeline.heights().map_type()
    }

    /// The climate stage.
    #[must_use]
    pub fn climate(&self) -> &ClimateModel {
        self.pipeline.climate()
    }

    /// The vertex lattice.
    #[must_use]
    pub fn lattice(&self) -> &Lattice {
        self.geometry().lattice()
    }

    /// Thresholds and type ranges in effect.
    #[must_use]
    pub fn thresholds(&self) -> &Thresholds {
        self.pipeline.thresholds()
    }

    /// hexx layout of the tiles in world `(x, z)` (hexx's `y` is world `z`).
    #[must_use]
    pub fn layout(&self) -> &HexLayout {
        self.geometry().layout()
    }

    /// The fBm height source.
    #[must_use]
    pub fn fbm(&self) -> &Fbm {
        self.heights().fbm()
    }

    /// The map's tiles in offset coordinates, `None` for an unbounded world.
    #[must_use]
    pub fn bounds(&self) -> Option<TileRect> {
        self.geometry().bounds()
    }

    /// The wrap of an east-west wrapping map, `None` otherwise.
    #[must_use]
    pub fn wrap(&self) -> Option<&Wrap> {
        self.geometry().wrap()
    }

    /// Tile at offset coordinate `[col, row]`.
    #[must_use]
    pub fn tile_from_offset(&self, offset: [i32; 2]) -> Hex {
        self.geometry().tile_from_offset(offset)
    }

    /// Offset coordinate `[col, row]` of a tile.
    #[must_use]
    pub fn offset_of(&self, tile: Hex) -> [i32; 2] {
        self.geometry().offset_of(tile)
    }

    /// Whether a tile belongs to the map: on a wrapping map, every tile of the map's rows (a
    /// tile past the east or west edge is a tile of the map again, see [`Terrain::wrap_tile`]).
    #[must_use]
    pub fn contains(&self, tile: Hex) -> bool {
        self.geometry().contains(tile)
    }

    /// Every tile of a bounded map, row by row; empty for an unbounded world.
    pub fn tiles(&self) -> impl Iterator<Item = Hex> + '_ {
        self.geometry().tiles()
    }

    /// The map's own tile a tile stands for: on a wrapping map, the tile of the same row whose
    /// column is the tile's column modulo the width; the tile itself otherwise. `None` for a
    /// tile not on the map.
    #[must_use]
    pub fn wrap_tile(&self, tile: Hex) -> Option<Hex> {
        self.contains(tile).then(|| self.geometry().wrap_tile(tile))
    }

    /// The canonical lattice point of a lattice point (itself unless the map wraps).
    #[must_use]
    pub fn wrap_point(&self, p: Hex) -> Hex {
        self.geometry().wrap_point(p)
    }

    /// The chunk of the map a chunk stands for (itself unless the map wraps), and how many
    /// periods east of it the chunk is placed.
    #[must_use]
    pub fn wrap_chunk(&self, chunk: ChunkCoord) -> (ChunkCoord, i32) {
        self.geometry().wrap_chunk(chunk)
    }

    /// Whether a tile is in the world (see [`Geometry::in_world`]): every query about a tile
    /// past it answers `None`.
    #[must_use]
    pub fn in_world(&self, tile: Hex) -> bool {
        self.geometry().in_world(tile)
    }

    /// Hex distance between two tiles, the short way round on a wrapping map; `None` when
    /// either is past the world.
    #[must_use]
    pub fn distance(&self, a: Hex, b: Hex) -> Option<u32> {
        self.geometry().distance(a, b)
    }

    /// The copy of a tile nearest another tile: on a wrapping map, of the tile and the tiles a
    /// whole number of map widths east or west of it, the one nearest `near` (where a path from
    /// `near` goes the short way round, across the seam if that is shorter); the tile itself
    /// otherwise.
    #[must_use]
    pub fn tile_near(&self, tile: Hex, near: Hex) -> Hex {
        self.geometry().tile_near(tile, near)
    }

    /// The six neighbors of a tile of the map, in hexx's direction order, each the map's own
    /// tile (across the seam on a wrapping map) or `None` where that neighbor is off the map;
    /// `None` for a tile not on the map.
    #[must_use]
    pub fn neighbors(&self, tile: Hex) -> Option<[Option<Hex>; 6]> {
        let g = self.geometry();
        g.contains(tile).then(|| tile.all_neighbors().map(|n| g.contains(n).then(|| g.wrap_tile(n))))
    }

    /// Chunk size in tiles.
    #[must_use]
    pub fn chunk_size(&self) -> (u32, u32) {
        self.geometry().chunk_size()
    }

    /// The chunk holding a tile of the map; `None` for a tile not on the map. On a wrapping
    /// map, a tile past the map's east or west edge is in a chunk placed there (see
    /// `crate::wrap`).
    #[must_use]
    pub fn chunk_of(&self, tile: Hex) -> Option<ChunkCoord> {
        self.contains(tile).then(|| self.geometry().chunk_of(tile))
    }

    /// A chunk's tiles clipped to the map, `None` when it lies outside (or, on an unbounded
    /// world, past [`crate::config::MAX_WORLD_TILE`]). On a wrapping map, the tiles of the
    /// map's chunk it stands for ([`Terrain::wrap_chunk`]): a chunk placed a period east has
    /// the same tiles.
    #[must_use]
    pub fn chunk_rect(&self, chunk: ChunkCoord) -> Option<TileRect> {
        self.geometry().chunk_rect(chunk)
    }

    /// The lattice point a rectangle's mesh positions are relative to: the center of its first
    /// tile.
    #[must_use]
    pub fn rect_origin(&self, rect: TileRect) -> Hex {
        self.geometry().rect_origin(rect)
    }

    /// World position `[x, y, z]` (computed in f64) of the origin of a chunk's mesh: where its
    /// entity goes. On a wrapping map, a chunk placed a period east is the same mesh one map
    /// width further east.
    #[must_use]
    pub fn chunk_origin(&self, chunk: ChunkCoord) -> Option<[f64; 3]> {
        self.geometry().chunk_origin(chunk)
    }

    /// Every chunk of a bounded map; empty for an unbounded world.
    #[must_use]
    pub fn chunks(&self) -> Vec<ChunkCoord> {
        self.geometry().chunks()
    }

    /// Normalised height after shaping (and the edits), before manipulation, at a lattice
    /// point; `None` past the world.
    #[must_use]
    pub fn raw_height(&self, p: Hex) -> Option<f32> {
        self.geometry().point_in_world(p).then(|| self.heights().raw_height(self.geometry(), p))
    }

    /// Bare source height (fBm or heightmap, no shaping) at a lattice point; `None` past the
    /// world.
    #[must_use]
    pub fn source_height(&self, p: Hex) -> Option<f64> {
        self.geometry().point_in_world(p).then(|| self.heights().source_height(self.geometry(), p))
    }

    /// Where a lattice point samples the noise: its world position in hex radii, shifted by the
    /// map's offset (on a wrapping map, the position of its canonical point); `None` past the
    /// world.
    #[must_use]
    pub fn noise_position(&self, p: Hex) -> Option<[f64; 2]> {
        self.geometry().point_in_world(p).then(|| self.heights().noise_position(self.geometry(), p))
    }

    /// Type of a tile (by its center), whether or not it is in the map; `None` past the world.
    #[must_use]
    pub fn tile_kind(&self, tile: Hex) -> Option<TileKind> {
        self.in_world(tile).then(|| self.pipeline.tile_kind(tile))
    }

    /// Type of a tile of the map; `None` for a tile not on the map.
    #[must_use]
    pub fn map_tile_kind(&self, tile: Hex) -> Option<TileKind> {
        self.in_world(tile).then(|| self.pipeline.map_tile_kind(tile)).flatten()
    }

    /// What a tile is: its type, center elevation, membership, terrain under the map's ruleset
    /// (a biome on a map without its own), river and lake; `None` past the world. The one
    /// answer every reader of a tile follows (chunk meshes' tiles, props, the minimap, the
    /// rules, the setup, the stats): a pure function of the config, the ruleset, the edits and
    /// the tile, the same for every copy of a tile on a wrapping map, in any order, on any
    /// thread.
    ///
    /// Its terrain: a terrain set by hand ([`TileEdit::terrain`](crate::TileEdit::terrain), or
    /// [`TileEdit::biome`](crate::TileEdit::biome) on a map without its own ruleset) first,
    /// whatever the tile's elevation, climate or water; else, on a map with its own ruleset,
    /// the highest-priority rule covering its climate (as
    /// [`Terrain::tile_climate`] reads it), landform, water and rivers; else its biome: on a
    /// map with a tile table (a bounded map with climate or rivers) the table's, where lake
    /// tiles are [`Biome::Lake`](crate::Biome::Lake); else the climate's; else, without climate,
    /// the kind's ([`Biome::of_kind`](crate::Biome::of_kind)).
    #[must_use]
    pub fn tile_info(&self, tile: Hex) -> Option<TileInfo> {
        self.in_world(tile).then(|| self.pipeline.tile_info(tile))
    }

    /// The cost of entering a tile of the map by the map's movement model
    /// ([`MovementConfig::enter_with`](crate::MovementConfig::enter_with) of its terrain's
    /// traits, on the sea or not, with its river);
    /// `None` when it cannot be entered, or is off the map. The game setup's reach and path
    /// costs use the same rule.
    #[must_use]
    pub fn move_cost(&self, tile: Hex) -> Option<u32> {
        match self.rule_table() {
            Some(table) => table.cost(table.index(self.offset_of(self.wrap_tile(tile)?))?),
            None => rules::evaluate_cost(self, tile),
        }
    }

    /// Temperature and moisture of a tile, `None` when the map has no climate or the tile is
    /// past the world. A tile of a map with a tile table (a bounded map with climate or rivers)
    /// reads the table's, where the winds' rain is; any other tile, the climate's fields at its
    /// center.
    #[must_use]
    pub fn tile_climate(&self, tile: Hex) -> Option<Climate> {
        let climate = self.climate();
        if !(climate.is_enabled() && self.in_world(tile)) {
            return None;
        }
        if let Some(found) = self.pipeline.table().and_then(|table| table.climate(self.geometry(), tile)) {
            return Some(found);
        }
        Some(climate.climate_of(self.geometry(), self.heights(), tile, &self.pipeline.tile_sample(tile)))
    }

    /// The map's terrain ruleset: the one its config names
    /// ([`MapConfig::ruleset`](crate::MapConfig::ruleset)), else the 13 biomes of its biome
    /// table.
    #[must_use]
    pub fn ruleset(&self) -> &crate::ruleset::TerrainRuleset {
        self.pipeline.ruleset()
    }

    /// Whether the config names its own terrain ruleset ([`MapConfig::ruleset`]): then meshes
    /// and the minimap take its colors.
    #[must_use]
    pub fn has_own_ruleset(&self) -> bool {
        self.pipeline.has_own_ruleset()
    }

    /// Evaluates one lattice vertex through the vertex chain, computing the kinds of the tiles
    /// around it; `None` for a point past the world ([`Geometry::point_in_world`]).
    #[must_use]
    pub fn vertex(&self, p: Hex) -> Option<VertexSample> {
        self.geometry().point_in_world(p).then(|| self.pipeline.vertex(p))
    }

    /// World height of the finished surface at a lattice point; `None` past the world.
    #[must_use]
    pub fn vertex_elevation(&self, p: Hex) -> Option<f32> {
        self.geometry().point_in_world(p).then(|| self.pipeline.vertex_elevation(p))
    }
}

#[cfg(test)]
mod tests;
