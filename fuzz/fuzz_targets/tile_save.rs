//! Fuzz target: see `hex_terrain_fuzz::tile_save`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| hex_terrain_fuzz::tile_save(data));
