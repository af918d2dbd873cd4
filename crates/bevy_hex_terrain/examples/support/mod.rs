//! What the examples share besides the plugin: the screenshot mode (`HEXTERRAIN_SCREENSHOT`) that
//! the README's pictures and the tests use, and the figures of what a frame draws.
#![allow(dead_code, reason = "each example uses its own part")]

pub mod render_figures;
pub mod screenshot;

/// The default streaming settings, with every chunk full when `HEXTERRAIN_LOD=off` (to compare
/// levels of detail).
pub fn streaming_from_env() -> bevy_hex_terrain::HexStreamingSettings {
    let mut streaming = bevy_hex_terrain::HexStreamingSettings::default();
    if std::env::var("HEXTERRAIN_LOD").is_ok_and(|v| v == "off") {
        streaming.coarse_distance = None;
    }
    streaming
}
