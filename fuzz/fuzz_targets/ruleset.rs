//! Fuzz target: see `hex_terrain_fuzz::ruleset`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| hex_terrain_fuzz::ruleset(data));
