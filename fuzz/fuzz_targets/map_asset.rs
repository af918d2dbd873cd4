//! Fuzz target: see `hex_terrain_fuzz::map_asset`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| hex_terrain_fuzz::map_asset(data));
