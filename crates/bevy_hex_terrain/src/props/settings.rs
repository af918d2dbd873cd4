//! The props plugin's settings.

use bevy::prelude::*;

/// The props' settings, owned by [`HexPropsPlugin`](crate::HexPropsPlugin) on a flat map and by
/// [`HexGlobePlugin`](crate::HexGlobePlugin) on a globe. Insert it (before or
/// after the plugins) to change the defaults.
#[derive(Resource, Debug, Clone, Copy, PartialEq, Reflect)]
#[reflect(Resource, Default)]
pub struct HexPropSettings {
    /// Show props (trees, rocks, reeds). Chunks always place them, so turning this off at run
    /// time despawns the props of loaded chunks at once and turning it on spawns them again.
    pub enabled: bool,
    /// Props a chunk keeps at most (the rest are thinned deterministically); applies to chunks
    /// built after a change.
    pub max_per_chunk: usize,
    /// Share of each tile's props that stand, in `[0, 1]`; applies to chunks built after a
    /// change.
    pub density: f32,
    /// Prop entities spawned per frame at most: a new chunk's props appear over a few frames
    /// (the chunks nearest an agent first) rather than all in the frame its mesh does, so no frame
    /// spends milliseconds spawning hundreds of them.
    pub max_spawns_per_frame: usize,
}

impl Default for HexPropSettings {
    fn default() -> Self {
        Self { enabled: true, max_per_chunk: 384, density: 1.0, max_spawns_per_frame: 64 }
    }
}
