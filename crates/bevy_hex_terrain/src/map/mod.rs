//! The [`HexMap`] resource: the active map and the queries a strategy game needs, answered by
//! the core crate so they hold for tiles whose chunk is not loaded. [`HexMapPlugin`] (in
//! `apply.rs`) keeps it in step with map assets, hot reloads and [`LoadHexMap`] requests.

mod apply;
mod error;
mod setup;
mod source;

use std::sync::Arc;

use bevy::math::{DVec3, Ray3d};
use bevy::prelude::*;
use hex_terrain::hexx::Hex;
use hex_terrain::{ChunkCoord, MapConfig, PlacedResource, PlacedWonder, RiverTile, Setup, Terrain, TileInfo, TileKind};

pub(crate) use apply::load_failure;
pub use apply::{HexMapHandle, HexMapPlugin, LoadHexMap};
pub use error::HexMapError;
pub use setup::{GameSetUp, SetUpGame};

/// The map plugin's systems that apply map assets and [`LoadHexMap`] (inside
/// [`HexTerrainSystems::Map`](crate::HexTerrainSystems::Map)): the editor runs after them.
#[derive(SystemSet, Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) struct MapAssets;
pub use source::MapSource;

/// The active map: its config, layout and tile queries.
///
/// Positions are Bevy world coordinates: `x` and `z` on the ground, `y` up.
///
/// It changes (in Bevy's change detection) only when its terrain does: another map takes
/// effect, a hot reload applies, or an edit applies ([`HexMapEdited`](crate::HexMapEdited));
/// streaming never marks it changed. So `resource_changed::<HexMap>` means "new terrain", not
/// "new map". Code that runs once per map reads [`TerrainReady`](crate::TerrainReady) (sent once
/// per map, when its terrain is on screen), or compares [`map_id`](Self::map_id), which an edit
/// and a hot reload keep. While a map file loads, `HexMap` holds a placeholder (the thesis' Map0,
/// [`is_waiting_for_asset`](Self::is_waiting_for_asset) true, nothing streamed) whose `map_id`
/// is its own: the file's map gets another when it applies. Which chunks are loaded is
/// [`ChunkStreamer`](crate::ChunkStreamer)'s business.
#[derive(Resource, Debug, Clone, Reflect)]
#[reflect(from_reflect = false, Debug)]
pub struct HexMap {
    /// The compiled terrain (not reflected: the core's stages hold no reflected state).
    #[reflect(ignore)]
    terrain: Arc<Terrain>,
    generation: u64,
    /// The generation of the last new config (every chunk changed then).
    base_generation: u64,
    /// The generation of the last edit that changed each chunk of the map, since the last new
    /// config.
    edited_chunks: bevy::platform::collections::HashMap<ChunkCoord, u64>,
    map_id: u64,
    waiting_for_asset: bool,
    appearance_fallback: bool,
    /// The map asset whose config is applied, if any, with its heightmap.
    #[reflect(ignore)]
    applied: Option<(AssetId<crate::asset::HexMapAsset>, Option<Arc<hex_terrain::HeightImage>>)>,
    /// The game setup [`SetUpGame`] placed on this map, kept over hot reloads of a file without
    /// one.
    #[reflect(ignore)]
    asked_setup: Option<hex_terrain::SetupConfig>,
}

impl HexMap {
    /// A map from a valid config.
    ///
    /// # Errors
    /// The first invalid field of the config.
    pub fn new(config: MapConfig) -> Result<Self, hex_terrain::ConfigError> {
        Ok(Self::from_terrain(Terrain::new(config)?))
    }

    pub(crate) fn from_terrain(terrain: Terrain) -> Self {
        Self {
            terrain: Arc::new(terrain),
            generation: 0,
            base_generation: 0,
            edited_chunks: default(),
            map_id: 0,
            waiting_for_asset: false,
            appearance_fallback: false,
            applied: None,
            asked_setup: None,
        }
    }

    /// The active config.
    #[must_use]
    pub fn config(&self) -> &MapConfig {
        self.terrain.config()
    }

    /// The core generator, shareable with tasks and other threads.
    #[must_use]
    pub fn terrain(&self) -> &Arc<Terrain> {
        &self.terrain
    }

