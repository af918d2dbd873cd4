//! Per-tile game state drawn by the terrain material: fog of war, territory, lens overlays and
//! highlights. The game writes [`TileStates`]; [`HexTileStatePlugin`] keeps its GPU window on
//! the map and around the loaded chunks and, after `Update`, packs the changed rows into
//! [`TileStateUpload`], which the material plugin copies into the texture the shader reads
//! (`material/tile_texture.rs`). No mesh is touched.

mod error;
mod state;
mod store;
mod style;
pub(crate) mod texel;
mod window;

#[cfg(test)]
mod tests;

use bevy::prelude::*;

pub use hex_terrain::save::{SaveError, TileStateSave};
pub use state::{FogState, Highlight, MAX_OWNERS, TileStateError, TileStates};
pub use style::HexTileStateStyle;
#[cfg(feature = "render")]
pub(crate) use texel::{FOG_MASK, bit as highlight_bit};
#[cfg(feature = "render")]
pub(crate) use window::TEXEL_BYTES;
pub use window::{Texel, TileStateUpload};

use crate::{ChunkStreamer, HexMap, HexTerrainSystems};

/// The tile state plugin's systems in `PostUpdate`, public so a system reading this frame's
/// [`TileStates::changed_tiles`] can run before them.
#[derive(SystemSet, Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum HexTileStateSystems {
    /// Packs the changed rows for the GPU and starts the next frame's list of changed tiles.
    Pack,
}

/// Parameters of the tile state store.
#[derive(Resource, Debug, Clone, PartialEq, Reflect)]
#[reflect(Resource)]
pub struct HexTileStateSettings {
    /// Largest window of tiles the GPU texture holds (8 bytes a tile). A bounded map that fits
    /// is held whole; a larger or unbounded map gets a window of this size that follows the
    /// loaded chunks, which must fit in it (tiles outside draw as unexplored and plain). Sides
    /// are clamped to `1..=4096`.
    pub max_window: UVec2,
}

impl Default for HexTileStateSettings {
    fn default() -> Self {
        Self { max_window: UVec2::splat(512) }
    }
}

/// Figures of the tile state uploads.
#[derive(Resource, Debug, Clone, Default, Reflect)]
#[reflect(Resource)]
pub struct HexTileStateStats {
    /// Bytes packed for the GPU in the last frame (0 when nothing changed).
    pub last_upload_bytes: usize,
    /// Bytes packed since the start.
    pub total_upload_bytes: u64,
    /// Frames that uploaded anything.
    pub uploads: u64,
    /// Times the window moved or was resized.
    pub window_moves: u64,
}

/// [`TileStates`], [`HexTileStateSettings`], [`HexTileStateStyle`] (how the states are drawn),
/// [`HexTileStateStats`] and [`TileStateUpload`], with the
/// systems keeping the window on the map ([`HexTerrainSystems::Tiles`]) and packing the
/// changes (`PostUpdate`). Works headless; the material plugin draws it. Its settings are
/// the [`HexTileStateSettings`] resource: a value inserted before the plugin is added is kept.
#[derive(Debug, Clone, Copy, Default)]
pub struct HexTileStatePlugin;

impl Plugin for HexTileStatePlugin {
    fn build(&self, app: &mut App) {
        if !app.is_plugin_added::<crate::HexMapPlugin>() {
            panic!("HexTileStatePlugin needs HexMapPlugin: add HexTerrainPlugins (or HexMapPlugin before it)");
        }
        app.init_resource::<HexTileStateSettings>()
            .init_resource::<TileStates>()
            .init_resource::<HexTileStateStyle>()
            .init_resource::<HexTileStateStats>()
            .init_resource::<TileStateUpload>()
            .register_type::<TileStates>()
            .register_type::<HexTileStateSettings>()
            .register_type::<HexTileStateStyle>()
            .register_type::<HexTileStateStats>()
            .register_type::<TileStateUpload>()
            .register_type::<FogState>()
            .register_type::<Highlight>()
            // Placed before `Startup`, so the material starts with the window's texture.
            .add_systems(PreStartup, (follow_map, follow_chunks).chain())
            // The map's bounds as soon as a map applies; the window once the frame's chunks are in.
            .add_systems(Update, follow_map.in_set(HexTerrainSystems::Map).after(crate::map::MapAssets))
            .add_systems(Update, follow_chunks.in_set(HexTerrainSystems::Tiles))
            .add_systems(PostUpdate, pack_upload.in_set(HexTileStateSystems::Pack));
    }
}

