//! The hex-in-hex lattice (thesis sections 5.3-5.4).
//!
//! Each hexagonal tile is cut into six triangles (center and two corners) and each of those into
//! `n * n` small triangles, where `n = inner_rings + 1`. The vertices at lattice distance `k`
//! from a tile's center form its ring `k`: ring 0 is the center, rings `1..n` the inner
//! hexagons, ring `n` the border (corners and edge vertices) shared with the neighbors. The
//! thesis' layout, one inner hexagon, is `n = 2`.
//!
//! Together the tiles form one regular triangular lattice over the whole plane, so every vertex
//! has an integer lattice coordinate, stored as a [`Hex`] of the *fine* lattice (its six lattice
//! neighbors are exactly hexx's six axial neighbors). A vertex shared by two or three tiles is
//! one lattice point, so it exists once per mesh, and two chunks computing it get the same bits.
//!
//! # Counts
//!
//! With `n = inner_rings + 1`, a tile holds `1 + 3n(n+1)` lattice points and `6n²` triangles.
//! In a tiling each edge vertex is shared by two tiles and each corner by three, so a map of
//! `T` tiles has `3n²` vertices per tile plus its outline: for a set of tiles whose union is
//! simply connected, `V = 3n²·T + n·E_b/2 + 1 + ...`; exactly, `V = 3n²·T + n·B / 2 + 1` where
//! `B` is the number of tile edges on the outline of the set (Euler's formula on the planar
//! lattice graph). [`Lattice::mesh_vertex_count`] evaluates it; the thesis layout (`n = 2`) has
//! 12 vertices and 24 triangles per tile in the limit, `n = 4` has 48 and 96.

use hexx::Hex;

use crate::config::Orientation;

const SQRT_3: f64 = 1.732_050_807_568_877_2;

/// A point of a tile's template: its offset from the tile center in lattice steps and its ring.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TemplatePoint {
    /// Offset from the center, as a fine-lattice coordinate.
    pub offset: Hex,
    /// Ring index: 0 at the center, `n` on the border.
    pub ring: u32,
}

/// Geometry of the fine triangular lattice for one subdivision count and orientation.
#[derive(Debug, Clone)]
pub struct Lattice {
    n: i32,
    orientation: Orientation,
    hex_size: f64,
    /// World vector of one step along the lattice's first axis.
    step_a: [f64; 2],
    /// World vector of one step along the lattice's second axis.
    step_b: [f64; 2],
    points: Vec<TemplatePoint>,
    triangles: Vec<[Hex; 3]>,
    /// `triangles` as indices into `points`.
    triangle_indices: Vec<[u16; 3]>,
    /// For each point of `points` on the border, the neighboring tiles sharing it (one on an
    /// edge, two on a corner) as indices into `Hex::all_neighbors`; `u8::MAX` when absent.
    shared_tiles: Vec<[u8; 2]>,
    /// For each point of `points` and each of the six [`NEIGHBORS`], the tiles (relative to
    /// the template's tile) holding that neighbor, and its ring.
    around_tiles: Vec<[TileSet; 6]>,
}

/// The six lattice directions around a point, counter-clockwise in lattice space.
pub const NEIGHBORS: [Hex; 6] =
    [Hex::new(1, 0), Hex::new(0, 1), Hex::new(-1, 1), Hex::new(-1, 0), Hex::new(0, -1), Hex::new(1, -1)];

