//! What the property tests' config generators share: the rules a wrapping map must follow, in
//! one place, so no generator re-derives them (and a change of the rules changes every
//! generator).

use hex_terrain::config::MIN_WRAP_COLUMNS;
use hex_terrain::{MapConfig, MapSize, Orientation, Shape};

/// `c` with `wrap` on or off, made valid for it: a wrapping map is bounded (8x6 for an unbounded
/// one), has at least [`MIN_WRAP_COLUMNS`] columns, an even number of them for flat tiles (odd
/// columns are shoved half a tile), and no gradient shape (it has no west edge to grade from).
#[must_use]
pub fn wrapping(mut c: MapConfig, wrap: bool) -> MapConfig {
    c.wrap = wrap;
    if !wrap {
        return c;
    }
    let (x, z) = c.size.bounds().unwrap_or((8, 6));
    let mut x = x.max(MIN_WRAP_COLUMNS);
    if c.layout.orientation == Orientation::Flat {
        x += x % 2;
    }
    c.size = MapSize::Bounded { x, z };
    if c.shape == Shape::Gradient {
        c.shape = Shape::None;
    }
    c
}
