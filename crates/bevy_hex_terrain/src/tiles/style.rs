//! How the tile states are drawn: fog of war, territory borders and tint, the lens and the
//! highlights. The material turns it into shader parameters; the minimap and the props' fog read
//! it too, so every view of a tile's state agrees.

use bevy::prelude::*;

/// How [`TileStates`](crate::TileStates) are drawn, changed at run time by the game (fog of war
/// on or off, borders, the lens). Owned by [`HexTileStatePlugin`](crate::HexTileStatePlugin);
/// insert it (before or after the plugins) to change the defaults.
#[derive(Resource, Debug, Clone, PartialEq, Reflect)]
#[reflect(Resource, Default)]
pub struct HexTileStateStyle {
    /// Draw fog of war from [`TileStates::visibility`](crate::TileStates::visibility):
    /// unexplored tiles dark, explored ones desaturated, props on unexplored tiles hidden. Off,
    /// every tile is drawn as visible.
    pub fog_of_war: bool,
    /// Color of unexplored tiles.
    pub unexplored_color: Color,
    /// Width of the fog's blend across tile borders, a fraction of the hex radius (0: hard).
    pub fog_softness: f32,
    /// Draw a line in the owner's color inside every owned tile's edges that border another
    /// owner or nobody.
    pub borders: bool,
    /// Border line width, a fraction of the hex radius.
    pub border_width: f32,
    /// Gap between a tile's edge and its border line, a fraction of the hex radius.
    pub border_inset: f32,
    /// Tint owned tiles lightly in their owner's color.
    pub territory_tint: bool,
    /// Owner colors: player `n` takes entry `n`; players past the list get generated hues
    /// ([`owner_color`](Self::owner_color)).
    pub owner_colors: Vec<Color>,
    /// Draw the tiles' overlay colors ([`TileStates::set_overlay`](crate::TileStates::set_overlay)): the lens.
    pub lens: bool,
    /// Tint of the hovered tile; alpha is the strength.
    pub hover_color: Color,
    /// Tint of selected tiles; alpha is the strength.
    pub selected_color: Color,
    /// Tint of reachable tiles; alpha is the strength.
    pub reachable_color: Color,
}

impl Default for HexTileStateStyle {
    fn default() -> Self {
        Self {
            fog_of_war: false,
            unexplored_color: Color::srgb(0.11, 0.10, 0.09),
            fog_softness: 0.35,
            borders: true,
            border_width: 0.14,
            border_inset: 0.03,
            territory_tint: true,
            owner_colors: vec![
                Color::srgb(0.90, 0.15, 0.12),
                Color::srgb(0.15, 0.45, 0.95),
                Color::srgb(0.98, 0.80, 0.10),
                Color::srgb(0.60, 0.20, 0.85),
                Color::srgb(0.95, 0.50, 0.10),
                Color::srgb(0.10, 0.80, 0.75),
                Color::srgb(0.95, 0.40, 0.70),
                Color::srgb(0.95, 0.95, 0.95),
            ],
            lens: false,
            hover_color: Color::srgba(1.0, 0.95, 0.55, 0.45),
            selected_color: Color::srgba(1.0, 0.85, 0.25, 0.5),
            reachable_color: Color::srgba(0.35, 0.75, 1.0, 0.4),
        }
    }
}

impl HexTileStateStyle {
    /// The color of player `owner` (from 0): its entry in [`owner_colors`](Self::owner_colors),
    /// or past the list a hue spaced by the golden angle.
    #[must_use]
    pub fn owner_color(&self, owner: u32) -> Color {
        let i = owner as usize;
        self.owner_colors.get(i).copied().unwrap_or_else(|| Color::hsl((i as f32 * 137.508) % 360.0, 0.75, 0.55))
    }
}
