//! Geometry, the first stage: where tiles and lattice points are. The lattice and the hexx layout,
//! the map's bounds and its wrap, the offset of its first tile in the world, the chunking, and the
//! lookups between world positions, tiles, offsets and chunks. Every later stage asks it where
//! a point is and which copy of a point on a wrapping map is the canonical one.

use hexx::{Hex, HexLayout, HexOrientation, OffsetHexMode, Vec2};

use crate::chunk::{ChunkCoord, TileRect};
use crate::config::{MAX_WORLD_TILE, MapConfig, Orientation};
use crate::lattice::{Lattice, cube_round};
use crate::wrap::Wrap;

/// Offset-coordinate convention of the map's rectangles (hexx's odd columns/rows shoved).
pub const OFFSET_MODE: OffsetHexMode = OffsetHexMode::Odd;

const SQRT_3: f64 = 1.732_050_807_568_877_2;

/// hexx orientation of a config orientation.
#[must_use]
pub fn hex_orientation(orientation: Orientation) -> HexOrientation {
    match orientation {
        Orientation::Flat => HexOrientation::Flat,
        Orientation::Pointy => HexOrientation::Pointy,
    }
}

/// The geometry of a map: lattice, layout, bounds, wrap and chunking.
#[derive(Debug, Clone)]
pub struct Geometry {
    lattice: Lattice,
    layout: HexLayout,
    /// The lattice point of the map's first tile in the world (the config's `offset`).
    origin_lattice: Hex,
    bounds: Option<TileRect>,
    wrap: Option<Wrap>,
    chunk_size: (u32, u32),
    hex_size: f64,
}

impl Geometry {
    /// The geometry of a (validated) config.
    #[must_use]
    pub fn new(config: &MapConfig) -> Self {
        let lattice = Lattice::new(config.subdivisions(), config.layout.orientation, config.layout.hex_size);
        let orientation = hex_orientation(config.layout.orientation);
        let layout = HexLayout { orientation, origin: Vec2::ZERO, scale: Vec2::splat(config.layout.hex_size) };
        let origin_tile = Hex::from_offset_coordinates([config.offset.0, config.offset.1], OFFSET_MODE, orientation);
        let origin_lattice = lattice.tile_center(origin_tile);
        let bounds = config.size.bounds().map(|(x, z)| TileRect::new([0, 0], [x, z]));
        let wrap = bounds.filter(|_| config.wrap).map(|b| Wrap::new(&lattice, b.max[0], config.chunk_size.0));
        Self {
            lattice,
            layout,
            origin_lattice,
            bounds,
            wrap,
            chunk_size: config.chunk_size,
            hex_size: f64::from(config.layout.hex_size),
        }
    }

    /// The vertex lattice.
    #[must_use]
    pub fn lattice(&self) -> &Lattice {
        &self.lattice
    }

    /// hexx layout of the tiles in world `(x, z)` (hexx's `y` is world `z`).
    #[must_use]
    pub fn layout(&self) -> &HexLayout {
        &self.layout
    }

    /// Hex radius in world units.
    #[must_use]
    pub fn hex_size(&self) -> f64 {
        self.hex_size
    }

    /// World length of one lattice step.
    #[must_use]
    pub fn step(&self) -> f64 {
        self.hex_size / f64::from(self.lattice.subdivisions())
    }

    /// The lattice point of the map's first tile in the world: the map's offset.
    #[must_use]
    pub fn origin_lattice(&self) -> Hex {
        self.origin_lattice
    }

    /// The map's tiles in offset coordinates, `None` for an unbounded world.
    #[must_use]
    pub fn bounds(&self) -> Option<TileRect> {
        self.bounds
    }

    /// The wrap of an east-west wrapping map, `None` otherwise.
    #[must_use]
    pub fn wrap(&self) -> Option<&Wrap> {
        self.wrap.as_ref()
    }

