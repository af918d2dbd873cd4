//! A globe's edits, as a flat map's (`crate::edits`): a designer's changes to tiles (the config's
//! `edits`, each naming its tile `(id, 0)`) turned into a change of the raw height of every fine
//! point they touch, and the biomes and prop densities set by hand. An edited tile moves by the difference between
//! its target center height and the generated one, its inner points kept in its type's range; a
//! point two or three tiles share moves by the mean of their moves (an unedited tile counts zero,
//! summed in ascending order), so every copy of a point gets the same bits and chunks still meet
//! exactly. Everything after it (tile kinds, climate and biomes, the finished points, meshes and
//! rules) reads the edited heights.

use std::collections::HashMap;

use super::GlobeTile;
use crate::config::{PropDensity, TileEdit};
use crate::edits::{TileShift, shared};
use crate::vocab::Biome;

/// The edits of a globe, compiled against its generated center heights.
#[derive(Debug, Clone, Default)]
pub(super) struct GlobeEdits {
    /// The tiles whose height or type is edited, by id.
    shifts: HashMap<u32, TileShift>,
    /// The biomes set by hand, by id.
    biomes: HashMap<u32, Biome>,
    /// The prop densities set by hand, by id.
    props: HashMap<u32, PropDensity>,
}

impl GlobeEdits {
    /// Compiles `edits` (validated: tiles of the globe, once each) for a globe whose raw sea and
    /// mountain thresholds are `thresholds` and whose generated raw center heights are
    /// `generated`, by id.
    pub(super) fn new(edits: &[TileEdit], thresholds: (f32, f32), generated: &[f32]) -> Self {
        let mut out = Self::default();
        for edit in edits {
            let tile = GlobeTile::from_at(edit.at).expect("validated: (id, 0)");
            if let Some(biome) = edit.biome {
                out.biomes.insert(tile.0, biome);
            }
            if let Some(density) = edit.props {
                out.props.insert(tile.0, density);
            }
            if let Some(shift) = TileShift::of(edit, thresholds, generated[tile.0 as usize]) {
                out.shifts.insert(tile.0, shift);
            }
        }
        out
    }

    /// The biome set by hand on a tile, if any.
    pub(super) fn biome(&self, tile: GlobeTile) -> Option<Biome> {
        if self.biomes.is_empty() {
            return None;
        }
        self.biomes.get(&tile.0).copied()
    }

    /// The prop density set by hand on a tile, if any.
    pub(super) fn props(&self, tile: GlobeTile) -> Option<PropDensity> {
        self.props.get(&tile.0).copied()
    }

    /// The edited raw height of a point held by `holders`, whose generated raw height is `raw`.
    #[inline]
    pub(super) fn apply(&self, holders: &[GlobeTile], raw: f32) -> f32 {
        if self.shifts.is_empty() {
            return raw;
        }
        if let [tile] = holders {
            return self.shifts.get(&tile.0).map_or(raw, |shift| shift.inner(raw));
        }
        let mut deltas = [0.0f32; 3];
        let mut edited = 0;
        for tile in holders {
            if let Some(shift) = self.shifts.get(&tile.0) {
                deltas[edited] = shift.delta;
                edited += 1;
            }
        }
        shared(raw, &mut deltas[..edited], holders.len())
    }
}
