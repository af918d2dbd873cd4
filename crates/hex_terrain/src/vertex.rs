//! The vertex chain: what turns a lattice point's raw height and the tiles that share it into a
//! finished vertex. Manipulation first ([`crate::manipulate`]: interpolation, hex unity, edge and
//! corner correction), then relief ([`crate::relief`]: peaks, ridges, hills), then carving
//! (river channels and lakes, from [`crate::water::channels`]). Every step keeps a non-border
//! vertex inside its tile kind's range.
//!
//! The one-vertex evaluator ([`VertexRules::evaluate`], which finds the tiles around a point
//! itself) and the mesh job (which knows them from its tile grid and feeds them in) both call
//! [`VertexRules::finish`], so a vertex is the same bits whichever path computed it.

use hexx::Hex;

use crate::config::{ManipulationConfig, MapConfig};
use crate::geometry::Geometry;
use crate::heights::HeightField;
use crate::kind::{Thresholds, TileKind};
use crate::manipulate::{Lanes, Manipulated, manipulate, manipulate_lanes, span};
use crate::relief::Relief;
use crate::table::TileTable;
use crate::water::channels;

/// One lattice vertex, evaluated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VertexSample {
    /// Normalised height after shaping, before manipulation.
    pub raw: f32,
    /// Normalised height after manipulation, relief and carving.
    pub height: f32,
    /// Whether hex unity, edge/corner correction or carving moved it.
    pub moved: bool,
    /// Ring in its tile (`n` on a border).
    pub ring: u32,
    /// Highest kind among the in-map tiles sharing it, or its height's kind outside the map.
    pub kind: TileKind,
    /// How much river or lake water covers it, in `[0, 1]` (0 on a map without rivers).
    pub water: f32,
}

/// The in-map tiles sharing a lattice point and their kinds (same order; one tile for an inner
/// point, up to three on a border, none outside the map).
#[derive(Debug, Clone, Copy)]
pub struct Sharing<'a> {
    /// The tiles.
    pub tiles: &'a [Hex],
    /// Their kinds.
    pub kinds: &'a [TileKind],
}

/// The rules of the vertex chain of a map.
#[derive(Debug, Clone)]
pub struct VertexRules {
    thresholds: Thresholds,
    manipulation: ManipulationConfig,
    relief: Relief,
    subdivisions: u32,
    /// How deep channels carve, as a fraction of the way to the bottom of the kind's range.
    carve: f32,
}

impl VertexRules {
    /// The rules of a validated config.
    #[must_use]
    pub fn new(config: &MapConfig, thresholds: Thresholds) -> Self {
        Self {
            thresholds,
            manipulation: config.manipulation.clone(),
            relief: Relief::new(config, thresholds),
            subdivisions: config.subdivisions(),
            carve: config.rivers.carve,
        }
    }

    /// Evaluates lattice point `p` on its own: its raw height from the height field, the tiles
    /// around it from the lattice, their kinds from `kind_of` (`None` outside the map), their
    /// water from `water` (the tile table of a map with rivers).
    #[must_use]
    #[inline]
    pub fn evaluate(
        &self,
        geometry: &Geometry,
        heights: &HeightField,
        water: Option<&TileTable>,
        p: Hex,
        kind_of: impl Fn(Hex) -> Option<TileKind>,
    ) -> VertexSample {
        self.finish_at(geometry, water, heights.raw_height(geometry, p), p, kind_of)
    }

    /// Finishes lattice point `p` of raw height `raw`, finding the tiles around it.
    #[must_use]
    #[inline]
    pub fn finish_at(
        &self,
        geometry: &Geometry,
        water: Option<&TileTable>,
        raw: f32,
        p: Hex,
        kind_of: impl Fn(Hex) -> Option<TileKind>,
    ) -> VertexSample {
        let set = geometry.lattice().tiles_at(p);
        let mut kinds = [TileKind::Sea; 3];
        let mut tiles = [Hex::ZERO; 3];
        let mut len = 0;
        for &tile in set.tiles() {
            if let Some(kind) = kind_of(tile) {
                kinds[len] = kind;
                tiles[len] = tile;
                len += 1;
            }
        }
        let sharing = Sharing { tiles: &tiles[..len], kinds: &kinds[..len] };
        self.finish(geometry, water, raw, p, set.ring, sharing)
    }

    /// The chain: manipulation, relief and carving of lattice point `p` of raw height `raw` at
    /// `ring`, shared by the in-map tiles of `sharing`. Carving reads `water` (none: no carving;
    /// a caller that knows no tile holding `p` is wet may pass none).
    #[must_use]
    #[inline(always)]
    pub fn finish(
        &self,
        geometry: &Geometry,
        water: Option<&TileTable>,
        raw: f32,
        p: Hex,
        ring: u32,
        sharing: Sharing<'_>,
    ) -> VertexSample {
        let span = span(sharing.kinds);
        let m = self.manipulated(raw, ring, span);
        let kind = span.map_or_else(|| self.thresholds.classify(raw), |(_, highest)| highest);
        let s = VertexSample { raw, height: m.height, moved: m.moved, ring, kind, water: 0.0 };
        self.finish_manipulated(geometry, water, p, sharing, s)
    }

