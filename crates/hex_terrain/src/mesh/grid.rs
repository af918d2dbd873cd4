//! The point grid: a dense lookup from lattice coordinates to point indices over the bounding
//! box of a rectangle of tiles, and the enumeration that numbers the points of those tiles and
//! of the one-step halo their normals need.

use hexx::Hex;

use crate::config::Orientation;
use crate::lattice::Lattice;

/// Lattice directions around a vertex, counter-clockwise in lattice space.
pub(super) const AROUND: [Hex; 6] = crate::lattice::NEIGHBORS;

/// The tile whose template enumerated a point first, and the point's index in that template.
#[derive(Clone, Copy)]
pub(super) struct Owner {
    /// Index of the tile in the job's tile list.
    pub tile: u32,
    /// Index of the point in the tile's template.
    pub k: u16,
}

/// Lattice points of a rectangle of tiles, as [`Points::collect`] enumerates them.
pub(super) struct Points {
    pub grid: Grid,
    /// Every point: the tiles' own first, then the halo, each in grid order (row by row).
    pub lattice: Vec<Hex>,
    /// How many points belong to the tiles (the rest is halo).
    pub owned: usize,
    /// The owner of each owned point.
    pub owner: Vec<Owner>,
}

/// Dense lookup from lattice coordinates to point indices over a bounding box.
///
/// Rows are staggered like hexx's offset coordinates, so that a rectangle of tiles covers a
/// rectangle of slots with little waste: for flat tiles a row is a lattice `y` and the column
/// `x + ⌊y/2⌋` follows world x; for pointy tiles a row is a lattice `x` (a world column) and
/// the column `y + ⌊x/2⌋` follows world z. Points are numbered in slot order, so the slots of a
/// run of points increase, and along a row consecutive points sit in consecutive slots and share
/// the parity of the row, which decides the slot offsets of their neighbors.
pub(super) struct Grid {
    pub shape: GridShape,
    pub slots: Vec<u32>,
    /// Slot offsets of the six [`AROUND`] steps, by row parity.
    around: [[isize; 6]; 2],
}

/// The extent and layout of a [`Grid`].
#[derive(Clone, Copy)]
pub(super) struct GridShape {
    /// Whether rows are lattice `x` (pointy tiles) rather than lattice `y` (flat).
    pointy: bool,
    min: [i32; 2],
    pub width: usize,
    height: usize,
}

impl GridShape {
    /// A shape holding every point of `tiles` and the one-step halo around them.
    pub fn around(lattice: &Lattice, tiles: &[Hex]) -> Self {
        let pointy = lattice.orientation() == Orientation::Pointy;
        let (mut min, mut max) = ([i32::MAX; 2], [i32::MIN; 2]);
        for &tile in tiles {
            let c = Self::coords(pointy, lattice.tile_center(tile));
            min = [min[0].min(c[0]), min[1].min(c[1])];
            max = [max[0].max(c[0]), max[1].max(c[1])];
        }
        if tiles.is_empty() {
            return Self { pointy, min: [0, 0], width: 0, height: 0 };
        }
        // A point `r` steps from a center is at most `r + 1` columns and `r` rows away (in
        // either layout); the halo adds one step to the tiles' `n`.
        let margin = lattice.subdivisions() as i32 + 2;
        let min = [min[0] - margin, min[1] - margin];
        let (width, height) = ((max[0] + margin - min[0] + 1) as usize, (max[1] + margin - min[1] + 1) as usize);
        Self { pointy, min, width, height }
    }

    /// `[column, row]` of a point in the grid.
    #[inline]
    fn coords(pointy: bool, p: Hex) -> [i32; 2] {
        if pointy { [p.y + p.x.div_euclid(2), p.x] } else { [p.x + p.y.div_euclid(2), p.y] }
    }

    /// Number of slots.
    pub fn len(&self) -> usize {
        self.width * self.height
    }

    /// The slot of a point.
    #[inline]
    pub fn slot(&self, p: Hex) -> usize {
        let [c, r] = Self::coords(self.pointy, p);
        let (c, r) = (c - self.min[0], r - self.min[1]);
        debug_assert!(c >= 0 && r >= 0 && (c as usize) < self.width && (r as usize) < self.height);
        r as usize * self.width + c as usize
    }

    /// The point in `slot`.
    #[inline]
    fn point(&self, slot: usize) -> Hex {
        let c = (slot % self.width) as i32 + self.min[0];
        let r = (slot / self.width) as i32 + self.min[1];
        if self.pointy { Hex::new(r, c - r.div_euclid(2)) } else { Hex::new(c - r.div_euclid(2), r) }
    }