    /// Chunk size in tiles.
    #[must_use]
    pub fn chunk_size(&self) -> (u32, u32) {
        self.chunk_size
    }

    /// Tile at offset coordinate `[col, row]`.
    #[must_use]
    #[inline]
    pub fn tile_from_offset(&self, offset: [i32; 2]) -> Hex {
        Hex::from_offset_coordinates(offset, OFFSET_MODE, self.layout.orientation)
    }

    /// Offset coordinate `[col, row]` of a tile (for a tile past the world, see
    /// [`Geometry::in_world`], the nearest coordinate `i32` holds).
    #[must_use]
    #[inline]
    pub fn offset_of(&self, tile: Hex) -> [i32; 2] {
        self.wide_offset(tile).map(|v| v.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32)
    }

    /// Offset coordinate of any tile, exact (hexx's conversion overflows near `i32::MAX`).
    #[inline]
    fn wide_offset(&self, tile: Hex) -> [i64; 2] {
        let (x, y) = (i64::from(tile.x), i64::from(tile.y));
        match self.layout.orientation {
            HexOrientation::Flat => [x, y + (x - (x & 1)) / 2],
            HexOrientation::Pointy => [x + (y - (y & 1)) / 2, y],
        }
    }

    /// Whether a tile is in the world: its offset column and row in
    /// `-MAX_WORLD_TILE..MAX_WORLD_TILE` ([`MAX_WORLD_TILE`]). Every tile of a bounded map is,
    /// and every tile a position of a wrapping map stands for. The queries answer `None` for the
    /// tiles past it: they have no chunk, and their lattice coordinates would not fit `i32`.
    #[must_use]
    #[inline]
    pub fn in_world(&self, tile: Hex) -> bool {
        let m = i64::from(MAX_WORLD_TILE);
        self.wide_offset(tile).iter().all(|c| (-m..m).contains(c))
    }

    /// Whether a lattice point is in the world: the tile nearest it is
    /// ([`Geometry::in_world`]). Computed in f64, so any point answers.
    #[must_use]
    pub fn point_in_world(&self, p: Hex) -> bool {
        let [q, r] = self.lattice.fract_tile(p);
        self.in_world(cube_round(q, r))
    }

    /// Whether a tile belongs to the map: on a wrapping map, every tile of the map's rows (a
    /// tile past the east or west edge is a tile of the map again, see [`Geometry::wrap_tile`])
    /// within the world; on an unbounded map, every tile of the world ([`Geometry::in_world`]).
    #[must_use]
    #[inline]
    pub fn contains(&self, tile: Hex) -> bool {
        match (self.bounds, &self.wrap) {
            (None, _) => self.in_world(tile),
            (Some(b), Some(_)) => (b.min[1]..b.max[1]).contains(&self.offset_of(tile)[1]) && self.in_world(tile),
            (Some(b), None) => b.contains(self.offset_of(tile)),
        }
    }

