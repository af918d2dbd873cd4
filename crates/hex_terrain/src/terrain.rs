//! [`Terrain`]: a validated config turned into pure functions of position: heights, tile types,
//! world <-> tile conversion and surface queries.

use hexx::{Hex, HexLayout, HexOrientation, OffsetHexMode, Vec2};
use serde::{Deserialize, Serialize};

use crate::chunk::{ChunkCoord, TileRect};
use crate::classify::{Manipulated, Thresholds, TileKind, manipulate};
use std::sync::Arc;

use crate::config::{HeightSourceConfig, MapConfig, MapSize, Orientation, Shape};
use crate::error::ConfigError;
use crate::image_source::{HeightImage, remap_sea_level};
use crate::lattice::Lattice;
use crate::noise::Fbm;
use crate::shape::{self, ShapeBounds};

/// Offset-coordinate convention of the map's rectangles (hexx's odd columns/rows shoved).
pub const OFFSET_MODE: OffsetHexMode = OffsetHexMode::Odd;

/// What a game needs to know about one tile.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TileInfo {
    /// Axial coordinate, map-local (the map's first tile is `Hex::ZERO`).
    pub hex: Hex,
    /// Type by centre height.
    pub kind: TileKind,
    /// World height of the tile's centre on the manipulated surface.
    pub elevation: f32,
    /// Whether the tile belongs to the map (always true for an unbounded world).
    pub in_map: bool,
}

/// One lattice vertex, evaluated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VertexSample {
    /// Normalised height after shaping, before manipulation.
    pub raw: f32,
    /// Normalised height after manipulation.
    pub height: f32,
    /// Whether hex unity or edge/corner correction moved it.
    pub moved: bool,
    /// Ring in its tile (`n` on a border).
    pub ring: u32,
    /// Highest kind among the in-map tiles sharing it, or its height's kind outside the map.
    pub kind: TileKind,
}