    /// Increases each time a new config takes effect (hot reload) or an edit changes the map;
    /// a chunk showing a mesh older than its [`chunk_generation`](Self::chunk_generation) is
    /// regenerated.
    #[must_use]
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// The oldest map generation whose mesh of `chunk` is still current: the last new config, or
    /// the last edit that changed the chunk (on a wrapping map, the chunk of the map it shows).
    #[must_use]
    pub fn chunk_generation(&self, chunk: ChunkCoord) -> u64 {
        if self.edited_chunks.is_empty() {
            return self.base_generation;
        }
        let chunk = self.terrain.wrap_chunk(chunk).0;
        self.edited_chunks.get(&chunk).map_or(self.base_generation, |&g| g.max(self.base_generation))
    }

    /// Whether a mesh of `chunk` built for map generation `built` shows the current map.
    #[must_use]
    pub fn is_current(&self, chunk: ChunkCoord, built: Option<u64>) -> bool {
        built.is_some_and(|g| g >= self.chunk_generation(chunk) && g <= self.generation)
    }

    /// Changes each time another map takes effect (the plugin's map file replacing the
    /// placeholder, [`LoadHexMap`]); stays the same over edits and hot reloads of the same map
    /// file. [`TileStates`](crate::TileStates) is cleared when it changes (but keeps what was
    /// written while the placeholder waited for the map file, on the tiles of the map).
    #[must_use]
    pub fn map_id(&self) -> u64 {
        self.map_id
    }

    /// The generation of the last new config (another map, a hot reload); edits leave it.
    pub(crate) fn config_generation(&self) -> u64 {
        self.base_generation
    }

    /// Whether the map still waits for its config asset (no chunks are streamed until then).
    #[must_use]
    pub fn is_waiting_for_asset(&self) -> bool {
        self.waiting_for_asset
    }

    pub(crate) fn set_waiting(&mut self, waiting: bool) {
        self.waiting_for_asset = waiting;
    }

    /// Whether the map file's appearance was out of range, so materials should draw flat colors.
    #[must_use]
    pub fn appearance_fallback(&self) -> bool {
        self.appearance_fallback
    }

    /// Another map: a new generation and a new [`map_id`](Self::map_id); every chunk is
    /// regenerated. (A game sends [`LoadHexMap`].)
    pub(crate) fn replace(&mut self, terrain: Terrain) {
        self.reload(terrain);
        self.map_id += 1;
        self.asked_setup = None;
    }

    /// The game setup (start positions, resources, natural wonders, the fairness report) when
    /// the map's config has a `setup` or [`SetUpGame`] placed one; placed once, the same in
    /// every chunk. `None` otherwise: send [`SetUpGame`] to set up a game on any map (the map
    /// types' presets come without one; the plugin logs it when such a map is ready).
    #[must_use]
    pub fn setup(&self) -> Option<&Setup> {
        self.terrain.setup()
    }

    /// The map's statistics ([`MapStats`](hex_terrain::MapStats): land and water, continents and
    /// islands, coast, straits, mountain ranges, biomes, rivers, lakes, the land of each start),
    /// measured now (a few milliseconds on the largest Civilization map: keep the answer while
    /// the map does not change); `None` for an unbounded world.
    #[must_use]
    pub fn stats(&self) -> Option<hex_terrain::MapStats> {
        hex_terrain::MapStats::measure(&self.terrain)
    }

    /// The resource on a tile (any copy of it on a wrapping map).
    #[must_use]
    pub fn resource(&self, tile: Hex) -> Option<&PlacedResource> {
        self.terrain.resource(tile)
    }

    /// The natural wonder on a tile.
    #[must_use]
    pub fn wonder(&self, tile: Hex) -> Option<&PlacedWonder> {
        self.terrain.wonder(tile)
    }

    /// The player starting on a tile (0 is the first).
    #[must_use]
    pub fn start(&self, tile: Hex) -> Option<u32> {
        self.terrain.start(tile)
    }

    /// A new config of the same map (hot reload): a new generation, the same [`map_id`](Self::map_id).
    pub(crate) fn reload(&mut self, terrain: Terrain) {
        self.terrain = Arc::new(terrain);
        self.generation += 1;
        self.base_generation = self.generation;
        self.edited_chunks.clear();
        self.waiting_for_asset = false;
        self.appearance_fallback = false;
        self.applied = None;
    }

