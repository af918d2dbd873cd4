//! The water plugin's settings: whether the surface shows, how deep rivers and lakes run, and
//! how the water looks.

use bevy::prelude::*;

/// The water surface's settings, owned by [`HexWaterPlugin`](crate::HexWaterPlugin). Insert it
/// (before or after the plugins) to change the defaults; changes apply the next frame, except
/// [`river_depth`](Self::river_depth), which applies to chunks built after the change.
#[derive(Resource, Debug, Clone, Copy, PartialEq, Reflect)]
#[reflect(Resource, Default)]
pub struct HexWaterSettings {
    /// Show the water surface over the sea, rivers and lakes (chunks always build it, so
    /// turning it on or off at run time takes effect at once).
    pub enabled: bool,
    /// Height of river and lake water over a fully covered vertex, a fraction of the hex size.
    pub river_depth: f32,
    /// Draw the sea floor as a floor (sand near the coast, darker deeper) under the water
    /// surface. With the surface hidden ([`enabled`](Self::enabled) off) or with this off, the
    /// sea floor is colored as the sea, the thesis' look.
    pub sea_floor: bool,
    /// Water color over the shallows, near coasts (linear blend to `deep_color`).
    pub shallow_color: Color,
    /// Water color over the deep sea.
    pub deep_color: Color,
    /// Foam color at the shore.
    pub foam_color: Color,
    /// Sea floor color at the coast (darkening with depth).
    pub sea_floor_color: Color,
    /// Depth of water at which it is fully deep (opaque, deep color), a fraction of the sea
    /// level's height above the lowest floor.
    pub deep_water: f32,
    /// Width of the shore foam, in depth of water (world units).
    pub foam_width: f32,
    /// Strength of the animated waves' normals, 0 for a still surface.
    pub waves: f32,
}

impl Default for HexWaterSettings {
    fn default() -> Self {
        Self {
            enabled: true,
            river_depth: 0.12,
            sea_floor: true,
            shallow_color: Color::srgb(0.09, 0.50, 0.62),
            deep_color: Color::srgb(0.02, 0.10, 0.28),
            foam_color: Color::srgb(0.93, 0.96, 0.97),
            sea_floor_color: Color::srgb(0.76, 0.70, 0.52),
            deep_water: 0.3,
            foam_width: 0.035,
            waves: 0.35,
        }
    }
}
