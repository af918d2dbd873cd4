//! The material's own settings: the layer palette, textures and outlines. How tile states and
//! the water look is set with their plugins ([`HexTileStateStyle`](crate::HexTileStateStyle),
//! [`HexWaterSettings`](crate::HexWaterSettings)).

use bevy::prelude::*;

/// How the terrain's ground is drawn, changed at run time by the game (outlines toggle,
/// textures). Owned by [`HexTerrainMaterialPlugin`](crate::HexTerrainMaterialPlugin); insert it
/// (before or after the plugins) to change the defaults.
#[derive(Resource, Debug, Clone, PartialEq, Reflect)]
#[reflect(Resource, Default)]
pub struct HexTerrainMaterialSettings {
    /// Draw tile outlines (thesis figure 47).
    pub outlines: bool,
    /// Outline width in world units.
    pub outline_width: f32,
    /// Use the textures instead of flat colors (figures 40-41 vs 36-39).
    pub textures: bool,
    /// Texture repeats per world unit.
    pub texture_scale: f32,
    /// Layer colors, sea, land, mountain (maps without climate or rivers).
    pub colors: [Color; 3],
    /// River and lake color (maps with rivers; biome colors come with the mesh).
    pub water_color: Color,
    /// Asset paths of the texture array's layers, in order (at most
    /// [`MAX_TEXTURE_LAYERS`](crate::MAX_TEXTURE_LAYERS), all of one size): the thesis' maps
    /// draw layers 0, 1 and 2 (sea, land, mountain) by height; a map with climate or rivers
    /// draws each tile with its terrain's layer (`Look::texture` of its ruleset; the default
    /// ruleset's biomes take 0, 1 and 2), a layer past the list with the last.
    pub texture_paths: Vec<String>,
}

impl Default for HexTerrainMaterialSettings {
    fn default() -> Self {
        Self {
            outlines: false,
            outline_width: 0.05,
            textures: false,
            texture_scale: 0.25,
            colors: [Color::srgb(0.11, 0.34, 0.72), Color::srgb(0.30, 0.60, 0.20), Color::srgb(0.62, 0.60, 0.58)],
            water_color: Color::srgb(0.16, 0.42, 0.72),
            texture_paths: ["sea", "grass", "mountain", "sand", "snow", "forest", "ash"]
                .map(|name| format!("textures/{name}.png"))
                .into(),
        }
    }
}
