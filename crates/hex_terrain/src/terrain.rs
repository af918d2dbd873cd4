//! [`Terrain`]: a validated config compiled into pure functions of position. This file builds it
//! and answers what a tile is; heights ([`crate::heights`]), manipulation
//! ([`crate::manipulate`]), surface queries ([`crate::query`]), chunk maths ([`crate::chunk`])
//! and mesh generation ([`crate::mesh`]) add their methods in their own files.

use hexx::{Hex, HexLayout, HexOrientation, OffsetHexMode, Vec2};
use serde::{Deserialize, Serialize};

use std::sync::Arc;

use crate::chunk::TileRect;
use crate::climate::{Biome, ClimateFields, TileTable};
use crate::config::{HeightSourceConfig, MapConfig, MapSize, Orientation, Shape};
use crate::error::ConfigError;
use crate::heights::{Fbm, HeightImage, ShapeBounds};
use crate::kind::{Thresholds, TileKind};
use crate::lattice::Lattice;
use crate::wrap::Wrap;

/// Offset-coordinate convention of the map's rectangles (hexx's odd columns/rows shoved).
pub const OFFSET_MODE: OffsetHexMode = OffsetHexMode::Odd;

/// What a game needs to know about one tile.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct TileInfo {
    /// Axial coordinate, map-local (the map's first tile is `Hex::ZERO`).
    pub hex: Hex,
    /// Type by center height.
    pub kind: TileKind,
    /// World height of the tile's center on the manipulated surface.
    pub elevation: f32,
    /// Whether the tile belongs to the map (always true for an unbounded world).
    pub in_map: bool,
    /// Biome (from the kind alone when the map has no climate).
    pub biome: Biome,
    /// Water a river on the tile carries, 0 without a river.
    pub river_flow: f32,
    /// The lake the tile belongs to, if it is a lake tile.
    pub lake: Option<u32>,
}

/// A map config compiled into pure functions of position. Cheap to share between threads.
///
/// ```
/// use hex_terrain::{MapConfig, Terrain, TileKind};
///
/// let terrain = Terrain::new(MapConfig::default()).unwrap();
/// let tile = terrain.tile_at(3.0, 2.0);
/// let info = terrain.tile_info(tile);
/// let (lo, hi) = terrain.thresholds().range(info.kind);
/// let max = terrain.config().terrain.max_elevation;
/// assert!(info.elevation >= lo * max - 1e-4 && info.elevation <= hi * max + 1e-4);
/// ```
#[derive(Debug, Clone)]
pub struct Terrain {
    pub(crate) config: MapConfig,
    pub(crate) fbm: Fbm,
    pub(crate) lattice: Lattice,
    pub(crate) layout: HexLayout,
    pub(crate) origin_lattice: Hex,
    pub(crate) bounds: Option<TileRect>,
    /// The period of an east-west wrapping map.
    pub(crate) wrap: Option<Wrap>,
    pub(crate) shape_bounds: Option<ShapeBounds>,
    /// Whether a shaping filter changes heights (a bounded map with a shape other than `None`).
    pub(crate) shaping: bool,
    pub(crate) thresholds: Thresholds,
    pub(crate) image: Option<(Arc<HeightImage>, f64)>,
    /// The climate's noise fields, when the map has a climate.
    pub(crate) climate: Option<ClimateFields>,
    /// Per-tile data of a bounded map with climate or rivers, computed once.
    pub(crate) table: Option<Arc<TileTable>>,
}

