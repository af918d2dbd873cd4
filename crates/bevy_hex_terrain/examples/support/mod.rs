//! What the examples share besides the plugin: the screenshot mode (`HEXTERRAIN_SCREENSHOT`) that
//! the README's pictures and the tests use, and the figures of what a frame draws.
#![allow(dead_code, reason = "each example uses its own part")]

pub mod render_figures;
pub mod screenshot;