    /// A game setup placed on the same map ([`SetUpGame`]): a new generation in which every
    /// chunk changed (their markers of starts, resources and wonders), the same
    /// [`map_id`](Self::map_id) and the same followed map file.
    pub(crate) fn set_up(&mut self, terrain: Terrain, setup: hex_terrain::SetupConfig) {
        self.terrain = Arc::new(terrain);
        self.generation += 1;
        self.base_generation = self.generation;
        self.edited_chunks.clear();
        self.asked_setup = Some(setup);
    }

    /// An edit of the same map: a new generation in which only `chunks` (of the map) changed,
    /// the same [`map_id`](Self::map_id) and the same followed map file.
    pub(crate) fn edit(&mut self, terrain: Terrain, chunks: &[ChunkCoord]) {
        self.terrain = Arc::new(terrain);
        self.generation += 1;
        for &chunk in chunks {
            self.edited_chunks.insert(chunk, self.generation);
        }
    }

    /// The tile under a world position (its `y` is ignored); on a wrapping map, the map's own
    /// tile (a position one map width east is the same tile). `None` past the world's edge
    /// ([`hex_terrain::config::MAX_WORLD_TILE`] tiles from the origin), which a wrapping map has
    /// only north and south.
    #[must_use]
    pub fn tile_at(&self, world: Vec3) -> Option<Hex> {
        self.tile_at_f64(world.as_dvec3())
    }

    /// [`tile_at`](Self::tile_at) for an f64 world position, exact however far from the origin
    /// (with the `big_space` feature, `Grid::grid_position_double` gives an entity's).
    #[must_use]
    pub fn tile_at_f64(&self, world: DVec3) -> Option<Hex> {
        self.terrain.tile_at(world.x, world.z)
    }

    /// The first tile a ray hits on the real terrain surface (not a flat plane), within
    /// `max_distance`.
    #[must_use]
    pub fn raycast(&self, ray: Ray3d, max_distance: f32) -> Option<TileHit> {
        let hit =
            self.raycast_f64(ray.origin.as_dvec3(), ray.direction.as_vec3().as_dvec3(), f64::from(max_distance))?;
        Some(TileHit { tile: hit.tile, point: hit.point.as_vec3(), distance: hit.distance as f32 })
    }

    /// [`raycast`](Self::raycast) from an f64 origin, exact however far from the world's origin.
    #[must_use]
    pub fn raycast_f64(&self, origin: DVec3, direction: DVec3, max_distance: f64) -> Option<TileHitF64> {
        let hit = self.terrain.raycast(origin.to_array(), direction.to_array(), max_distance)?;
        Some(TileHitF64 { tile: hit.tile, point: DVec3::from_array(hit.point), distance: hit.distance })
    }

    /// What a tile is: its type, center elevation, map membership, terrain under the map's
    /// ruleset (its biome on a map without its own: `terrain().ruleset().biome(..)`),
    /// river flow and lake; `None` for a tile past the world's edge (so is every tile query's
    /// answer).
    #[must_use]
    pub fn tile_info(&self, tile: Hex) -> Option<TileInfo> {
        self.terrain.tile_info(tile)
    }

    /// The cost of entering a tile by the map's movement model (its config's `movement`: the
    /// terrain's cost, plus fording a river through it); `None` when it cannot be entered or is
    /// off the map. The game setup's reach and path costs use the same rule.
    #[must_use]
    pub fn move_cost(&self, tile: Hex) -> Option<u32> {
        self.terrain.move_cost(tile)
    }

    /// The cost of the step between two neighbors: entering `to`, plus crossing a river on the
    /// edge between them ([`Terrain::step_cost`](hex_terrain::Terrain::step_cost)); what paths
    /// add up.
    #[must_use]
    pub fn step_cost(&self, from: Hex, to: Hex) -> Option<u32> {
        self.terrain.step_cost(from, to)
    }

    /// The cheapest path between two tiles by the map's movement model
    /// ([`Terrain::path`](hex_terrain::Terrain::path): A*, across the seam of a wrapping map when
    /// cheaper, a fixed choice among equal paths); `None` when there is none.
    #[must_use]
    pub fn path(&self, from: Hex, to: Hex) -> Option<hex_terrain::Path> {
        self.terrain.path(from, to)
    }

