//! A globe's terrain: the thesis' tiles on the sphere. Every fine point's height is 3D fBm at
//! its direction (the flat map's octaves, persistence, lacunarity and scale, so no seam and no
//! pinch anywhere), a tile's kind is its center's height against the thresholds, and each point
//! is manipulated as on the flat map (interpolation, hex unity, edge and corner correction) from
//! its raw height, its ring and the kinds of the tiles holding it: a pure function of the
//! config and the point, so chunks meet bit for bit and a globe made chunk by chunk is the globe
//! made whole.

use std::sync::Arc;

use rayon::prelude::*;

use super::atlas::Spot;
use super::fine::{Fine, Point};
use super::project::{self, Dir};
use super::{GlobeGrid, GlobeTile};
pub use chunks::GlobeChunk;
pub use mesh::{GlobeMesh, GlobePoint};

mod chunks;
mod coarse;
mod mesh;
mod tiles;
mod whole;
use super::climate::Ground;
use super::edits::GlobeEdits;
use super::map_type::{GlobeMapType, TypeGround};
use crate::climate::Climate;
use crate::climate::landform;
use crate::config::{MapConfig, MapSize, SetupConfig, TileEdit};
use crate::error::ConfigError;
use crate::heights::MapTypeReport;
use crate::heights::fbm::{LANES, SolidFbm};
use crate::kind::{Thresholds, TileKind};
use crate::manipulate::{manipulate, span};
use crate::mesh::vertex_color;
use crate::ruleset::{Landform, TerrainRuleset};
use crate::setup::survey::GlobeStages;
use crate::setup::{GlobeSetup, TileSetup};
use crate::vocab::Biome;

/// A point of a globe finished: its height after manipulation, its ring, the highest kind of
/// the tiles holding it, its world position, and on a globe with a climate its color (the
/// holders' biome colors averaged).
#[derive(Debug, Clone, Copy)]
pub(super) struct Finished {
    pub(super) height: f32,
    pub(super) ring: u32,
    pub(super) kind: TileKind,
    pub(super) position: Dir,
    pub(super) color: Option<[u8; 4]>,
}

impl Finished {
    /// A point not finished yet: what a buffer of them starts as.
    pub(super) const UNSET: Self = Self { height: 0.0, ring: 0, kind: TileKind::Sea, position: [0.0; 3], color: None };
}

/// A hex globe's terrain, compiled from a [`MapConfig`] of size [`MapSize::Globe`].
#[derive(Clone)]
pub struct GlobeTerrain {
    config: MapConfig,
    grid: GlobeGrid,
    fine: Fine,
    /// The fBm, its points in hex radii.
    fbm: SolidFbm,
    /// The config's map type, compiled for this globe.
    map_type: Option<GlobeMapType>,
    thresholds: Thresholds,
    /// The globe's radius in hex radii.
    radius: f64,
    /// Each tile's generated center height (raw, before the edits), by id.
    generated: Vec<f32>,
    /// The config's edits, compiled.
    edits: GlobeEdits,
    /// Each tile's center height (raw, edited), kind, climate and biome, by id.
    centers: Vec<f32>,
    kinds: Vec<TileKind>,
    climates: Vec<Option<Climate>>,
    biomes: Vec<Biome>,
    landforms: Vec<Landform>,
    /// The config's default terrain ruleset ([`TerrainRuleset::biomes`]): what each biome's
    /// tiles cost to enter, whether they stand tall, what they yield.
    ruleset: Arc<TerrainRuleset>,
    /// Each chunk's cap: the direction of its middle and the angle from it that holds all of
    /// its ground; found at the first [`GlobeTerrain::chunks_within`].
    caps: std::sync::OnceLock<Vec<(GlobeChunk, Dir, f64)>>,
    /// The game setup, when the config has one.
    setup: Option<Arc<GlobeSetup>>,
}

impl std::fmt::Debug for GlobeTerrain {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GlobeTerrain")
            .field("name", &self.config.name)
            .field("seed", &self.config.seed)
            .field("frequency", &self.grid.frequency())
            .field("radius", &self.radius())
            .finish_non_exhaustive()
    }
}