impl Lattice {
    /// A lattice with `subdivisions` steps from a tile's center to its corners (at least 1).
    #[must_use]
    pub fn new(subdivisions: u32, orientation: Orientation, hex_size: f32) -> Self {
        let n = subdivisions.max(1) as i32;
        let e = f64::from(hex_size) / f64::from(n);
        let (step_a, step_b) = match orientation {
            // Corners at 0° and 60°.
            Orientation::Flat => ([e, 0.0], [e * 0.5, e * SQRT_3 * 0.5]),
            // Corners at 30° and 90°.
            Orientation::Pointy => ([e * SQRT_3 * 0.5, e * 0.5], [0.0, e]),
        };
        let mut points = Vec::with_capacity(1 + 3 * (n * (n + 1)) as usize);
        points.push(TemplatePoint { offset: Hex::ZERO, ring: 0 });
        for k in 1..=n as u32 {
            points.extend(Hex::ZERO.ring(k).map(|offset| TemplatePoint { offset, ring: k }));
        }
        let mut triangles = Vec::with_capacity(6 * (n * n) as usize);
        let inside = |h: Hex| h.ulength() <= n as u32;
        // A triangle's lowest corner may lie just outside the tile, so scan one ring further.
        for o in Hex::ZERO.range(n as u32 + 1) {
            let (a, b, ab) = (o + Hex::new(1, 0), o + Hex::new(0, 1), o + Hex::new(1, 1));
            // Wound so that the face normal points up (+y) with world z = lattice y.
            if inside(o) && inside(a) && inside(b) {
                triangles.push([o, b, a]);
            }
            if inside(a) && inside(b) && inside(ab) {
                triangles.push([a, b, ab]);
            }
        }
        let index_of = |h: Hex| points.iter().position(|p| p.offset == h).map_or(u16::MAX, |i| i as u16);
        let triangle_indices = triangles.iter().map(|t| t.map(index_of)).collect();
        let mut lattice = Self {
            n,
            orientation,
            hex_size: f64::from(hex_size),
            step_a,
            step_b,
            points,
            triangles,
            triangle_indices,
            shared_tiles: Vec::new(),
            around_tiles: Vec::new(),
        };
        // Tile centers are a linear function of tile coordinates, so the tiles sharing a border
        // point of any tile are that tile's neighbors in the same directions as for the origin.
        lattice.shared_tiles = lattice
            .points
            .iter()
            .map(|p| {
                let mut shared = [u8::MAX; 2];
                let set = lattice.tiles_at(p.offset);
                let others = set.tiles().iter().filter(|&&t| t != Hex::ZERO);
                for (slot, &tile) in shared.iter_mut().zip(others) {
                    let direction = Hex::ZERO.all_neighbors().iter().position(|&d| d == tile);
                    *slot = direction.map_or(u8::MAX, |d| d as u8);
                }
                shared
            })
            .collect();
        lattice.around_tiles =
            lattice.points.iter().map(|p| NEIGHBORS.map(|d| lattice.tiles_at(p.offset + d))).collect();
        lattice
    }

    /// The tiles (relative to the template's tile, to be added to a tile's coordinate) holding
    /// the lattice neighbor in direction `d` ([`NEIGHBORS`]) of template point `i`, and that
    /// neighbor's ring: what [`Lattice::tiles_at`] gives for it, found once for the origin tile.
    #[must_use]
    pub(crate) fn around_tiles(&self, i: usize, d: usize) -> &TileSet {
        &self.around_tiles[i][d]
    }

    /// For template point `i`, the neighboring tiles that share it besides the tile itself (none
    /// inside the tile, one on an edge, two on a corner), as indices into `Hex::all_neighbors`;
    /// `u8::MAX` marks an empty slot.
    #[must_use]
    pub(crate) fn shared_tiles(&self, i: usize) -> [u8; 2] {
        self.shared_tiles[i]
    }

    /// [`Lattice::template_triangles`] as indices into [`Lattice::template`].
    #[must_use]
    pub fn template_triangle_indices(&self) -> &[[u16; 3]] {
        &self.triangle_indices
    }

    /// Steps from center to corner, `inner_rings + 1`.
    #[must_use]
    pub fn subdivisions(&self) -> u32 {
        self.n as u32
    }

    /// Hexagon orientation.
    #[must_use]
    pub fn orientation(&self) -> Orientation {
        self.orientation
    }

    /// The tile template: every lattice point of one tile, center first, ring by ring.
    #[must_use]
    pub fn template(&self) -> &[TemplatePoint] {
        &self.points
    }

    /// The `6n²` triangles of one tile, as lattice offsets from its center.
    #[must_use]
    pub fn template_triangles(&self) -> &[[Hex; 3]] {
        &self.triangles
    }

    /// Lattice coordinate of a tile's center.
    #[must_use]
    pub fn tile_center(&self, tile: Hex) -> Hex {
        let n = self.n;
        match self.orientation {
            Orientation::Flat => Hex::new(n * (tile.x - tile.y), n * (tile.x + 2 * tile.y)),
            Orientation::Pointy => Hex::new(n * (2 * tile.x + tile.y), n * (tile.y - tile.x)),
        }
    }

    /// Fractional axial tile coordinates of a lattice point.
    pub(crate) fn fract_tile(&self, p: Hex) -> [f64; 2] {
        let (i, j) = (f64::from(p.x), f64::from(p.y));
        let d = 3.0 * f64::from(self.n);
        match self.orientation {
            Orientation::Flat => [(2.0 * i + j) / d, (j - i) / d],
            Orientation::Pointy => [(i - j) / d, (i + 2.0 * j) / d],
        }
    }

