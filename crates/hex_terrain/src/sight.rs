//! What a unit sees from a tile, by the map's sight rule ([`SightConfig`](crate::SightConfig)):
//! a pure function of the compiled terrain and the tile, the same on any thread, and bounded by
//! the map's tiles whatever the radius asked.

use hexx::Hex;

use crate::terrain::Terrain;

/// The largest sight reach (a radius plus the viewer's bonus) a query may ask on an unbounded
/// world, which has no end to bound it: a larger one is refused ([`SightError`]). Far beyond any
/// game's sight (Civilization's units see 2 tiles, 4 from a mountain).
pub const MAX_UNBOUNDED_SIGHT: u32 = 64;

/// A sight radius an unbounded world refuses: with the viewer's bonus it reaches farther than
/// [`MAX_UNBOUNDED_SIGHT`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error(
    "sight radius {radius} reaches {reach} tiles with the viewer's bonus: on an unbounded world at most \
     {MAX_UNBOUNDED_SIGHT}"
)]
pub struct SightError {
    /// The radius asked for.
    pub radius: u32,
    /// The radius plus the viewer's bonus.
    pub reach: u32,
}

/// A viewer, ready to look: its tile (the map's own), its sight height and how far it sees.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Viewer {
    from: Hex,
    own: u8,
    reach: u32,
}

impl Terrain {
    /// A tile's height for sight ([`SightConfig`](crate::SightConfig)): 2 for a mountain (a
    /// lake on a mountain tile is water, not a mountain: it is its biome's height), 1 for a
    /// tile of a tall biome, 0 otherwise; `None` off the map.
    #[must_use]
    pub fn sight_height(&self, tile: Hex) -> Option<u8> {
        match self.rule_table() {
            Some(table) => Some(table.sight(table.index(self.offset_of(self.wrap_tile(tile)?))?)),
            None => crate::terrain::rules::evaluate_sight(self, tile),
        }
    }

    /// The largest sight reach (a radius plus the viewer's bonus) that can matter: on a bounded
    /// or wrapping map its columns plus its rows, since no two of its tiles lie farther apart (a
    /// larger radius sees the same tiles, and costs no more); on an unbounded world
    /// [`MAX_UNBOUNDED_SIGHT`], past which a radius is refused.
    #[must_use]
    pub fn sight_limit(&self) -> u32 {
        self.bounds().map_or(MAX_UNBOUNDED_SIGHT, |rect| {
            let [w, h] = [0, 1].map(|a| (rect.max[a] - rect.min[a]).unsigned_abs());
            w.saturating_add(h)
        })
    }

    /// The tiles a unit on `from` sees with sight `radius` (plus the bonus of a tall tile or a
    /// mountain, [`SightConfig`](crate::SightConfig)), by the map's sight rule: each tile of the
    /// map within reach whose view is not blocked by a higher tile or a mountain strictly between.
    ///
    /// - **The line** is hexx's line from `from` to the tile, drawn with `from` at the origin so
    ///   that the view does not depend on where on the map it is taken. Tiles on it that lie off a
    ///   bounded map (past its ragged edge) block nothing.
    /// - **On a wrapping map** a tile is looked at through its copy nearest `from` (the short
    ///   way round); of two copies equally near, the western one (the lower column). So each tile
    ///   is seen at most once.
    /// - **Any radius**: a reach beyond [`Terrain::sight_limit`] sees what that limit sees on a
    ///   bounded or wrapping map; the work is bounded by the map's tiles, never by the number.
    ///
    /// `from` is always seen. The map's own tiles, each once, in the map's row order; empty off the
    /// map.
    ///
    /// # Errors
    /// [`SightError`] on an unbounded world when the radius plus the viewer's bonus passes
    /// [`MAX_UNBOUNDED_SIGHT`].
    pub fn field_of_view(&self, from: Hex, radius: u32) -> Result<Vec<Hex>, SightError> {
        let mut out = Vec::new();
        if let Some(viewer) = self.viewer(from, radius)? {
            self.each_seen(viewer, |tile| {
                let [col, row] = self.offset_of(tile);
                out.push(((row, col), tile));
            });
        }
        out.sort_unstable_by_key(|&(key, _)| key);
        Ok(out.into_iter().map(|(_, tile)| tile).collect())
    }

    /// A unit on `from` with sight `radius`, ready to look: `None` off the map, its reach brought
    /// within [`Terrain::sight_limit`] on a bounded map.
    pub(crate) fn viewer(&self, from: Hex, radius: u32) -> Result<Option<Viewer>, SightError> {
        let Some(from) = self.wrap_tile(from) else { return Ok(None) };
        let Some(own) = self.sight_height(from) else { return Ok(None) };
        let sight = &self.config().sight;
        let reach = radius.saturating_add(match own {
            2 => sight.mountain_bonus,
            1 => sight.tall_bonus,
            _ => 0,
        });
        let limit = self.sight_limit();
        if self.bounds().is_none() && reach > limit {
            return Err(SightError { radius, reach });
        }
        Ok(Some(Viewer { from, own, reach: reach.min(limit) }))
    }