impl GlobeTerrain {
    /// Validates `config` and compiles the globe: every tile's center height and kind.
    ///
    /// # Errors
    /// The first invalid field, or `size` when the config is not a globe's.
    pub fn new(config: MapConfig) -> Result<Self, ConfigError> {
        config.validate()?;
        let MapSize::Globe { frequency } = config.size else {
            return Err(ConfigError::new(
                "size",
                format!("{:?}", config.size),
                "Globe { frequency } for a globe (a flat map is compiled by Terrain::new)".to_owned(),
            ));
        };
        let grid = GlobeGrid::new(frequency)?;
        // The thesis' vertex step is a quarter of a hex radius, and its noise scale counts them.
        let fbm = SolidFbm::new(config.seed, &config.noise, 4.0 / config.noise.scale);
        // The sphere whose area is the tiles' at the flat map's hexagon area (3 sqrt 3 / 2 for a
        // hex radius of 1): every tile about the size of a flat map's tile.
        let tiles = f64::from(grid.tile_count());
        let radius = (tiles * 3.0 * 3f64.sqrt() / (8.0 * std::f64::consts::PI)).sqrt();
        let mut globe = Self {
            fine: Fine::new(frequency, config.subdivisions()),
            fbm,
            map_type: None,
            thresholds: Thresholds::new(&config.terrain, &config.manipulation),
            radius,
            generated: Vec::new(),
            edits: GlobeEdits::default(),
            centers: Vec::new(),
            kinds: Vec::new(),
            climates: Vec::new(),
            biomes: Vec::new(),
            landforms: Vec::new(),
            ruleset: Arc::new(TerrainRuleset::biomes(&config)),
            caps: std::sync::OnceLock::new(),
            setup: None,
            grid,
            config,
        };
        let centers: Vec<Point> = globe.grid.tiles().map(|t| globe.fine.center(globe.spot(t))).collect();
        let fbm: Vec<(Dir, f64)> =
            centers.par_chunks(LANES).flat_map_iter(|batch| globe.directions_and_fbm(batch)).collect();
        if let Some(config) = &globe.config.map_type {
            let t = &globe.thresholds;
            globe.map_type = Some(GlobeMapType::build(&TypeGround {
                config,
                seed: globe.config.seed,
                grid: &globe.grid,
                centers: &fbm,
                diamonds: &globe.grid.projection.diamond_caps(),
                thresholds: (t.sea, t.mountain),
            }));
        }
        globe.generated = centers.iter().zip(&fbm).map(|(&p, &(dir, fbm))| globe.shape(p, dir, fbm)).collect();
        globe.compile_tiles();
        globe.setup = globe.place_setup()?;
        Ok(globe)
    }

    /// The globe with other edits ([`MapConfig::edits`]): the same config but for them,
    /// compiled again without generating the map type or the centers' noise again (what the
    /// [`GlobeEditor`](crate::GlobeEditor) does after each stroke). Equal, bit for bit, to
    /// [`GlobeTerrain::new`] of the config with those edits.
    ///
    /// # Errors
    /// The first invalid field of the edited config (`edits[i]...`).
    pub fn with_edits(&self, edits: Vec<TileEdit>) -> Result<Self, ConfigError> {
        let config = MapConfig { edits, ..self.config.clone() };
        config.validate()?;
        let mut globe = Self { config, caps: std::sync::OnceLock::new(), ..self.clone() };
        globe.compile_tiles();
        globe.setup = globe.place_setup()?;
        Ok(globe)
    }

    /// The same globe with another game setup (`None`: none), validated like any config: the
    /// tiles are reused, so this costs the setup's placement alone.
    ///
    /// # Errors
    /// The first invalid field of the setup (`setup.players`, ...), or `setup.players` or
    /// `setup.min_distance` when its starts do not fit the globe.
    pub fn with_setup(&self, setup: Option<SetupConfig>) -> Result<Self, ConfigError> {
        let config = MapConfig { setup, ..self.config.clone() };
        config.validate()?;
        let mut globe = Self { config, ..self.clone() };
        globe.setup = globe.place_setup()?;
        Ok(globe)
    }

    /// The game setup of the config's `setup`, placed on the compiled tiles.
    fn place_setup(&self) -> Result<Option<Arc<GlobeSetup>>, ConfigError> {
        let Some(config) = &self.config.setup else { return Ok(None) };
        let stages = GlobeStages {
            grid: &self.grid,
            kinds: &self.kinds,
            biomes: &self.biomes,
            terrains: self.grid.tiles().map(|t| self.tile_terrain(t).expect("a tile of the globe")).collect(),
            costs: self.grid.tiles().map(|t| self.move_cost(t)).collect(),
            ruleset: &self.ruleset,
            movement: &self.config.movement,
        };
        GlobeSetup::build(stages, config, self.config.seed).map(|setup| Some(Arc::new(setup)))
    }

    /// The game setup (start positions, resources, natural wonders, the fairness report), when
    /// the config has a `setup`.
    #[must_use]
    pub fn setup(&self) -> Option<&GlobeSetup> {
        self.setup.as_deref()
    }

