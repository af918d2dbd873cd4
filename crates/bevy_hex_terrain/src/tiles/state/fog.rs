//! One player's view of a fog of war kept for every player ([`FogOfWar`], the core's): what a
//! hotseat game, a replay or a client of a server shows.

use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use hex_terrain::FogOfWar;

use super::{FOG_MASK, FogState, TileStateError, TileStates, texel};

impl TileStates {
    /// Shows `player`'s fog: each tile's visibility becomes what the fog says `player` knows of
    /// it (a tile it has not seen unexplored), the other states (owners, overlays, highlights)
    /// untouched. Its cost is the tiles stored here plus the tiles the player has seen.
    ///
    /// ```
    /// use bevy::prelude::*;
    /// use bevy_hex_terrain::hex_terrain::FogOfWar;
    /// use bevy_hex_terrain::prelude::*;
    ///
    /// /// Every player's fog, kept by the game (a server keeps the same without Bevy).
    /// #[derive(Resource)]
    /// struct Fogs(FogOfWar);
    ///
    /// /// The player at the screen; another in a hotseat game's next turn.
    /// #[derive(Resource)]
    /// struct Viewer(u32);
    ///
    /// fn show(fogs: Res<Fogs>, viewer: Res<Viewer>, mut states: ResMut<TileStates>) {
    ///     if fogs.is_changed() || viewer.is_changed() {
    ///         if let Err(error) = states.show_fog(&fogs.0, viewer.0) {
    ///             warn!("{error}");
    ///         }
    ///     }
    /// }
    /// # App::new().add_systems(Update, show.after(HexTerrainSystems::Map));
    /// ```
    ///
    /// # Errors
    /// [`TileStateError::NoSuchPlayer`] for a player the fog does not have,
    /// [`TileStateError::OutsideMap`] for a fog of a larger map; nothing changes then.
    pub fn show_fog(&mut self, fog: &FogOfWar, player: u32) -> Result<(), TileStateError> {
        if player >= fog.players() {
            return Err(TileStateError::NoSuchPlayer { player, players: fog.players() });
        }
        let seen = fog
            .seen(player)
            .map(|(tile, state)| Ok((self.check(tile)?, state)))
            .collect::<Result<HashMap<IVec2, FogState>, TileStateError>>()?;
        // What another view showed and this player has not seen goes dark again.
        for (oc, texel) in self.tiles.stored() {
            if texel[0] & FOG_MASK != 0 && !seen.contains_key(&oc) {
                self.update(oc, |t| *t = texel::with_fog(*t, FogState::Unexplored));
            }
        }
        for (oc, state) in seen {
            self.update(oc, |t| *t = texel::with_fog(*t, state));
        }
        Ok(())
    }
}
