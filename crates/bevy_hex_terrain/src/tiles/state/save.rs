//! Save games of [`TileStates`]: every tile's state to a [`TileStateSave`] and back, bit for
//! bit (the format, its encodings and its checks are the core's `hex_terrain::save`).

use bevy::prelude::*;
use hex_terrain::save::{SaveError, SavedMap, SavedTile, TileStateSave};
use hex_terrain::{Geometry, MapConfig};

use super::{FOG_MASK, FogState, Highlight, TileStates, bit};

impl TileStates {
    /// The state of every tile, as a save of `config`'s map (the map these states follow): the
    /// tiles not in the default state, row by row. Write it with
    /// [`TileStateSave::to_ron`] or [`TileStateSave::to_bytes`]; [`TileStates::load`] reads it
    /// back bit for bit.
    #[must_use]
    pub fn save(&self, config: &MapConfig) -> TileStateSave {
        let mut stored = self.tiles.stored();
        stored.sort_unstable_by_key(|(oc, _)| (oc.y, oc.x));
        let tiles = stored
            .into_iter()
            .map(|(oc, [t0, owner, rg, ba])| SavedTile {
                at: (oc.x, oc.y),
                fog: FogState::from_bits((t0 & FOG_MASK) as u8).unwrap_or(FogState::Visible),
                // The texel holds the player + 1 (below 65); 0 is nobody.
                owner: owner.checked_sub(1).map(|o| o as u8),
                overlay: (rg != 0 || ba != 0).then_some([rg as u8, (rg >> 8) as u8, ba as u8, (ba >> 8) as u8]),
                highlights: Highlight::ALL.into_iter().filter(|&h| t0 & bit(h) != 0).collect(),
            })
            .collect();
        TileStateSave { version: hex_terrain::save::SAVE_VERSION, map: SavedMap::of(config), tiles }
    }

    /// Replaces every tile's state with a save's, after checking it against `config`'s map
    /// ([`TileStateSave::check`]: the same map, a format this version reads, every tile on the
    /// map). The texture is uploaded again after `Update`, as for any write.
    ///
    /// # Errors
    /// The save's first problem ([`SaveError`]); then nothing changes.
    pub fn load(&mut self, config: &MapConfig, save: &TileStateSave) -> Result<(), SaveError> {
        save.check(config)?;
        self.set_map(&Geometry::new(config), false);
        for tile in &save.tiles {
            let oc = IVec2::new(tile.at.0, tile.at.1);
            let highlights = tile.highlights.iter().fold(0, |b, &h| b | bit(h));
            let [r, g, b, a] = tile.overlay.unwrap_or([0; 4]).map(u16::from);
            let texel =
                [tile.fog as u16 | highlights, tile.owner.map_or(0, |o| u16::from(o) + 1), r | g << 8, b | a << 8];
            self.store(oc, [0; 4], texel);
            for h in tile.highlights.iter().copied() {
                let hex = self.geometry.tile_from_offset(oc.to_array());
                self.highlighted[h as usize].insert(hex);
            }
        }
        Ok(())
    }

    /// [`TileStates::save`] as RON text.
    #[must_use]
    pub fn save_ron(&self, config: &MapConfig) -> String {
        self.save(config).to_ron()
    }

    /// [`TileStates::save`] as compact binary (CBOR with a header and a CRC-32).
    #[must_use]
    pub fn save_bytes(&self, config: &MapConfig) -> Vec<u8> {
        self.save(config).to_bytes()
    }

    /// [`TileStates::load`] from RON text.
    ///
    /// # Errors
    /// Malformed RON (with the line and column) or the save's first problem; nothing changes.
    pub fn load_ron(&mut self, config: &MapConfig, text: &str) -> Result<(), SaveError> {
        self.load(config, &TileStateSave::from_ron(text)?)
    }

    /// [`TileStates::load`] from compact binary.
    ///
    /// # Errors
    /// A damaged file ([`SaveError::Corrupt`]) or the save's first problem; nothing changes.
    pub fn load_bytes(&mut self, config: &MapConfig, bytes: &[u8]) -> Result<(), SaveError> {
        self.load(config, &TileStateSave::from_bytes(bytes)?)
    }
}