    /// What the setup placed on a tile; `None` without a setup or for a tile not of the globe.
    #[must_use]
    pub fn tile_setup(&self, tile: GlobeTile) -> Option<TileSetup<'_, GlobeTile>> {
        self.setup()?.at(tile)
    }

    /// Each tile's edited center height, kind, climate and biome from the generated centers and
    /// the config's edits.
    fn compile_tiles(&mut self) {
        let t = &self.thresholds;
        self.edits = GlobeEdits::new(&self.config.edits, (t.sea, t.mountain), &self.generated);
        self.centers = self.grid.tiles().zip(&self.generated).map(|(t, &h)| self.edits.apply(&[t], h)).collect();
        self.kinds = self.centers.iter().map(|&h| self.thresholds.classify(h)).collect();
        let ground = Ground {
            config: &self.config,
            thresholds: &self.thresholds,
            grid: &self.grid,
            heights: &self.centers,
            kinds: &self.kinds,
            radius: self.radius,
        };
        (self.climates, self.biomes) = ground.climates();
        let (t, hills) = (&self.thresholds, self.config.climate.enabled.then_some(self.config.climate.hills));
        self.landforms =
            self.grid.tiles().map(|tile| landform(&ground.sample(tile), false, (t.sea, t.mountain), hills)).collect();
        for (t, biome) in self.grid.tiles().zip(&mut self.biomes) {
            if let Some(by_hand) = self.edits.biome(t) {
                *biome = by_hand;
            }
        }
    }

    /// The config it was compiled from.
    #[must_use]
    pub fn config(&self) -> &MapConfig {
        &self.config
    }

    /// Its tiles' grid.
    #[must_use]
    pub fn grid(&self) -> &GlobeGrid {
        &self.grid
    }

    /// The thresholds tile kinds are classified by.
    #[must_use]
    pub fn thresholds(&self) -> &Thresholds {
        &self.thresholds
    }

    /// The radius of height 0, in world units: the sphere whose area is the tiles' at the flat
    /// map's tile area (`layout.hex_size` the hex radius). A point of normalised height `h` lies
    /// at `radius() + h * terrain.max_elevation` from the center; the sea's surface at
    /// `radius() + terrain.sea_threshold * terrain.max_elevation`.
    #[must_use]
    pub fn radius(&self) -> f64 {
        self.radius * f64::from(self.config.layout.hex_size)
    }

    /// The globe's terrain ruleset: its config's biome table as the 13 biomes
    /// ([`TerrainRuleset::biomes`]; a ruleset of a game's own is for flat maps yet).
    #[must_use]
    pub fn ruleset(&self) -> &TerrainRuleset {
        &self.ruleset
    }

    /// What came of the config's map type: its targets measured on the globe's tiles, and the
    /// tries it took; `None` without a map type.
    #[must_use]
    pub fn map_type_report(&self) -> Option<&MapTypeReport> {
        self.map_type.as_ref().map(GlobeMapType::report)
    }

    /// The share of the tiles that are sea.
    #[must_use]
    pub fn sea_share(&self) -> f64 {
        self.kinds.iter().filter(|&&k| k == TileKind::Sea).count() as f64 / self.kinds.len() as f64
    }

    /// Vertices of the whole globe's mesh: `30 f^2 n^2 + 2` (`n = inner_rings + 1`), every fine
    /// point once.
    #[must_use]
    pub fn vertex_count(&self) -> u64 {
        let (f, n) = (u64::from(self.grid.frequency()), u64::from(self.config.subdivisions()));
        30 * f * f * n * n + 2
    }

    /// Triangles of the whole globe's mesh: `60 f^2 n^2` (`6 n^2` a hexagon, `5 n^2` a pentagon).
    #[must_use]
    pub fn triangle_count(&self) -> u64 {
        let (f, n) = (u64::from(self.grid.frequency()), u64::from(self.config.subdivisions()));
        60 * f * f * n * n
    }

    /// The mesh of a chunk (empty for a chunk not of this globe).
    #[must_use]
    pub fn generate(&self, chunk: GlobeChunk) -> GlobeMesh {
        let tiles = self.chunk_tiles(chunk);
        let origin = tiles.first().map_or([0.0; 3], |&t| {
            let c = self.direction(self.fine.center(self.spot(t)));
            [c[0] * self.radius(), c[1] * self.radius(), c[2] * self.radius()]
        });
        self.mesh(tiles, origin)
    }

    /// A tile's fine triangles as meshed, in world units from the globe's center.
    pub(super) fn tile_triangles(&self, tile: GlobeTile) -> Vec<[Dir; 3]> {
        let spot = self.spot(tile);
        let points = self.fine.tile_points(spot);
        let known = vec![None; points.len()];
        let at: std::collections::HashMap<u64, Dir> = points
            .chunks(LANES)
            .zip(known.chunks(LANES))
            .flat_map(|(p, k)| {
                p.iter().zip(self.finish_batch(p, k)).map(|(&q, f)| (self.fine.id(q), f.position)).collect::<Vec<_>>()
            })
            .collect();
        self.fine.triangles(spot).into_iter().map(|t| t.map(|p| at[&self.fine.id(p)])).collect()
    }

    /// The direction of a tile's center.
    pub(super) fn center(&self, tile: GlobeTile) -> Dir {
        self.direction(self.fine.center(self.spot(tile)))
    }

    fn spot(&self, tile: GlobeTile) -> Spot {
        self.grid.spot(tile).expect("a tile of the grid")
    }

    fn direction(&self, p: Point) -> Dir {
        let (d, u, v) = project::spot_uv(self.fine.big(), p);
        self.grid.projection.direction(d, u, v)
    }

    /// Up to `LANES` points' directions and fBm, before a map type shapes it.
    fn directions_and_fbm(&self, points: &[Point]) -> Vec<(Dir, f64)> {
        self.directions_and_fbm_lanes(points)[..points.len()].to_vec()
    }

    /// Up to `LANES` points' directions and fBm, in the first `points.len()` lanes.
    fn directions_and_fbm_lanes(&self, points: &[Point]) -> [(Dir, f64); LANES] {
        debug_assert!(!points.is_empty() && points.len() <= LANES);
        // Each lane's vector toward its point (the lanes beyond the points repeat them: the
        // batch is always full), then all normalised in one loop the compiler vectorizes:
        // `direction`'s bits, without waiting on each lane's square root and division.
        let mut dirs = [[0.0; 3]; LANES];
        for (l, d) in dirs.iter_mut().enumerate() {
            let (diamond, u, v) = project::spot_uv(self.fine.big(), points[l % points.len()]);
            *d = self.grid.projection.toward(diamond, u, v);
        }
        for d in &mut dirs {
            *d = project::normalize(*d);
        }
        let at = dirs.map(|d| d.map(|c| c * self.radius));
        let mut fbm = [0.0; LANES];
        self.fbm.sample_batch(&at, &mut fbm);
        std::array::from_fn(|l| (dirs[l], fbm[l]))
    }

    /// A point's raw height from its fBm: the map type's, if the globe has one.
    fn shape(&self, p: Point, dir: Dir, fbm: f64) -> f32 {
        match &self.map_type {
            Some(map_type) => {
                let diamond = match p {
                    Spot::Diamond { d, .. } => Some(d),
                    _ => None,
                };
                map_type.apply(diamond, dir, fbm) as f32
            }
            None => fbm as f32,
        }
    }

    /// Up to `LANES` points finished ([`Finished`]), in order. `known` is a point's ring and
    /// tile when that tile alone holds it, if the caller knows them.
    pub(super) fn finish_batch(
        &self,
        points: &[Point],
        known: &[Option<(u32, GlobeTile)>],
    ) -> impl Iterator<Item = Finished> + use<> {
        let raw = self.directions_and_fbm_lanes(points);
        let mut out = [Finished::UNSET; LANES];
        for (l, ((&p, &known), o)) in points.iter().zip(known).zip(&mut out).enumerate() {
            let (dir, fbm) = raw[l];
            *o = self.finish(p, known, dir, self.shape(p, dir, fbm));
        }
        out.into_iter().take(points.len())
    }

    fn finish(&self, p: Point, known: Option<(u32, GlobeTile)>, dir: Dir, raw: f32) -> Finished {
        let mut tiles = [GlobeTile(0); 3];
        let (ring, len) = match known {
            Some((ring, tile)) => {
                tiles[0] = tile;
                (ring, 1)
            }
            None => {
                let holders = self.fine.holders(p);
                for (k, &t) in tiles.iter_mut().zip(holders.tiles()) {
                    *k = self.grid.id(t);
                }
                (holders.ring, holders.tiles().len())
            }
        };
        let tiles = &tiles[..len];
        let raw = self.edits.apply(tiles, raw);
        let mut kinds = [TileKind::Sea; 3];
        for (k, t) in kinds.iter_mut().zip(tiles) {
            *k = self.kinds[t.0 as usize];
        }
        let span = span(&kinds[..len]);
        let height = if self.config.manipulation.any() {
            let n = self.config.subdivisions();
            manipulate(&self.thresholds, &self.config.manipulation, raw, ring, n, span).height
        } else {
            raw
        };
        let r = self.radius() + f64::from(height) * f64::from(self.config.terrain.max_elevation);
        let color = self.config.climate.enabled.then(|| {
            let mut biomes = [Biome::Ocean; 3];
            for (b, t) in biomes.iter_mut().zip(tiles) {
                *b = self.biomes[t.0 as usize];
            }
            vertex_color(&biomes[..len], 0.0)
        });
        Finished { height, ring, kind: span.map_or(TileKind::Sea, |(_, hi)| hi), position: dir.map(|c| c * r), color }
    }
}
