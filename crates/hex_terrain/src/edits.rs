//! Edits, the stage right after the height field: a designer's changes to tiles (the config's
//! `edits`, [`TileEdit`]) turned into a change of the raw height of every lattice point they
//! touch. Everything after it (tile kinds, the tile table with rivers, lakes and biomes, the
//! vertex chain, meshes, queries, the game setup) reads the edited heights, so an edit is
//! consistent everywhere at once: a raised ridge changes the drainage, a new mountain gets its
//! peak, biomes follow the new elevation.
//!
//! An edited tile moves by `delta`, the difference between its target center height and the
//! generated one, so it keeps its relief. A point inside the tile moves by the tile's delta and
//! is then kept inside the raw range of the tile's (new) type, so every inner vertex lies in the
//! type's range after the vertex chain whatever the manipulation settings. A border point moves
//! by the mean of the deltas of the tiles sharing it (an unedited tile counts zero; the deltas
//! summed in ascending order, so every copy of a point gets the same bits), so the
//! surface stays continuous and an unedited neighbor keeps every inner vertex it had. Each edited
//! point is a pure function of the point and the edits: chunks stay bit-identical at seams and
//! chunked equals whole.

use std::collections::HashMap;

use hexx::Hex;

use crate::config::{FeatureEdit, PropDensity, RiverEdit, TileEdit};
use crate::geometry::Geometry;
use crate::vocab::{Biome, RuleId, TileKind};

/// How one edited tile moves its points (a flat map's and a globe's edits alike).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct TileShift {
    /// Added to the raw height of its points (its border points share it).
    pub(crate) delta: f32,
    /// The raw heights its inner points are kept in: its type's classification range.
    range: (f32, f32),
}

impl TileShift {
    /// How `edit` moves its tile, on a map whose raw sea and mountain thresholds are
    /// `(sea, mountain)` and whose generated raw center height there is `base`; `None` when the
    /// edit sets neither a height nor a type.
    pub(crate) fn of(edit: &TileEdit, (sea, mountain): (f32, f32), base: f32) -> Option<Self> {
        if edit.height.is_none() && edit.kind.is_none() {
            return None;
        }
        let wanted = edit.height.unwrap_or(base);
        let classified = if wanted < sea {
            TileKind::Sea
        } else if wanted < mountain {
            TileKind::Land
        } else {
            TileKind::Mountain
        };
        let range = raw_range((sea, mountain), edit.kind.unwrap_or(classified));
        let target = wanted.clamp(range.0, range.1);
        Some(Self { delta: target - base, range })
    }

    /// The edited raw height of a point of the tile that no other tile holds.
    #[inline]
    pub(crate) fn inner(&self, raw: f32) -> f32 {
        (raw + self.delta).clamp(self.range.0, self.range.1)
    }
}

/// The edited raw height of a point `holders` tiles share, whose edited holders move by
/// `deltas` (reordered here): the mean of the deltas (an unedited holder counts zero), summed in
/// ascending order so every copy of the point gets the same bits whatever order its holders
/// were listed in.
#[inline]
pub(crate) fn shared(raw: f32, deltas: &mut [f32], holders: usize) -> f32 {
    if deltas.is_empty() {
        return raw;
    }
    deltas.sort_unstable_by(f32::total_cmp);
    let sum = deltas.iter().fold(0.0f32, |sum, &d| sum + d);
    (raw + sum / holders as f32).clamp(0.0, 1.0)
}

/// The edits of a map, compiled against its generated heights (see the module docs).
#[derive(Debug, Clone, Default)]
pub struct Edits {
    /// By the map's own tile (axial): the tiles whose height or type is edited.
    tiles: HashMap<Hex, TileShift>,
    /// The biomes set by hand, by the map's own tile.
    biomes: HashMap<Hex, Biome>,
    /// The rivers set by hand, by the map's own tile.
    rivers: HashMap<Hex, RiverEdit>,
    /// The prop densities set by hand, by the map's own tile.
    props: HashMap<Hex, PropDensity>,
    /// The terrains and features set by hand (a map with its own ruleset), by the map's own
    /// tile.
    terrains: HashMap<Hex, (Option<RuleId>, Option<FeatureEdit>)>,
}