/// Follows the map (see [`TileStates::follow`]): runs at the end of
/// [`HexTerrainSystems::Map`], so a system after that set that sees a new [`HexMap`] writes the
/// states of its tiles.
fn follow_map(map: Res<HexMap>, mut states: ResMut<TileStates>) {
    if map.is_changed() {
        states.follow(map.terrain().geometry(), map.map_id(), map.is_waiting_for_asset(), map.config_generation());
    }
}

/// Places the window: the whole map when it fits, else around the loaded chunks, following their
/// center in steps of a sixteenth of the window (and at once when they leave it).
fn follow_chunks(
    map: Res<HexMap>,
    settings: Res<HexTileStateSettings>,
    streamer: Option<Res<ChunkStreamer>>,
    mut states: ResMut<TileStates>,
    mut stats: ResMut<HexTileStateStats>,
    mut warned: Local<bool>,
) {
    let terrain = map.terrain();
    let max = settings.max_window.clamp(UVec2::ONE, UVec2::splat(4096));
    let bounds = terrain.bounds().map(|b| IRect::new(b.min[0], b.min[1], b.max[0], b.max[1]));
    let size = bounds.map_or(max, |b| b.size().as_uvec2().max(UVec2::ONE).min(max));
    let (origin, current) = states.window();
    let mut want = origin;
    if let Some(b) = bounds.filter(|b| b.size().as_uvec2() == size) {
        want = b.min;
    } else {
        // The loaded chunks' tiles (or the wanted ones before any loaded).
        let mut area: Option<IRect> = None;
        if let Some(streamer) = &streamer {
            let chunks = streamer.loaded_chunks().chain(streamer.wanted().map(|(c, _)| c));
            for chunk in chunks {
                let r = chunk.rect(terrain.chunk_size());
                let r = IRect::new(r.min[0], r.min[1], r.max[0], r.max[1]);
                area = Some(area.map_or(r, |a| a.union(r)));
            }
        }
        let area = area.unwrap_or_else(|| IRect::from_center_size(IVec2::ZERO, IVec2::ONE));
        if (area.width() as u32 > size.x || area.height() as u32 > size.y) && !*warned {
            warn!(
                "hex terrain: the loaded chunks span {}x{} tiles, more than the tile state window of {}x{} \
                 (HexTileStateSettings::max_window): tiles outside it draw as unexplored",
                area.width(),
                area.height(),
                size.x,
                size.y
            );
            *warned = true;
        }
        let inside = |o: IVec2| {
            let w = IRect::from_corners(o, o + size.as_ivec2());
            w.contains(area.min) && w.contains(area.max - IVec2::ONE)
        };
        // The window follows the loaded area's center in steps of a sixteenth of its size, so a
        // move rewrites a strip of that width (about half a millisecond for a 512-tile window),
        // not half the window at once when the area reaches its edge.
        let step = (size.as_ivec2() / 16).max(IVec2::ONE);
        let drift = (area.center() - (origin + size.as_ivec2() / 2)).abs();
        if current != size || !inside(origin) || drift.x >= step.x || drift.y >= step.y {
            want = area.center() - size.as_ivec2() / 2;
            if let Some(b) = bounds {
                want = want.clamp(b.min, b.max - size.as_ivec2());
            }
        }
    }
    if want != origin || size != current {
        states.refill_window(want, size);
        stats.window_moves += 1;
    }
}

/// Packs the rows changed this frame for the GPU (a frame without changes touches nothing) and
/// starts the next frame's list of changed tiles.
fn pack_upload(
    mut states: ResMut<TileStates>,
    mut upload: ResMut<TileStateUpload>,
    mut stats: ResMut<HexTileStateStats>,
) {
    states.bypass_change_detection().clear_journal();
    if !states.has_upload() {
        if stats.last_upload_bytes != 0 {
            stats.last_upload_bytes = 0;
        }
        return;
    }
    *upload = states.bypass_change_detection().take_upload();
    stats.last_upload_bytes = upload.bytes();
    stats.total_upload_bytes += upload.bytes() as u64;
    stats.uploads += 1;
}