impl Terrain {
    /// Validates `config` and prepares the generator.
    ///
    /// # Errors
    /// The first invalid field of the config.
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
        Self::with_image(config, image)
    }

    /// Like [`Terrain::new`], with the heightmap of an `Image` source already decoded (from an
    /// asset, say); `image` is ignored for a `Noise` source.
    ///
    /// # Errors
    /// The first invalid field of the config, or `source.path` when an `Image` source has no
    /// image.
    pub fn with_image(config: MapConfig, image: Option<Arc<HeightImage>>) -> Result<Self, ConfigError> {
        config.validate()?;
        let image = match &config.source {
            HeightSourceConfig::Noise => None,
            HeightSourceConfig::Image { path, sea_level } => Some((
                image.ok_or_else(|| {
                    ConfigError::new("source.path", format!("{path:?}"), "a decoded heightmap image".into())
                })?,
                f64::from(*sea_level),
            )),
        };
        let lattice = Lattice::new(config.subdivisions(), config.layout.orientation, config.layout.hex_size);
        let orientation = hex_orientation(config.layout.orientation);
        let layout = HexLayout { orientation, origin: Vec2::ZERO, scale: Vec2::splat(config.layout.hex_size) };
        let origin_tile = Hex::from_offset_coordinates([config.offset.0, config.offset.1], OFFSET_MODE, orientation);
        let origin_lattice = lattice.tile_center(origin_tile);
        let bounds = config.size.bounds().map(|(x, z)| TileRect::new([0, 0], [x, z]));
        let wrap = bounds.filter(|_| config.wrap).map(|b| Wrap::new(&lattice, b.max[0], config.chunk_size.0));
        let fbm = match &wrap {
            Some(w) => Fbm::wrapped(config.seed, &config.noise, w.width / f64::from(config.layout.hex_size)),
            None => Fbm::new(config.seed, &config.noise),
        };
        let mut terrain = Self {
            fbm,
            wrap,
            thresholds: Thresholds::new(&config.terrain, &config.manipulation),
            config,
            lattice,
            layout,
            origin_lattice,
            bounds,
            shape_bounds: None,
            shaping: false,
            image,
            climate: None,
            table: None,
        };
        terrain.shape_bounds = bounds.map(|rect| {
            let (mut min_x, mut max_x, mut min_z, mut max_z) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
            let corners = [
                rect.min,
                [rect.max[0] - 1, rect.min[1]],
                [rect.min[0], rect.max[1] - 1],
                [rect.max[0] - 1, rect.max[1] - 1],
            ];
            // Both parities of the first and last columns/rows, so the zig-zag is covered.
            for [c, r] in corners {
                for (dc, dr) in [(0, 0), (1, 0), (-1, 0), (0, 1), (0, -1)] {
                    let oc = [c + dc, r + dr];
                    if rect.contains(oc) {
                        let [x, z] = terrain.lattice.world(terrain.lattice.tile_center(terrain.tile_from_offset(oc)));
                        min_x = min_x.min(x);
                        max_x = max_x.max(x);
                        min_z = min_z.min(z);
                        max_z = max_z.max(z);
                    }
                }
            }
            let step = terrain.lattice.steps().0[0].abs().max(terrain.lattice.steps().1[0].abs());
            let min_u = if max_x > min_x { step / (max_x - min_x) } else { 1.0 };
            ShapeBounds { min_x, max_x, min_z, max_z, min_u }
        });
        terrain.shaping = terrain.shape_bounds.is_some() && terrain.config.shape != Shape::None;
        if terrain.config.climate.enabled {
            let wrap_width = terrain.wrap.map(|w| w.width / f64::from(terrain.config.layout.hex_size));
            terrain.climate = Some(ClimateFields::new(&terrain.config, wrap_width));
        }
        // Rivers need the whole map's table; a climate alone uses it on maps up to the size
        // rivers allow, and computes biomes chunk by chunk on larger ones.
        let tiles = bounds.map_or(u64::MAX, |b| b.len() as u64);
        if let Some(rect) = bounds
            && (terrain.config.rivers.enabled
                || (terrain.config.climate.enabled && tiles <= crate::config::MAX_WATER_TILES))
        {
            terrain.table = Some(Arc::new(TileTable::build(&terrain, rect)));
        }
        Ok(terrain)
    }

    /// The config it was built from.
    #[must_use]
    pub fn config(&self) -> &MapConfig {
        &self.config
    }

    /// The vertex lattice.
    #[must_use]
    pub fn lattice(&self) -> &Lattice {
        &self.lattice
    }

    /// Thresholds and type ranges in effect.
    #[must_use]
    pub fn thresholds(&self) -> &Thresholds {
        &self.thresholds
    }

    /// hexx layout of the tiles in world `(x, z)` (hexx's `y` is world `z`).
    #[must_use]
    pub fn layout(&self) -> &HexLayout {
        &self.layout
    }

    /// The fBm height source.
    #[must_use]
    pub fn fbm(&self) -> &Fbm {
        &self.fbm
    }

    /// The map's tiles in offset coordinates, `None` for an unbounded world.
    #[must_use]
    pub fn bounds(&self) -> Option<TileRect> {
        self.bounds
    }

    /// Tile at offset coordinate `[col, row]`.
    #[must_use]
    pub fn tile_from_offset(&self, offset: [i32; 2]) -> Hex {
        Hex::from_offset_coordinates(offset, OFFSET_MODE, self.layout.orientation)
    }

    /// Offset coordinate `[col, row]` of a tile.
    #[must_use]
    pub fn offset_of(&self, tile: Hex) -> [i32; 2] {
        tile.to_offset_coordinates(OFFSET_MODE, self.layout.orientation)
    }

    /// Whether a tile belongs to the map: on a wrapping map, every tile of the map's rows (a
    /// tile past the east or west edge is a tile of the map again, see [`Terrain::wrap_tile`]).
    #[must_use]
    pub fn contains(&self, tile: Hex) -> bool {
        match (self.bounds, &self.wrap) {
            (None, _) => true,
            (Some(b), Some(_)) => (b.min[1]..b.max[1]).contains(&self.offset_of(tile)[1]),
            (Some(b), None) => b.contains(self.offset_of(tile)),
        }
    }

    /// Every tile of a bounded map, row by row; empty for an unbounded world.
    pub fn tiles(&self) -> impl Iterator<Item = Hex> + '_ {
        self.bounds.into_iter().flat_map(|b| b.iter()).map(|oc| self.tile_from_offset(oc))
    }

    /// Type of a tile (by its center), whether or not it is in the map.
    #[must_use]
    pub fn tile_kind(&self, tile: Hex) -> TileKind {
        self.thresholds.classify(self.raw_height(self.lattice.tile_center(tile)))
    }

    /// Type of a tile if it belongs to the map.
    #[must_use]
    pub fn map_tile_kind(&self, tile: Hex) -> Option<TileKind> {
        self.contains(tile).then(|| self.tile_kind(tile))
    }

    /// Type, center elevation, membership, biome, river and lake of a tile.
    #[must_use]
    pub fn tile_info(&self, tile: Hex) -> TileInfo {
        let sample = self.vertex(self.lattice.tile_center(tile));
        self.info_of(tile, self.thresholds.classify(sample.raw), sample.height * self.config.terrain.max_elevation)
    }

    /// A tile's info from its kind and center elevation.
    pub(crate) fn info_of(&self, tile: Hex, kind: TileKind, elevation: f32) -> TileInfo {
        TileInfo {
            hex: tile,
            kind,
            elevation,
            in_map: self.contains(tile),
            biome: self.tile_biome(tile),
            river_flow: self.river(tile).map_or(0.0, |r| r.flow),
            lake: self.lake(tile),
        }
    }

    /// Whether a world is unbounded.
    #[must_use]
    pub fn is_unbounded(&self) -> bool {
        self.config.size == MapSize::Unbounded
    }
}

/// hexx orientation of a config orientation.
#[must_use]
pub fn hex_orientation(orientation: Orientation) -> HexOrientation {
    match orientation {
        Orientation::Flat => HexOrientation::Flat,
        Orientation::Pointy => HexOrientation::Pointy,
    }
}

#[cfg(test)]
mod tests;
