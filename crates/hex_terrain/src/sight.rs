//! What a unit sees from a tile, by the map's sight rule ([`SightConfig`](crate::SightConfig)):
//! a pure function of the compiled terrain and the tile, the same on any thread.

use hexx::Hex;

use crate::terrain::Terrain;

impl Terrain {
    /// A tile's height for sight ([`SightConfig`](crate::SightConfig)): 2 for a mountain, 1 for
    /// a tile of a tall biome, 0 otherwise; `None` off the map.
    #[must_use]
    pub fn sight_height(&self, tile: Hex) -> Option<u8> {
        match self.rule_table() {
            Some(table) => Some(table.sight(table.index(self.offset_of(self.wrap_tile(tile)?))?)),
            None => crate::terrain::rules::evaluate_sight(self, tile),
        }
    }

    /// The tiles a unit on `from` sees with sight `radius` (plus the bonus of a tall tile or a
    /// mountain), by the map's sight rule ([`SightConfig`](crate::SightConfig)): each tile of
    /// the map within reach whose view is not blocked by a higher tile or a mountain strictly
    /// between (on hexx's line from `from` to the tile's copy nearest it, the short way round a
    /// wrapping map, drawn with `from` at the origin so that the view does not depend on where
    /// on the map it is taken). `from` is always seen. The map's own tiles, each once, in the map's row order; empty off the map.
    #[must_use]
    pub fn field_of_view(&self, from: Hex, radius: u32) -> Vec<Hex> {
        let mut out = Vec::new();
        self.each_seen(from, radius, |tile| {
            let [col, row] = self.offset_of(tile);
            out.push(((row, col), tile));
        });
        out.sort_unstable_by_key(|&(key, _)| key);
        out.into_iter().map(|(_, tile)| tile).collect()
    }

    /// Calls `f` once with each tile of the map a unit on `from` sees with sight `radius` (the
    /// rule of [`Terrain::field_of_view`], in no particular order; the fog's update reads it
    /// without collecting).
    pub(crate) fn each_seen(&self, from: Hex, radius: u32, mut f: impl FnMut(Hex)) {
        let Some(from) = self.wrap_tile(from) else { return };
        let Some(own) = self.sight_height(from) else { return };
        let sight = &self.config().sight;
        let reach = radius.saturating_add(match own {
            2 => sight.mountain_bonus,
            1 => sight.tall_bonus,
            _ => 0,
        });
        let blocks = |tile: Hex| self.sight_height(tile).is_some_and(|h| h > own || h == 2);
        let mut look = |offset: Hex, between: &mut dyn Iterator<Item = Hex>| {
            let Some(target) = self.wrap_tile(from + offset) else { return };
            // The copy of a tile nearest the viewer is the one it looks at: on a narrow
            // wrapping map only one copy of each tile passes, so each is seen once.
            if self.tile_near(target, from) != from + offset {
                return;
            }
            for step in between {
                if blocks(from + step) {
                    return;
                }
            }
            f(target);
        };
        let lines = lines();
        if reach <= CACHED_REACH {
            // The lines drawn once for every viewer, nearest tiles first.
            let count = Hex::range_count(reach) as usize;
            for (offset, steps) in &lines.tiles[..count] {
                look(*offset, &mut lines.steps[steps.clone()].iter().copied());
            }
        } else {
            for offset in Hex::ZERO.range(reach) {
                look(offset, &mut interior(offset));
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
