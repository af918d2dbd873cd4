//! What a globe's compiled tiles are: each tile's kind, center height, biome, terrain, climate
//! and hand-set props, read from the tables [`GlobeTerrain::new`] compiles, and the tile a
//! direction falls in.

use super::GlobeTerrain;
use crate::climate::Climate;
use crate::globe::GlobeTile;
use crate::kind::TileKind;
use crate::ruleset::{TerrainId, TileTerrain};
use crate::vocab::Biome;

impl GlobeTerrain {
    /// A tile's kind, by its center's height; `None` for a tile not of this globe.
    #[must_use]
    pub fn tile_kind(&self, tile: GlobeTile) -> Option<TileKind> {
        self.kinds.get(tile.0 as usize).copied()
    }

    /// A tile's center height (normalised, edited, before manipulation); `None` for a tile not
    /// of this globe.
    #[must_use]
    pub fn tile_height(&self, tile: GlobeTile) -> Option<f32> {
        self.centers.get(tile.0 as usize).copied()
    }

    /// A tile's biome: the one set by hand ([`TileEdit::biome`]) first; else by its climate and
    /// the config's biome table on a globe with a climate (coast or ocean at sea), else by its
    /// kind; `None` for a tile not of this globe.
    pub(crate) fn tile_biome(&self, tile: GlobeTile) -> Option<Biome> {
        self.biomes.get(tile.0 as usize).copied()
    }

    /// What a tile is under the globe's terrain ruleset (its config's default,
    /// [`GlobeTerrain::ruleset`]): its biome's terrain on its landform, with the traits the
    /// config gives the biome; `None` for a tile not of this globe.
    pub(crate) fn tile_terrain(&self, tile: GlobeTile) -> Option<TileTerrain> {
        let (biome, landform) = (self.tile_biome(tile)?, self.landforms[tile.0 as usize]);
        let terrain = TerrainId(biome as u8);
        Some(TileTerrain { terrain, landform, feature: None, traits: self.ruleset.traits(terrain, landform, None) })
    }

    /// The prop density set by hand on a tile ([`TileEdit::props`]), if any.
    pub(in crate::globe) fn tile_props(&self, tile: GlobeTile) -> Option<crate::config::PropDensity> {
        self.edits.props(tile)
    }

    /// A tile's temperature and moisture; `None` when the globe has no climate or for a tile not
    /// of this globe.
    #[must_use]
    pub fn tile_climate(&self, tile: GlobeTile) -> Option<Climate> {
        self.climates.get(tile.0 as usize).copied().flatten()
    }

    /// The tile a direction from the globe's center falls in (any length but zero); `None` for
    /// a zero or non-finite vector.
    #[must_use]
    pub fn tile_at(&self, direction: [f64; 3]) -> Option<GlobeTile> {
        self.grid.tile_at(direction)
    }

    /// A tile's center height after manipulation (normalised).
    pub(in crate::globe) fn center_height(&self, tile: GlobeTile) -> f32 {
        let p = self.fine.center(self.spot(tile));
        self.finish_batch(&[p], &[Some((0, tile))]).next().expect("one point finished").height
    }
}
