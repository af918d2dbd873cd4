//! The facade's game setup: starts, resources, wonders and regions of a map whose config has a
//! `setup`.

use hexx::Hex;

use super::Terrain;
use crate::setup::{PlacedResource, PlacedWonder, Setup, TileSetup};

impl Terrain {
    /// The game setup (start positions, resources, natural wonders, the fairness report), when
    /// the config has a `setup`.
    #[must_use]
    pub fn setup(&self) -> Option<&Setup> {
        self.pipeline().setup()
    }

    /// What the setup placed on a tile (any copy of it on a wrapping map); `None` without a
    /// setup or outside its area.
    #[must_use]
    pub fn tile_setup(&self, tile: Hex) -> Option<TileSetup<'_>> {
        if !self.contains(tile) {
            return None;
        }
        self.setup()?.at(self.geometry(), tile)
    }

    /// The resource on a tile.
    #[must_use]
    pub fn resource(&self, tile: Hex) -> Option<&PlacedResource> {
        self.tile_setup(tile)?.resource
    }

    /// The natural wonder on a tile.
    #[must_use]
    pub fn wonder(&self, tile: Hex) -> Option<&PlacedWonder> {
        self.tile_setup(tile)?.wonder
    }

    /// The player starting on a tile.
    #[must_use]
    pub fn start(&self, tile: Hex) -> Option<u32> {
        self.tile_setup(tile)?.start
    }
}
