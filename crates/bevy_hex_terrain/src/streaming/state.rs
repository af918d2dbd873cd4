//! What the streaming systems share: the streamer, its figures, the map and the settings, as one
//! system parameter.

use bevy::ecs::system::SystemParam;
use bevy::prelude::*;

use super::{ChunkStreamer, HexStreamingSettings, HexStreamingStats};
use crate::map::HexMap;

/// The streaming state a streaming system reads and writes.
#[derive(SystemParam)]
pub(crate) struct StreamState<'w> {
    /// Which chunks are wanted, loaded and current.
    pub streamer: ResMut<'w, ChunkStreamer>,
    /// The figures.
    pub stats: ResMut<'w, HexStreamingStats>,
    /// The map.
    pub map: Res<'w, HexMap>,
    /// The settings.
    pub settings: Res<'w, HexStreamingSettings>,
}