impl Edits {
    /// Compiles `edits` (validated: on the map, once each) for a map whose raw sea and mountain
    /// thresholds are `(sea, mountain)` (a center below `sea` is sea, from `mountain` on
    /// mountain) and whose generated raw height at a tile's center is `generated(tile)`.
    pub fn new(
        edits: &[TileEdit],
        geometry: &Geometry,
        thresholds: (f32, f32),
        generated: impl Fn(Hex) -> f32,
    ) -> Self {
        let mut tiles = HashMap::with_capacity(edits.len());
        let mut biomes = HashMap::new();
        let mut rivers = HashMap::new();
        let mut props = HashMap::new();
        let mut terrains = HashMap::new();
        for edit in edits {
            let tile = geometry.wrap_tile(geometry.tile_from_offset([edit.at.0, edit.at.1]));
            if let Some(biome) = edit.biome {
                biomes.insert(tile, biome);
            }
            if let Some(river) = edit.river {
                rivers.insert(tile, river);
            }
            if let Some(density) = edit.props {
                props.insert(tile, density);
            }
            if edit.terrain.is_some() || edit.feature.is_some() {
                terrains.insert(tile, (edit.terrain, edit.feature));
            }
            // A biome, a terrain, a feature, a river or props alone move no height.
            if edit.height.is_some() || edit.kind.is_some() {
                let shift = TileShift::of(edit, thresholds, generated(tile)).expect("a height or a type");
                tiles.insert(tile, shift);
            }
        }
        Self { tiles, biomes, rivers, props, terrains }
    }

    /// Whether no tile is edited.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.tiles.is_empty()
            && self.biomes.is_empty()
            && self.rivers.is_empty()
            && self.props.is_empty()
            && self.terrains.is_empty()
    }

    /// Whether a tile's height or type (any copy of it on a wrapping map) is edited.
    #[must_use]
    pub fn is_edited(&self, geometry: &Geometry, tile: Hex) -> bool {
        self.tiles.contains_key(&geometry.wrap_tile(tile))
    }

    /// The biome set by hand on a tile (any copy of it on a wrapping map), if any.
    #[must_use]
    #[inline]
    pub fn biome(&self, geometry: &Geometry, tile: Hex) -> Option<Biome> {
        by_hand(&self.biomes, geometry, tile)
    }

    /// The terrain and the feature set by hand on a tile (any copy of it on a wrapping map):
    /// `(terrain, feature)`, each `None` when not set.
    #[must_use]
    pub fn terrain(&self, geometry: &Geometry, tile: Hex) -> (Option<RuleId>, Option<FeatureEdit>) {
        by_hand(&self.terrains, geometry, tile).unwrap_or((None, None))
    }

    /// The river set by hand on a tile (any copy of it on a wrapping map), if any.
    #[must_use]
    pub fn river(&self, geometry: &Geometry, tile: Hex) -> Option<RiverEdit> {
        by_hand(&self.rivers, geometry, tile)
    }

    /// The prop density set by hand on a tile (any copy of it on a wrapping map), if any.
    #[must_use]
    #[inline]
    pub fn props(&self, geometry: &Geometry, tile: Hex) -> Option<PropDensity> {
        by_hand(&self.props, geometry, tile)
    }

    /// The edited raw height of lattice point `p`, whose generated raw height is `raw`.
    #[must_use]
    #[inline]
    pub fn apply(&self, geometry: &Geometry, p: Hex, raw: f32) -> f32 {
        if self.tiles.is_empty() {
            return raw;
        }
        let set = geometry.lattice().tiles_at(p);
        let tiles = set.tiles();
        if let [tile] = tiles {
            return match self.tiles.get(&geometry.wrap_tile(*tile)) {
                Some(shift) => shift.inner(raw),
                None => raw,
            };
        }
        // The deltas are summed in ascending order, not in the order `tiles_at` lists the
        // tiles: that order follows the cube rounding of the point, which can differ between a
        // point and its copy one period away, and three f32 additions in another order can
        // round to other bits (the seam would no longer be exact).
        let mut deltas = [0.0f32; 3];
        let mut edited = 0;
        for tile in tiles {
            if let Some(shift) = self.tiles.get(&geometry.wrap_tile(*tile)) {
                deltas[edited] = shift.delta;
                edited += 1;
            }
        }
        shared(raw, &mut deltas[..edited], tiles.len())
    }
}

/// What was set by hand on a tile (any copy of it on a wrapping map); no lookup when nothing was.
#[inline]
fn by_hand<T: Copy>(set: &HashMap<Hex, T>, geometry: &Geometry, tile: Hex) -> Option<T> {
    if set.is_empty() {
        return None;
    }
    set.get(&geometry.wrap_tile(tile)).copied()
}

/// The raw heights whose centers classify as `kind`: `[0, sea)`, `[sea, mountain)`,
/// `[mountain, 1]`, closed at the largest height below an open end.
fn raw_range((sea, mountain): (f32, f32), kind: TileKind) -> (f32, f32) {
    match kind {
        TileKind::Sea => (0.0, sea.next_down().max(0.0)),
        TileKind::Land => (sea, mountain.next_down().max(sea)),
        TileKind::Mountain => (mountain, 1.0),
    }
}