    /// Calls `f` once with each tile of the map the viewer sees (the rule of
    /// [`Terrain::field_of_view`], in no particular order; the fog's update reads it without
    /// collecting).
    pub(crate) fn each_seen(&self, viewer: Viewer, mut f: impl FnMut(Hex)) {
        let Viewer { from, own, reach } = viewer;
        let mut heights = Heights::new(self, from, reach);
        let mut look = |offset: Hex, between: &mut dyn Iterator<Item = Hex>| {
            let Some(target) = self.wrap_tile(from + offset) else { return };
            // The copy of a tile nearest the viewer is the one it looks at: on a narrow
            // wrapping map only one copy of each tile passes, so each is seen once.
            if self.tile_near(target, from) != from + offset {
                return;
            }
            for step in between {
                if heights.get(step).is_some_and(|h| h > own || h == 2) {
                    return;
                }
            }
            f(target);
        };
        if reach <= CACHED_REACH {
            // The lines drawn once for every viewer, nearest tiles first.
            let lines = lines();
            let count = Hex::range_count(reach) as usize;
            for (offset, steps) in &lines.tiles[..count] {
                look(*offset, &mut lines.steps[steps.clone()].iter().copied());
            }
        } else if let Some(rect) = self.bounds().filter(|rect| hexagon_tiles(reach) > rect.len() as u64) {
            // Fewer tiles on the map than within reach: each tile's nearest copy, if in reach.
            for offset in rect.iter() {
                let offset = self.tile_near(self.tile_from_offset(offset), from) - from;
                if offset.unsigned_distance_to(Hex::ZERO) <= reach {
                    look(offset, &mut interior(offset));
                }
            }
        } else {
            for offset in Hex::ZERO.range(reach) {
                look(offset, &mut interior(offset));
            }
        }
    }
}

/// Tiles within `reach` of a tile, counted without overflow.
fn hexagon_tiles(reach: u32) -> u64 {
    let r = u64::from(reach);
    3 * r * (r + 1) + 1
}

/// The sight heights a viewer's lines read, by offset from the viewer: the map's table on a
/// bounded map; on an unbounded world each tile evaluated once, however many lines cross it.
enum Heights<'a> {
    Table { terrain: &'a Terrain, from: Hex },
    Evaluated { terrain: &'a Terrain, from: Hex, reach: i32, side: usize, known: Vec<u8> },
}

/// A tile's sight height not yet evaluated.
const UNKNOWN: u8 = u8::MAX;
/// A tile off the map (it blocks nothing).
const OFF_MAP: u8 = u8::MAX - 1;

impl<'a> Heights<'a> {
    fn new(terrain: &'a Terrain, from: Hex, reach: u32) -> Self {
        if terrain.rule_table().is_some() || reach <= 1 || reach > MAX_UNBOUNDED_SIGHT {
            return Self::Table { terrain, from };
        }
        // A square of axial offsets covers the hexagon (and every line in it).
        let reach = reach as i32;
        let side = 2 * reach as usize + 1;
        Self::Evaluated { terrain, from, reach, side, known: vec![UNKNOWN; side * side] }
    }

    /// The sight height of the tile at `offset` from the viewer; `None` off the map.
    fn get(&mut self, offset: Hex) -> Option<u8> {
        match self {
            Self::Table { terrain, from } => terrain.sight_height(*from + offset),
            Self::Evaluated { terrain, from, reach, side, known } => {
                let [x, y] = [offset.x + *reach, offset.y + *reach];
                let slot = &mut known[y as usize * *side + x as usize];
                if *slot == UNKNOWN {
                    *slot = terrain.sight_height(*from + offset).unwrap_or(OFF_MAP);
                }
                (*slot != OFF_MAP).then_some(*slot)
            }
        }
    }
}

/// The reach up to which the lines of sight are drawn once, for every viewer (a sight radius
/// plus its bonus is rarely more).
const CACHED_REACH: u32 = 12;

/// The lines of sight from the origin to every tile within [`CACHED_REACH`], nearest first:
/// each tile with the range of `steps` holding the tiles strictly between it and the origin.
struct Lines {
    tiles: Vec<(Hex, std::ops::Range<usize>)>,
    steps: Vec<Hex>,
}

fn lines() -> &'static Lines {
    static LINES: std::sync::OnceLock<Lines> = std::sync::OnceLock::new();
    LINES.get_or_init(|| {
        let mut offsets: Vec<Hex> = Hex::ZERO.range(CACHED_REACH).collect();
        offsets.sort_by_key(|h| (h.unsigned_distance_to(Hex::ZERO), h.x, h.y));
        let mut steps = Vec::new();
        let tiles = offsets
            .into_iter()
            .map(|offset| {
                let start = steps.len();
                steps.extend(interior(offset));
                (offset, start..steps.len())
            })
            .collect();
        Lines { tiles, steps }
    })
}

/// The tiles strictly between the origin and `offset` on hexx's line (drawn around the origin,
/// so far from it the lines keep their precision).
fn interior(offset: Hex) -> impl Iterator<Item = Hex> {
    let line = Hex::ZERO.line_to(offset);
    let steps = line.len();
    line.skip(1).take(steps.saturating_sub(2))
}