    /// Every tile of a bounded map, row by row; empty for an unbounded world.
    pub fn tiles(&self) -> impl Iterator<Item = Hex> + '_ {
        self.bounds.into_iter().flat_map(|b| b.iter()).map(|oc| self.tile_from_offset(oc))
    }

    /// The tile of the map a tile stands for: on a wrapping map, the tile of the same row whose
    /// column is the tile's column modulo the width; the tile itself otherwise.
    #[must_use]
    #[inline]
    pub fn wrap_tile(&self, tile: Hex) -> Hex {
        match &self.wrap {
            Some(_) if !self.in_world(tile) => tile,
            Some(w) => {
                let k = w.tile_period(self.offset_of(tile)[0]);
                if k == 0 { tile } else { tile - w.tile_shift * k }
            }
            None => tile,
        }
    }

    /// The canonical lattice point of a lattice point (itself unless the map wraps, and for a
    /// point past the world).
    #[must_use]
    #[inline]
    pub fn wrap_point(&self, p: Hex) -> Hex {
        match &self.wrap {
            // Lattice points of the world are within 2^30 (see `in_world`); past it the shift
            // could overflow, and there is no map to wrap into.
            Some(w) if p.x.unsigned_abs() < 1 << 30 && p.y.unsigned_abs() < 1 << 30 => w.point(p),
            _ => p,
        }
    }

    /// The chunk of the map a chunk stands for (itself unless the map wraps), and how many
    /// periods east of it the chunk is placed.
    #[must_use]
    pub fn wrap_chunk(&self, chunk: ChunkCoord) -> (ChunkCoord, i32) {
        self.wrap.as_ref().map_or((chunk, 0), |w| w.chunk(chunk))
    }

    /// Hex distance between two tiles, the short way round on a wrapping map; `None` when
    /// either is past the world ([`Geometry::in_world`]).
    #[must_use]
    pub fn distance(&self, a: Hex, b: Hex) -> Option<u32> {
        if !self.in_world(a) || !self.in_world(b) {
            return None;
        }
        let (a, b) = (self.wrap_tile(a), self.wrap_tile(b));
        match &self.wrap {
            Some(w) => [-1, 0, 1].iter().map(|&k| a.unsigned_distance_to(b + w.tile_shift * k)).min(),
            None => Some(a.unsigned_distance_to(b)),
        }
    }

    /// The copy of a tile nearest another tile: on a wrapping map, of the tile and the tiles a
    /// whole number of map widths east or west of it, the one nearest `near`; the tile itself
    /// otherwise (and for tiles past the world).
    #[must_use]
    pub fn tile_near(&self, tile: Hex, near: Hex) -> Hex {
        let Some(w) = &self.wrap else { return tile };
        if !self.in_world(tile) || !self.in_world(near) {
            return tile;
        }
        let tile = self.wrap_tile(tile);
        let k = w.tile_period(self.offset_of(near)[0]);
        (k - 1..=k + 1).map(|k| tile + w.tile_shift * k).min_by_key(|t| t.unsigned_distance_to(near)).unwrap_or(tile)
    }

    /// The six neighbors of a tile, each wrapped into the map on a wrapping map; `None` for a
    /// tile past the world ([`Geometry::in_world`]).
    #[must_use]
    pub fn neighbors(&self, tile: Hex) -> Option<[Hex; 6]> {
        self.in_world(tile).then(|| tile.all_neighbors().map(|nb| self.wrap_tile(nb)))
    }

    /// The six neighbors of a tile of the world, wrapped (for the stages, which only ask about
    /// tiles of the map).
    #[inline]
    pub(crate) fn wrapped_neighbors(&self, tile: Hex) -> [Hex; 6] {
        tile.all_neighbors().map(|nb| self.wrap_tile(nb))
    }

    /// The tile under world `(x, z)` of the plane, not wrapped; `None` past the world (or for a
    /// position that is not finite).
    #[must_use]
    pub fn unwrapped_tile_at(&self, x: f64, z: f64) -> Option<Hex> {
        // Axial coordinates and cube rounding in f64 (hexx's layout works in f32, which loses
        // whole tiles far out).
        let s = self.hex_size;
        let (q, r) = match self.lattice.orientation() {
            Orientation::Flat => (2.0 / 3.0 * x / s, (-x / 3.0 + SQRT_3 / 3.0 * z) / s),
            Orientation::Pointy => ((SQRT_3 / 3.0 * x - z / 3.0) / s, 2.0 / 3.0 * z / s),
        };
        // Far enough past the world to be out, near enough for `i32`; NaN is out too.
        let limit = 4.0 * f64::from(MAX_WORLD_TILE);
        if !(q.abs() < limit && r.abs() < limit) {
            return None;
        }
        let tile = cube_round(q, r);
        self.in_world(tile).then_some(tile)
    }

    /// The position of the map's own copy of world `(x, z)`: on a wrapping map, `x` reduced to
    /// one period (exactly: the remainder of a float division has no rounding error), so every
    /// finite position east or west answers with the map's tile; `(x, z)` itself otherwise.
    #[must_use]
    #[inline]
    pub fn wrap_position(&self, x: f64, z: f64) -> (f64, f64) {
        match &self.wrap {
            Some(w) if x.is_finite() => (x % w.width, z),
            _ => (x, z),
        }
    }

    /// The tile under world `(x, z)` (the map's own tile on a wrapping map, for any finite
    /// `x`); `None` past the world.
    #[must_use]
    pub fn tile_at(&self, x: f64, z: f64) -> Option<Hex> {
        let (x, z) = self.wrap_position(x, z);
        self.unwrapped_tile_at(x, z).map(|t| self.wrap_tile(t))
    }

    /// The chunk holding a tile. On a wrapping map, a tile past the map's east or west edge is
    /// in a chunk placed there (see `crate::wrap`).
    #[must_use]
    pub fn chunk_of(&self, tile: Hex) -> ChunkCoord {
        match &self.wrap {
            // Past the world: a chunk past it too, which has no tiles.
            _ if !self.in_world(tile) => {
                let [col, row] = self.wide_offset(tile);
                let (w, h) = (i64::from(self.chunk_size.0), i64::from(self.chunk_size.1));
                let fit = |v: i64| v.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32;
                ChunkCoord::new(fit(col.div_euclid(w)), fit(row.div_euclid(h)))
            }
            Some(w) => w.chunk_of(self.offset_of(tile), self.chunk_size.1),
            None => ChunkCoord::of(self.offset_of(tile), self.chunk_size),
        }
    }

    /// A chunk's tiles clipped to the map, `None` when it lies outside (or, on an unbounded
    /// world, past [`MAX_WORLD_TILE`]). On a wrapping map, the tiles of the map's chunk it
    /// stands for ([`Geometry::wrap_chunk`]).
    #[must_use]
    pub fn chunk_rect(&self, chunk: ChunkCoord) -> Option<TileRect> {
        let (chunk, _) = self.wrap_chunk(chunk);
        let (w, h) = (i64::from(self.chunk_size.0), i64::from(self.chunk_size.1));
        let far = i64::from(MAX_WORLD_TILE) + w.max(h);
        if (i64::from(chunk.x) * w).abs() > far || (i64::from(chunk.z) * h).abs() > far {
            return None;
        }
        let rect = chunk.rect(self.chunk_size);
        let world = TileRect { min: [-MAX_WORLD_TILE; 2], max: [MAX_WORLD_TILE; 2] };
        let rect = rect.intersect(&self.bounds.unwrap_or(world));
        (!rect.is_empty()).then_some(rect)
    }

    /// The lattice point a rectangle's mesh positions are relative to: the center of its first
    /// tile.
    #[must_use]
    pub fn rect_origin(&self, rect: TileRect) -> Hex {
        self.lattice.tile_center(self.tile_from_offset(rect.min))
    }

    /// How far, in world units, a horizontal vertex position of a mesh of `rect` can lie from
    /// its exact place once brought into the world frame in f64 (mesh origin plus position):
    /// positions are f32 relative to the origin ([`Geometry::rect_origin`]), so the bound is
    /// half an f32 ulp of the farthest vertex from it, per axis, plus the f64 rounding of the
    /// sum. It grows with the rectangle's extent, not with its distance from the world's
    /// origin. Two copies of a vertex shared by meshes of `a` and `b` agree within
    /// `position_error(a) + position_error(b)`. Divide by [`Geometry::step`] for lattice steps,
    /// the unit the docs quote it in.
    #[must_use]
    pub fn position_error(&self, rect: TileRect) -> f64 {
        let Some((rx, rz, o)) = self.reach(rect) else { return 0.0 };
        Self::error_of(rx, rz, o)
    }

    /// The bound of [`Geometry::position_error`] from the reach of the vertices from the origin
    /// per axis and the origin's distance from the world's origin.
    fn error_of(rx: f64, rz: f64, origin: f64) -> f64 {
        let half_ulp = |r: f64| if r > 0.0 { (r.log2().floor() - 24.0).exp2() } else { 0.0 };
        half_ulp(rx).hypot(half_ulp(rz)) + 4.0 * f64::EPSILON * (origin + rx.max(rz))
    }

    /// How far a mesh of `rect`'s vertices reach from its origin in x and z, and the origin's
    /// largest coordinate; `None` for an empty rectangle.
    fn reach(&self, rect: TileRect) -> Option<(f64, f64, f64)> {
        if rect.is_empty() {
            return None;
        }
        let origin = self.rect_origin(rect);
        let (mut rx, mut rz) = (0.0_f64, 0.0_f64);
        // The farthest vertices belong to tiles on the rectangle's edge; every vertex of a tile
        // lies within a hex radius of its center.
        let [c0, r0] = rect.min;
        let [c1, r1] = [rect.max[0] - 1, rect.max[1] - 1];
        let edge = (c0..=c1).flat_map(|c| [[c, r0], [c, r1]]).chain((r0..=r1).flat_map(|r| [[c0, r], [c1, r]]));
        for oc in edge {
            let [x, z] = self.lattice.world(self.lattice.tile_center(self.tile_from_offset(oc)) - origin);
            rx = rx.max(x.abs() + self.hex_size);
            rz = rz.max(z.abs() + self.hex_size);
        }
        let [ox, oz] = self.lattice.world(origin);
        Some((rx, rz, ox.abs().max(oz.abs())))
    }

    /// The largest [`Geometry::position_error`] of a chunk of this geometry (a chunk's tiles,
    /// clipped to the map, anywhere in the world), in world units (divide by [`Geometry::step`]
    /// for lattice steps). A wrapping map's chunk placed
    /// periods east adds `2^-50` of its distance from the world's origin.
    #[must_use]
    pub fn chunk_position_error(&self) -> f64 {
        // Odd columns and rows are shoved, so a chunk's shape depends on the parity of its
        // first column and row; the farthest origin adds the f64 rounding of the sum.
        let [x, z] = self.lattice.world(self.lattice.tile_center(self.tile_from_offset([MAX_WORLD_TILE; 2])));
        let far = x.abs().max(z.abs());
        [[0, 0], [1, 0], [0, 1], [1, 1]]
            .into_iter()
            .filter_map(|min| self.reach(TileRect::new(min, [self.chunk_size.0, self.chunk_size.1])))
            .map(|(rx, rz, _)| Self::error_of(rx, rz, far))
            .fold(0.0, f64::max)
    }

    /// World position `[x, y, z]` (computed in f64) of the origin of a chunk's mesh: where its
    /// entity goes. On a wrapping map, a chunk placed a period east is the same mesh one map
    /// width further east.
    #[must_use]
    pub fn chunk_origin(&self, chunk: ChunkCoord) -> Option<[f64; 3]> {
        let rect = self.chunk_rect(chunk)?;
        let [x, z] = self.lattice.world(self.rect_origin(rect));
        let shift = self.wrap.as_ref().map_or(0.0, |w| w.width * f64::from(self.wrap_chunk(chunk).1));
        Some([x + shift, 0.0, z])
    }

    /// Every chunk of a bounded map; empty for an unbounded world.
    #[must_use]
    pub fn chunks(&self) -> Vec<ChunkCoord> {
        let Some(b) = self.bounds else { return Vec::new() };
        let (w, h) = (self.chunk_size.0 as i32, self.chunk_size.1 as i32);
        let (cx, cz) = ((b.max[0] + w - 1) / w, (b.max[1] + h - 1) / h);
        (0..cz).flat_map(|z| (0..cx).map(move |x| ChunkCoord::new(x, z))).collect()
    }
}
