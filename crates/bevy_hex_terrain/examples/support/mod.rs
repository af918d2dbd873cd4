//! What the examples share besides the plugin: the figures of what a frame draws (printed in
//! screenshot mode, `HexScreenshotPlugin`), and the check that the map file an example loads is
//! where Bevy looks for it.
#![allow(dead_code, reason = "each example uses its own part")]

pub mod render_figures;

/// The default streaming settings, with every chunk full when `HEXTERRAIN_LOD=off` (to compare
/// levels of detail).
pub fn streaming_from_env() -> bevy_hex_terrain::HexStreamingSettings {
    let mut streaming = bevy_hex_terrain::HexStreamingSettings::default();
    if std::env::var("HEXTERRAIN_LOD").is_ok_and(|v| v == "off") {
        streaming.coarse_distance = None;
    }
    streaming
}

/// Exits with status 2 and a message naming the path and `BEVY_ASSET_ROOT` when the map file an
/// example loads at start (`path`, relative to the asset folder) is not where Bevy's asset
/// server looks for it: `assets/` under `BEVY_ASSET_ROOT`, else under the crate when run by
/// `cargo run`, else beside the executable. Without it a binary run from elsewhere would log an
/// error, draw an empty picture and exit 0.
pub fn require_asset(path: &str) {
    let root = bevy::asset::io::file::FileAssetReader::get_base_path().join("assets");
    let file = root.join(path);
    if file.is_file() {
        return;
    }
    let what = if root.is_dir() { "the map file" } else { "the asset folder" };
    eprintln!(
        "error: {what} is missing: {} (the asset folder is {}; set BEVY_ASSET_ROOT to the directory holding \
         `assets/`, e.g. crates/bevy_hex_terrain, or run the example with `cargo run --example`)",
        file.display(),
        root.display()
    );
    std::process::exit(2);
}