    /// Parity of `p`'s row: which of the tables of [`GridShape::offsets`] applies.
    #[inline]
    pub fn parity(&self, p: Hex) -> usize {
        (if self.pointy { p.x } else { p.y } & 1) as usize
    }

    /// Slot offset of lattice offset `d` from a point whose row has `parity`.
    pub fn offset(&self, parity: i32, d: Hex) -> isize {
        let p = if self.pointy { Hex::new(parity, 0) } else { Hex::new(0, parity) };
        let [c0, r0] = Self::coords(self.pointy, p);
        let [c, r] = Self::coords(self.pointy, p + d);
        (r - r0) as isize * self.width as isize + (c - c0) as isize
    }

    /// Slot offsets of lattice offsets `d` from a point, for each parity of the point.
    fn offsets<const N: usize>(&self, d: [Hex; N]) -> [[isize; N]; 2] {
        [0, 1].map(|parity| d.map(|d| self.offset(parity, d)))
    }

    /// Slot offsets of every template point from its tile's center, for each parity of the
    /// center.
    pub fn template_offsets(&self, lattice: &Lattice) -> [Vec<isize>; 2] {
        let template = lattice.template();
        [0, 1].map(|parity| template.iter().map(|tp| self.offset(parity, tp.offset)).collect())
    }
}

impl Grid {
    const EMPTY: u32 = u32::MAX;
    /// A slot of the halo, before numbering.
    const HALO: u32 = u32::MAX - 1;

    fn new(shape: GridShape) -> Self {
        Self { shape, slots: vec![Self::EMPTY; shape.len()], around: shape.offsets(AROUND) }
    }

    /// The slot of a point.
    #[inline]
    pub fn slot(&self, p: Hex) -> usize {
        self.shape.slot(p)
    }

    /// Slot offsets of the six lattice neighbors of `p`, in [`AROUND`] order.
    #[inline]
    pub fn around(&self, p: Hex) -> [isize; 6] {
        self.around[self.shape.parity(p)]
    }
}

impl Points {
    /// Lattice points of `tiles` and of the one-step halo around them that smooth normals need,
    /// with the grid indexing both. Each point belongs to the first tile (in `tiles` order)
    /// whose template holds it; the tiles' points come first, then the halo's, each in grid
    /// order.
    pub fn collect(lattice: &Lattice, tiles: &[Hex], shape: GridShape, offsets: &[Vec<isize>; 2]) -> Self {
        let n = lattice.subdivisions();
        let ppt = lattice.points_per_tile();
        let template = lattice.template();
        let mut grid = Grid::new(shape);
        // Claim: each slot holds `tile * ppt + k` of its first tile until it is numbered.
        for (t, &tile) in tiles.iter().enumerate() {
            let center = lattice.tile_center(tile);
            let base = grid.slot(center);
            for (k, &d) in offsets[shape.parity(center)].iter().enumerate() {
                let slot = &mut grid.slots[base.wrapping_add_signed(d)];
                if *slot == Grid::EMPTY {
                    *slot = (t * ppt + k) as u32;
                }
            }
        }
        // Number the tiles' points in slot order, marking the halo around border points.
        let estimate = tiles.len() * 3 * (n * n) as usize + 64;
        let mut points = Vec::with_capacity(estimate + estimate / 8);
        let mut owner = Vec::with_capacity(estimate);
        for slot in 0..grid.slots.len() {
            let code = grid.slots[slot];
            if code >= Grid::HALO {
                continue;
            }
            let (tile, k) = (code as usize / ppt, code as usize % ppt);
            let p = shape.point(slot);
            grid.slots[slot] = points.len() as u32;
            points.push(p);
            owner.push(Owner { tile: tile as u32, k: k as u16 });
            if template[k].ring == n {
                for d in grid.around(p) {
                    let next = &mut grid.slots[slot.wrapping_add_signed(d)];
                    if *next == Grid::EMPTY {
                        *next = Grid::HALO;
                    }
                }
            }
        }
        let owned = points.len();
        for slot in 0..grid.slots.len() {
            if grid.slots[slot] == Grid::HALO {
                grid.slots[slot] = points.len() as u32;
                points.push(shape.point(slot));
            }
        }
        Points { grid, lattice: points, owned, owner }
    }

    /// The slot of point `i`.
    #[inline]
    pub fn slot_of(&self, i: usize) -> usize {
        self.grid.slot(self.lattice[i])
    }
}
