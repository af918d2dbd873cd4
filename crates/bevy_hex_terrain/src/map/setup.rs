//! A game set up on the map shown: [`SetUpGame`] places a game setup (starts, resources,
//! wonders, the fairness report) on the loaded map without loading it again, and [`GameSetUp`]
//! tells when the starts are there, for maps set up that way and for maps whose config has a
//! `setup`.

use bevy::prelude::*;
use hex_terrain::SetupConfig;

use super::{HexMap, HexMapError};

/// Asks the plugin to set up a game on the map shown (a map-type preset, say, which comes
/// without one): the setup is placed on the map's terrain as it is (the same tiles, bit for
/// bit, the same [`HexMap::map_id`](crate::HexMap::map_id)), and [`GameSetUp`] follows in the
/// same frame. It costs the setup's placement (about 16 ms for 12 players on Civilization VI's
/// Huge size, on the main thread) and a rebuild of the loaded chunks, whose markers show the
/// starts, resources and wonders; the world builder's undo history starts anew (the edits stay).
/// A setup that does not fit the map (too many players for its land) is a [`HexMapError`], the
/// map unchanged. Only the last request of a frame counts; one sent while a map file loads
/// applies to that map when it arrives. The map keeps the setup over edits and hot reloads of
/// its file (unless the file brings a `setup` of its own); another map ([`LoadHexMap`]) starts
/// without it.
///
/// [`LoadHexMap`]: crate::LoadHexMap
#[derive(Message, Debug, Clone, Reflect)]
pub struct SetUpGame(pub SetupConfig);

/// The game setup's starts are there: [`HexMap::setup`](crate::HexMap::setup) holds them. Sent
/// when [`SetUpGame`] placed a setup, and for a map whose config has a `setup`, once, beside
/// [`TerrainReady`](crate::TerrainReady) (not for its edits or hot reloads, which keep the
/// players where they are). The one place to put the players on the map, whichever way it was
/// set up.
#[derive(Message, Debug, Clone, Copy, PartialEq, Eq, Reflect)]
pub struct GameSetUp {
    /// The map set up.
    pub map_id: u64,
    /// Its generation then.
    pub generation: u64,
}

/// Places the last [`SetUpGame`] of the frame (or the one waiting for a map file).
pub(super) fn set_up_requested(
    mut requests: MessageReader<SetUpGame>,
    mut map: ResMut<HexMap>,
    mut pending: Local<Option<SetupConfig>>,
    mut set_up: MessageWriter<GameSetUp>,
    mut errors: MessageWriter<HexMapError>,
) {
    if let Some(SetUpGame(setup)) = requests.read().last() {
        *pending = Some(setup.clone());
    }
    if map.is_waiting_for_asset() {
        return;
    }
    let Some(setup) = pending.take() else { return };
    match map.terrain().with_setup(Some(setup.clone())) {
        Ok(terrain) => {
            info!("hex terrain: a game for {} players set up on map {:?}", setup.players, terrain.config().name);
            map.set_up(terrain, setup);
            set_up.write(GameSetUp { map_id: map.map_id(), generation: map.generation() });
        }
        Err(e) => {
            let error = HexMapError::invalid(&format!("the game setup of map {:?}", map.config().name), &e);
            error!("{error}");
            errors.write(error);
        }
    }
}
