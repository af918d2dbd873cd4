//! Fuzz target: see `hex_terrain_fuzz::map_text`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| hex_terrain_fuzz::map_text(data));
