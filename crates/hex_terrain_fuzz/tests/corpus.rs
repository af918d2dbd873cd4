//! Replays the fuzz corpus (`fuzz/corpus/<target>`, kept minimised by `scripts/fuzz.sh`) and
//! every input that once broke a property (`fuzz/regressions/<target>`) through the targets'
//! bodies: what the fuzzer found stays fixed, on the stable toolchain, in seconds.

use std::path::{Path, PathBuf};

fn inputs(kind: &str, target: &str) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz").join(kind).join(target);
    let Ok(entries) = std::fs::read_dir(&dir) else { return Vec::new() };
    let mut files: Vec<PathBuf> = entries.filter_map(Result::ok).map(|e| e.path()).filter(|p| p.is_file()).collect();
    files.sort();
    files
}

fn replay(target: &str, body: fn(&[u8])) {
    let corpus = inputs("corpus", target);
    assert!(corpus.len() >= 5, "fuzz/corpus/{target} holds {} inputs: run scripts/fuzz.sh", corpus.len());
    for path in corpus.iter().chain(&inputs("regressions", target)) {
        let data = std::fs::read(path).unwrap();
        let outcome = std::panic::catch_unwind(|| body(&data));
        assert!(outcome.is_ok(), "{target} broke on {}", path.display());
    }
}

#[test]
fn map_text_corpus() {
    replay("map_text", hex_terrain_fuzz::map_text);
}

#[test]
fn heightmap_corpus() {
    replay("heightmap", hex_terrain_fuzz::heightmap);
}

#[test]
fn tile_save_corpus() {
    replay("tile_save", hex_terrain_fuzz::tile_save);
}

#[test]
fn map_asset_corpus() {
    replay("map_asset", hex_terrain_fuzz::map_asset);
}

#[test]
fn edits_corpus() {
    replay("edits", hex_terrain_fuzz::edits);
}

#[test]
fn fog_save_corpus() {
    replay("fog_save", hex_terrain_fuzz::fog_save);
}

#[test]
fn ruleset_corpus() {
    replay("ruleset", hex_terrain_fuzz::ruleset);
}