    /// As [`path`](Self::path), never entering a tile `blocked` says is taken (another unit)
    /// (the core's `Terrain::path_avoiding`).
    #[must_use]
    pub fn path_avoiding(&self, from: Hex, to: Hex, blocked: impl Fn(Hex) -> bool) -> Option<hex_terrain::Path> {
        self.terrain.path_avoiding(from, to, blocked)
    }

    /// As [`reachable`](Self::reachable), never entering a tile `blocked` says is taken
    /// (the core's `Terrain::reachable_avoiding`).
    #[must_use]
    pub fn reachable_avoiding(&self, from: Hex, budget: u32, blocked: impl Fn(Hex) -> bool) -> Vec<(Hex, u32)> {
        self.terrain.reachable_avoiding(from, budget, blocked)
    }

    /// Every tile reachable from `from` for at most `budget` movement points, with its cost
    /// ([`Terrain::reachable`](hex_terrain::Terrain::reachable)).
    #[must_use]
    pub fn reachable(&self, from: Hex, budget: u32) -> Vec<(Hex, u32)> {
        self.terrain.reachable(from, budget)
    }

    /// A path split into turns ([`Terrain::turns`](hex_terrain::Terrain::turns): Civilization V's
    /// rule for a tile that costs more than the points left).
    #[must_use]
    pub fn turns(&self, path: &hex_terrain::Path, points: u32, left: u32) -> Option<hex_terrain::Turns> {
        self.terrain.turns(path, points, left)
    }

    /// The tiles a unit on `from` sees with sight `radius`, by the map's sight rule
    /// ([`Terrain::field_of_view`](hex_terrain::Terrain::field_of_view): higher tiles and
    /// mountains block, tall tiles and mountains see farther; any radius on a bounded map).
    ///
    /// # Errors
    /// [`SightError`](hex_terrain::SightError) on an unbounded world, for a radius that with the
    /// viewer's bonus passes [`MAX_UNBOUNDED_SIGHT`](hex_terrain::MAX_UNBOUNDED_SIGHT).
    pub fn field_of_view(&self, from: Hex, radius: u32) -> Result<Vec<Hex>, hex_terrain::SightError> {
        self.terrain.field_of_view(from, radius)
    }

    /// The river running through a tile (its flow, where it comes from and goes), if any.
    #[must_use]
    pub fn river(&self, tile: Hex) -> Option<RiverTile> {
        self.terrain.river(tile)
    }

    /// The lake a tile belongs to, if it is a lake tile (water above sea level).
    #[must_use]
    pub fn lake(&self, tile: Hex) -> Option<u32> {
        self.terrain.lake(tile)
    }

    /// Type of a tile.
    #[must_use]
    pub fn tile_kind(&self, tile: Hex) -> Option<TileKind> {
        self.terrain.tile_kind(tile)
    }

    /// World position of a tile's center on the surface: where a unit standing on it goes.
    #[must_use]
    pub fn tile_center(&self, tile: Hex) -> Option<Vec3> {
        self.tile_center_f64(tile).map(DVec3::as_vec3)
    }

    /// [`tile_center`](Self::tile_center) in f64, exact however far from the origin.
    #[must_use]
    pub fn tile_center_f64(&self, tile: Hex) -> Option<DVec3> {
        self.terrain.tile_center(tile).map(DVec3::from_array)
    }

    /// Height of the surface at a world position (its `y` is ignored); `None` past the world's
    /// edge.
    #[must_use]
    pub fn surface_height(&self, world: Vec3) -> Option<f32> {
        self.surface_height_f64(world.as_dvec3()).map(|h| h as f32)
    }

    /// [`surface_height`](Self::surface_height) at an f64 world position.
    #[must_use]
    pub fn surface_height_f64(&self, world: DVec3) -> Option<f64> {
        self.terrain.surface_height(world.x, world.z)
    }

    /// Upward unit normal of the surface (as meshed) at a world position; `None` past the
    /// world's edge.
    #[must_use]
    pub fn surface_normal(&self, world: Vec3) -> Option<Vec3> {
        self.surface_normal_f64(world.as_dvec3()).map(|n| n.as_vec3())
    }