    /// The tiles containing a lattice point (1 inside a tile, 2 on an edge, 3 on a corner), and
    /// the point's ring in the first of them.
    #[must_use]
    pub fn tiles_at(&self, p: Hex) -> TileSet {
        // Cube rounding in f64: hexx's `Hex::round` takes f32, which loses whole lattice steps
        // beyond ~10^7 and would misplace far-away points of an unbounded world.
        let [q, r] = self.fract_tile(p);
        let first = cube_round(q, r);
        let ring = p.distance_to(self.tile_center(first)) as u32;
        let mut set = TileSet { tiles: [first; 3], len: 1, ring };
        if ring >= self.n as u32 {
            for neighbor in first.all_neighbors() {
                if p.distance_to(self.tile_center(neighbor)) <= self.n && set.len < 3 {
                    set.tiles[set.len] = neighbor;
                    set.len += 1;
                }
            }
        }
        set
    }

    /// World `(x, z)` of a lattice point.
    #[must_use]
    pub fn world(&self, p: Hex) -> [f64; 2] {
        let (i, j) = (f64::from(p.x), f64::from(p.y));
        [i * self.step_a[0] + j * self.step_b[0], i * self.step_a[1] + j * self.step_b[1]]
    }

    /// Position of a lattice point in hex radii (world divided by the hex size), for sampling
    /// noise independently of the world scale.
    #[must_use]
    pub fn unit(&self, p: Hex) -> [f64; 2] {
        let [x, z] = self.world(p);
        [x / self.hex_size, z / self.hex_size]
    }

    /// The lattice triangle containing world `(x, z)`: its three vertices and barycentric
    /// weights.
    #[must_use]
    pub fn triangle_at(&self, x: f64, z: f64) -> ([Hex; 3], [f64; 3]) {
        let [ax, az] = self.step_a;
        let [bx, bz] = self.step_b;
        let det = ax * bz - bx * az;
        let fi = (x * bz - z * bx) / det;
        let fj = (ax * z - az * x) / det;
        let (i0, j0) = (fi.floor(), fj.floor());
        let (u, v) = (fi - i0, fj - j0);
        let p = Hex::new(i0 as i32, j0 as i32);
        if u + v <= 1.0 {
            ([p, p + Hex::new(1, 0), p + Hex::new(0, 1)], [1.0 - u - v, u, v])
        } else {
            let w = Hex::new(1, 1);
            ([p + w, p + Hex::new(0, 1), p + Hex::new(1, 0)], [u + v - 1.0, 1.0 - u, 1.0 - v])
        }
    }

    /// World vectors of the two lattice axes, one step each.
    #[must_use]
    pub fn steps(&self) -> ([f64; 2], [f64; 2]) {
        (self.step_a, self.step_b)
    }

    /// Lattice points of one tile: `1 + 3n(n+1)`.
    #[must_use]
    pub fn points_per_tile(&self) -> usize {
        (1 + 3 * self.n * (self.n + 1)) as usize
    }

    /// Triangles of one tile: `6n²`.
    #[must_use]
    pub fn triangles_per_tile(&self) -> usize {
        (6 * self.n * self.n) as usize
    }

    /// Vertex count of the mesh of a set of `tiles` tiles whose outline (union) is simply
    /// connected and has `boundary_edges` tile edges: `3n²·T + n·B/2 + 1`.
    ///
    /// Each tile owns `3n² - 3n + 1` interior points; edge points (`n - 1` per edge) and corners
    /// are shared. By Euler's formula on the tile graph (`V - E + F = 1` for one simply connected
    /// patch, with `F = T`, `6T = 2E - B`), corners number `2T + B/2 + 1` and edges `3T + B/2`,
    /// which sums to the formula. For the thesis layout (`n = 2`) that is `12T + B + 1`.
    #[must_use]
    pub fn mesh_vertex_count(&self, tiles: usize, boundary_edges: usize) -> usize {
        let n = self.n as usize;
        3 * n * n * tiles + n * boundary_edges / 2 + 1
    }
}

/// The hex nearest fractional axial coordinates `(q, r)`, by cube rounding in f64 (hexx's
/// `Hex::round` takes f32, which loses whole hexes beyond ~10^7).
#[must_use]
pub fn cube_round(q: f64, r: f64) -> Hex {
    let s = -q - r;
    let (mut rq, mut rr, rs) = (q.round(), r.round(), s.round());
    let (dq, dr, ds) = ((rq - q).abs(), (rr - r).abs(), (rs - s).abs());
    if dq > dr && dq > ds {
        rq = -rr - rs;
    } else if dr > ds {
        rr = -rq - rs;
    }
    Hex::new(rq as i32, rr as i32)
}

/// Up to three tiles sharing a lattice point.
#[derive(Debug, Clone, Copy)]
pub struct TileSet {
    tiles: [Hex; 3],
    len: usize,
    /// Ring of the point in the first tile (equal to the subdivision count on a border).
    pub ring: u32,
}

impl TileSet {
    /// The tiles.
    #[must_use]
    pub fn tiles(&self) -> &[Hex] {
        &self.tiles[..self.len]
    }
}

#[cfg(test)]
mod tests;