    /// The chain's first step, manipulation, of a vertex of raw height `raw` at `ring` whose
    /// sharing tiles' kinds span `span` ([`span`]). Branch-free in the height: the mesh runs it
    /// over a batch of vertices in one loop, then [`VertexRules::finish_manipulated`].
    #[must_use]
    #[inline(always)]
    pub(crate) fn manipulated(&self, raw: f32, ring: u32, span: Option<(TileKind, TileKind)>) -> Manipulated {
        if self.manipulation.any() {
            manipulate(&self.thresholds, &self.manipulation, raw, ring, self.subdivisions, span)
        } else {
            Manipulated { height: raw, moved: false }
        }
    }

    /// [`VertexRules::manipulated`] of `L` vertices in the map at once, in loops that vectorise
    /// (the same bits).
    #[inline(always)]
    fn manipulated_lanes<const L: usize>(&self, v: &Lanes<'_, L>, height: &mut [f32; L], moved: &mut [bool; L]) {
        if self.manipulation.any() {
            manipulate_lanes(&self.thresholds, &self.manipulation, self.subdivisions, v, height, moved);
        } else {
            *height = *v.raw;
            *moved = [false; L];
        }
    }

    /// [`VertexRules::manipulated`] of many vertices in the map (raw heights and rings, and the
    /// lowest and highest kinds of the tiles sharing each) into `heights` and `moved`, sixteen at
    /// a time in loops that vectorise, the rest one by one: the same bits as one by one.
    #[inline(always)]
    pub(crate) fn manipulated_many(
        &self,
        (raws, rings): (&[f32], &[u32]),
        (los, his): (&[TileKind], &[TileKind]),
        heights: &mut [f32],
        moved: &mut [bool],
    ) {
        const L: usize = 16;
        let whole = heights.len() / L * L;
        let chunks = heights[..whole].chunks_exact_mut(L).zip(moved[..whole].chunks_exact_mut(L));
        for (c, (height, moved)) in chunks.enumerate() {
            let range = c * L..(c + 1) * L;
            let lanes: Lanes<'_, L> = Lanes {
                raw: raws[range.clone()].try_into().expect("L vertices"),
                ring: rings[range.clone()].try_into().expect("L vertices"),
                lo: los[range.clone()].try_into().expect("L vertices"),
                hi: his[range].try_into().expect("L vertices"),
            };
            self.manipulated_lanes(
                &lanes,
                height.try_into().expect("L vertices"),
                moved.try_into().expect("L vertices"),
            );
        }
        for i in whole..heights.len() {
            let m = self.manipulated(raws[i], rings[i], Some((los[i], his[i])));
            (heights[i], moved[i]) = (m.height, m.moved);
        }
    }

    /// Whether the chain ends at manipulation for a vertex of a map with `water`: no relief and
    /// no water to carve, so [`VertexRules::finish_manipulated`] changes nothing.
    #[must_use]
    pub(crate) fn ends_at_manipulation(&self, water: Option<&TileTable>) -> bool {
        !self.relief.is_active() && water.is_none_or(|t| t.hydrology().is_none())
    }

    /// The chain after manipulation: relief and carving of vertex `s` at `p` (its height
    /// manipulated, its kind the highest of the tiles of `sharing`; see [`VertexRules::finish`]).
    #[must_use]
    #[inline(always)]
    pub(crate) fn finish_manipulated(
        &self,
        geometry: &Geometry,
        water: Option<&TileTable>,
        p: Hex,
        sharing: Sharing<'_>,
        s: VertexSample,
    ) -> VertexSample {
        let height = self.relief.apply(geometry, s.height, s.raw, p, s.ring, sharing.kinds);
        let s = VertexSample { height, ..s };
        match water {
            Some(table) if table.hydrology().is_some() => self.carve(geometry, table, p, sharing, s),
            _ => s,
        }
    }

    /// Carves a vertex at `p`: lowers it by the water cover towards the bottom of its kind's
    /// range, only where every tile sharing it is of one kind (a border vertex between kinds
    /// stays on its threshold).
    #[inline]
    fn carve(
        &self,
        geometry: &Geometry,
        table: &TileTable,
        p: Hex,
        sharing: Sharing<'_>,
        mut s: VertexSample,
    ) -> VertexSample {
        let Some(&first) = sharing.kinds.first() else { return s };
        if sharing.kinds.iter().any(|&k| k != first) {
            return s;
        }
        let f = sharing.tiles.iter().map(|&t| channels::cover(geometry, table, t, p)).fold(0.0_f32, f32::max);
        if f > 0.0 {
            let lo = self.thresholds.range(first).0;
            if s.height > lo {
                let carved = s.height - f * self.carve * (s.height - lo);
                s.moved |= carved != s.height;
                s.height = carved.max(lo);
            }
            s.water = f;
        }
        s
    }
}