/// A ray hitting the terrain surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayHit {
    /// World position of the hit.
    pub point: [f32; 3],
    /// Distance along the (normalised) ray.
    pub distance: f32,
    /// The tile under the hit.
    pub tile: Hex,
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
    config: MapConfig,
    fbm: Fbm,
    lattice: Lattice,
    layout: HexLayout,
    origin_lattice: Hex,
    bounds: Option<TileRect>,
    shape_bounds: Option<ShapeBounds>,
    /// Whether a shaping filter changes heights (a bounded map with a shape other than `None`).
    shaping: bool,
    thresholds: Thresholds,
    image: Option<(Arc<HeightImage>, f64)>,
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
        let origin_lattice = lattice.tile_centre(origin_tile);
        let bounds = config.size.bounds().map(|(x, z)| TileRect::new([0, 0], [x, z]));
        let mut terrain = Self {
            fbm: Fbm::new(config.seed, &config.noise),
            thresholds: Thresholds::new(&config.terrain, &config.manipulation),
            config,
            lattice,
            layout,
            origin_lattice,
            bounds,
            shape_bounds: None,
            shaping: false,
            image,
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
                        let [x, z] = terrain.lattice.world(terrain.lattice.tile_centre(terrain.tile_from_offset(oc)));
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

    /// Whether a tile belongs to the map.
    #[must_use]
    pub fn contains(&self, tile: Hex) -> bool {
        self.bounds.is_none_or(|b| b.contains(self.offset_of(tile)))
    }

    /// Every tile of a bounded map, row by row; empty for an unbounded world.
    pub fn tiles(&self) -> impl Iterator<Item = Hex> + '_ {
        self.bounds.into_iter().flat_map(|b| b.iter()).map(|oc| self.tile_from_offset(oc))
    }

    /// Normalised height after shaping, before manipulation, at a lattice point.
    #[must_use]
    #[inline]
    pub fn raw_height(&self, p: Hex) -> f32 {
        self.shaped(self.noise_height(p), p)
    }

    /// Applies the shaping filter to a bare noise height at lattice point `p`.
    #[inline]
    pub(crate) fn shaped(&self, noise: f64, p: Hex) -> f32 {
        if self.shaping {
            let [x, z] = self.lattice.world(p);
            shape::apply(&self.config.shape, self.shape_bounds.as_ref(), noise, x, z) as f32
        } else {
            noise as f32
        }
    }

    /// Bare fBm height (no shaping) at a lattice point.
    #[must_use]
    #[inline]
    pub fn noise_height(&self, p: Hex) -> f64 {
        if let Some((image, sea_level)) = &self.image {
            return self.image_height(image, *sea_level, p);
        }
        let [ux, uz] = self.noise_position(p);
        self.fbm.sample(ux, uz)
    }

    /// Whether heights come from fBm (rather than a heightmap image).
    pub(crate) fn samples_noise(&self) -> bool {
        self.image.is_none()
    }

    /// Heights of many lattice points from the height source (batched for the noise).
    pub(crate) fn base_heights(&self, points: &[Hex], out: &mut [f64]) {
        if let Some((image, sea_level)) = &self.image {
            for (p, o) in points.iter().zip(out) {
                *o = self.image_height(image, *sea_level, *p);
            }
        } else {
            const STEP: usize = 256;
            let mut positions = [[0.0; 2]; STEP];
            for (points, out) in points.chunks(STEP).zip(out.chunks_mut(STEP)) {
                for (position, &p) in positions.iter_mut().zip(points) {
                    *position = self.noise_position(p);
                }
                self.fbm.sample_many(&positions[..points.len()], out);
            }
        }
    }

    fn image_height(&self, image: &HeightImage, sea_level: f64, p: Hex) -> f64 {
        let [x, z] = self.lattice.world(p);
        let (u, v) = self.shape_bounds.map_or((0.5, 0.5), |b| b.normalise(x, z));
        remap_sea_level(image.sample(u, v), sea_level, f64::from(self.config.terrain.sea_threshold))
    }

    /// Where a lattice point samples the noise: its world position in hex radii, shifted by the
    /// map's offset.
    #[must_use]
    #[inline]
    pub fn noise_position(&self, p: Hex) -> [f64; 2] {
        self.lattice.unit(p + self.origin_lattice)
    }

    /// Type of a tile (by its centre), whether or not it is in the map.
    #[must_use]
    pub fn tile_kind(&self, tile: Hex) -> TileKind {
        self.thresholds.classify(self.raw_height(self.lattice.tile_centre(tile)))
    }

    /// Type of a tile if it belongs to the map.
    #[must_use]
    pub fn map_tile_kind(&self, tile: Hex) -> Option<TileKind> {
        self.contains(tile).then(|| self.tile_kind(tile))
    }

    /// Type, centre elevation and membership of a tile.
    #[must_use]
    pub fn tile_info(&self, tile: Hex) -> TileInfo {
        let sample = self.vertex(self.lattice.tile_centre(tile));
        TileInfo {
            hex: tile,
            kind: self.thresholds.classify(sample.raw),
            elevation: sample.height * self.config.terrain.max_elevation,
            in_map: self.contains(tile),
        }
    }

    /// Evaluates one lattice vertex, computing the kinds of the tiles around it.
    #[must_use]
    pub fn vertex(&self, p: Hex) -> VertexSample {
        self.vertex_with(p, |tile| self.map_tile_kind(tile))
    }

    /// Evaluates one lattice vertex with tile kinds from `kind_of` (`None` outside the map).
    #[must_use]
    #[inline]
    pub fn vertex_with(&self, p: Hex, kind_of: impl Fn(Hex) -> Option<TileKind>) -> VertexSample {
        self.border_vertex(self.raw_height(p), p, kind_of)
    }

    /// Finishes a vertex whose raw height is known, finding the tiles around it.
    #[inline]
    pub(crate) fn border_vertex(&self, raw: f32, p: Hex, kind_of: impl Fn(Hex) -> Option<TileKind>) -> VertexSample {
        let set = self.lattice.tiles_at(p);
        let mut kinds = [TileKind::Sea; 3];
        let mut len = 0;
        for &tile in set.tiles() {
            if let Some(kind) = kind_of(tile) {
                kinds[len] = kind;
                len += 1;
            }
        }
        self.finish_vertex(raw, set.ring, &kinds[..len])
    }

    /// Applies manipulation to a vertex of raw height `raw` at `ring`, shared by the in-map
    /// tiles of `kinds`.
    #[inline(always)]
    pub(crate) fn finish_vertex(&self, raw: f32, ring: u32, kinds: &[TileKind]) -> VertexSample {
        let n = self.lattice.subdivisions();
        let Manipulated { height, moved } = if self.config.manipulation.any() {
            manipulate(&self.thresholds, &self.config.manipulation, raw, ring, n, kinds)
        } else {
            Manipulated { height: raw, moved: false }
        };
        let kind = kinds.iter().copied().max().unwrap_or_else(|| self.thresholds.classify(raw));
        VertexSample { raw, height, moved, ring, kind }
    }

    /// World height of the manipulated surface at a lattice point.
    #[must_use]
    pub fn vertex_elevation(&self, p: Hex) -> f32 {
        self.vertex(p).height * self.config.terrain.max_elevation
    }

    /// The tile under world `(x, z)`.
    #[must_use]
    pub fn tile_at(&self, x: f32, z: f32) -> Hex {
        self.layout.world_pos_to_hex(Vec2::new(x, z))
    }

    /// World position of a tile's centre on the surface.
    #[must_use]
    pub fn tile_centre(&self, tile: Hex) -> [f32; 3] {
        let p = self.lattice.tile_centre(tile);
        let [x, z] = self.lattice.world(p);
        [x as f32, self.vertex_elevation(p), z as f32]
    }

    /// World height of the surface (as meshed) at world `(x, z)`.
    #[must_use]
    pub fn surface_height(&self, x: f32, z: f32) -> f32 {
        let (tri, w) = self.lattice.triangle_at(f64::from(x), f64::from(z));
        let h: f64 = tri.iter().zip(w).map(|(&p, w)| w * f64::from(self.vertex_elevation(p))).sum();
        h as f32
    }

    /// First hit of a ray on the surface within `max_distance`, marching at a fraction of a
    /// lattice step and refining by bisection.
    #[must_use]
    pub fn raycast(&self, origin: [f32; 3], direction: [f32; 3], max_distance: f32) -> Option<RayHit> {
        let len = (direction[0].powi(2) + direction[1].powi(2) + direction[2].powi(2)).sqrt();
        if len.is_nan() || len <= 0.0 || !max_distance.is_finite() || origin.iter().any(|v| !v.is_finite()) {
            return None;
        }
        let d = direction.map(|v| v / len);
        let at = |t: f32| [origin[0] + d[0] * t, origin[1] + d[1] * t, origin[2] + d[2] * t];
        let above = |t: f32| {
            let p = at(t);
            p[1] - self.surface_height(p[0], p[2])
        };
        // Skip down to the highest possible surface quickly when looking from far above.
        let top = self.config.terrain.max_elevation;
        let mut t0 = 0.0;
        if origin[1] > top && d[1] < 0.0 {
            t0 = (origin[1] - top) / -d[1];
        }
        let step = (self.config.layout.hex_size / self.lattice.subdivisions() as f32 * 0.5).max(1e-4);
        let mut prev = above(t0);
        if prev < 0.0 {
            return None;
        }
        let mut t = t0;
        while t < max_distance {
            let next = (t + step).min(max_distance);
            let h = above(next);
            if h <= 0.0 {
                let (mut lo, mut hi) = (t, next);
                for _ in 0..24 {
                    let mid = 0.5 * (lo + hi);
                    if above(mid) > 0.0 { lo = mid } else { hi = mid }
                }
                let point = at(hi);
                return Some(RayHit { point, distance: hi, tile: self.tile_at(point[0], point[2]) });
            }
            prev = h;
            t = next;
            // A ray going up and already above every possible height never comes back.
            if d[1] >= 0.0 && at(t)[1] > top && prev > 0.0 {
                return None;
            }
        }
        None
    }

    /// Chunk size in tiles.
    #[must_use]
    pub fn chunk_size(&self) -> (u32, u32) {
        self.config.chunk_size
    }

    /// The chunk holding a tile.
    #[must_use]
    pub fn chunk_of(&self, tile: Hex) -> ChunkCoord {
        ChunkCoord::of(self.offset_of(tile), self.config.chunk_size)
    }

    /// A chunk's tiles clipped to the map, `None` when it lies outside.
    #[must_use]
    pub fn chunk_rect(&self, chunk: ChunkCoord) -> Option<TileRect> {
        let rect = chunk.rect(self.config.chunk_size);
        let rect = self.bounds.map_or(rect, |b| rect.intersect(&b));
        (!rect.is_empty()).then_some(rect)
    }

    /// Every chunk of a bounded map; empty for an unbounded world.
    #[must_use]
    pub fn chunks(&self) -> Vec<ChunkCoord> {
        let Some(b) = self.bounds else { return Vec::new() };
        let (w, h) = (self.config.chunk_size.0 as i32, self.config.chunk_size.1 as i32);
        let (cx, cz) = ((b.max[0] + w - 1) / w, (b.max[1] + h - 1) / h);
        (0..cz).flat_map(|z| (0..cx).map(move |x| ChunkCoord::new(x, z))).collect()
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