    /// [`surface_normal`](Self::surface_normal) at an f64 world position.
    #[must_use]
    pub fn surface_normal_f64(&self, world: DVec3) -> Option<DVec3> {
        self.terrain.surface_normal(world.x, world.z).map(DVec3::from_array)
    }

    /// The six neighbors of a tile of the map, in hexx's direction order: each the map's own
    /// tile (across the seam on a wrapping map), `None` where that neighbor is off the map;
    /// `None` for a tile not on the map ([`Terrain::neighbors`]).
    #[must_use]
    pub fn neighbors(&self, tile: Hex) -> Option<[Option<Hex>; 6]> {
        self.terrain.neighbors(tile)
    }

    /// The tile at an offset coordinate `[column, row]` (the coordinates of map files, the CLI
    /// and what a player sees); every input answers.
    #[must_use]
    pub fn tile_from_offset(&self, offset: [i32; 2]) -> Hex {
        self.terrain.tile_from_offset(offset)
    }

    /// The offset coordinate `[column, row]` of a tile; every input answers.
    #[must_use]
    pub fn offset_of(&self, tile: Hex) -> [i32; 2] {
        self.terrain.offset_of(tile)
    }

    /// Hex distance between two tiles, the short way round on a wrapping map; `None` when
    /// either is past the world's edge.
    #[must_use]
    pub fn distance(&self, a: Hex, b: Hex) -> Option<u32> {
        self.terrain.distance(a, b)
    }

    /// The map's own tile a tile stands for (on a wrapping map, its column modulo the map's
    /// width; the tile itself otherwise); `None` for a tile not on the map.
    #[must_use]
    pub fn wrap_tile(&self, tile: Hex) -> Option<Hex> {
        self.terrain.wrap_tile(tile)
    }

    /// The copy of `tile` nearest `near` on a wrapping map (one a whole number of map widths
    /// east or west): the goal of a path from `near` that takes the short way round, across the
    /// seam when that is shorter. The tile itself otherwise.
    #[must_use]
    pub fn tile_near(&self, tile: Hex, near: Hex) -> Hex {
        self.terrain.tile_near(tile, near)
    }

    /// On a wrapping map, `position` moved by whole map widths to the copy nearest `near` (where
    /// to draw a unit of a tile near the camera); `position` itself otherwise.
    #[must_use]
    pub fn wrap_near(&self, position: Vec3, near: Vec3) -> Vec3 {
        let Some(width) = self.terrain.wrap().map(|w| w.width as f32) else { return position };
        let k = ((near.x - position.x) / width).round();
        position + Vec3::X * (k * width)
    }

    /// [`wrap_near`](Self::wrap_near) in f64 (positions far from the origin).
    #[must_use]
    pub fn wrap_near_f64(&self, position: DVec3, near: DVec3) -> DVec3 {
        let Some(width) = self.terrain.wrap().map(|w| w.width) else { return position };
        let k = ((near.x - position.x) / width).round();
        position + DVec3::X * (k * width)
    }

    /// Whether a tile belongs to the map (every tile of the world, for an unbounded one).
    #[must_use]
    pub fn contains(&self, tile: Hex) -> bool {
        self.terrain.contains(tile)
    }

    /// The chunk holding a tile of the map (on a wrapping map, a tile past the east or west
    /// edge is in a chunk placed there); `None` for a tile not on the map.
    #[must_use]
    pub fn chunk_of(&self, tile: Hex) -> Option<ChunkCoord> {
        self.terrain.chunk_of(tile)
    }
}

/// A ray hitting a tile.
#[derive(Debug, Clone, Copy, PartialEq, Reflect)]
pub struct TileHit {
    /// The tile hit.
    pub tile: Hex,
    /// World position of the hit on the surface.
    pub point: Vec3,
    /// Distance along the ray.
    pub distance: f32,
}

/// A ray hitting a tile, in f64 world coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Reflect)]
pub struct TileHitF64 {
    /// The tile hit.
    pub tile: Hex,
    /// World position of the hit on the surface.
    pub point: DVec3,
    /// Distance along the ray.
    pub distance: f64,
}
