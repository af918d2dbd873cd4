//! How the terrain looks: the game's run-time choices, turned into shader parameters by
//! `params.rs`.

use bevy::prelude::*;

/// How the terrain looks, changed at run time by the game (outlines toggle, textures, fog of
/// war, borders, the lens). Per-tile state itself is in [`TileStates`](crate::TileStates).
#[derive(Resource, Debug, Clone, Reflect)]
#[reflect(Resource)]
pub struct TerrainAppearance {
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
    /// Asset paths of the sea, grass and mountain textures.
    pub texture_paths: [String; 3],
    /// Draw fog of war from [`TileStates::visibility`](crate::TileStates::visibility):
    /// unexplored tiles dark, explored ones desaturated. Off, every tile is drawn as visible.
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
    /// Owner colors: owner `n` takes entry `n - 1`; owners past the list get generated hues.
    pub owner_colors: Vec<Color>,
    /// Draw the tiles' overlay colors ([`TileStates::set_overlay`](crate::TileStates::set_overlay)): the lens.
    pub lens: bool,
    /// Tint of the hovered tile; alpha is the strength.
    pub hover_color: Color,
    /// Tint of selected tiles; alpha is the strength.
    pub selected_color: Color,
    /// Tint of reachable tiles; alpha is the strength.
    pub reachable_color: Color,
    /// Draw the sea floor as a floor (sand near the coast, darker deeper) under the water
    /// surface. Without a shown water surface
    /// ([`WaterSettings::enabled`](crate::WaterSettings::enabled) off) or with this off, the sea
    /// floor is colored as the sea, the thesis' look.
    pub sea_floor: bool,
    /// Water color over the shallows, near coasts (linear blend to `deep_water_color`).
    pub shallow_water_color: Color,
    /// Water color over the deep sea.
    pub deep_water_color: Color,
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

impl Default for TerrainAppearance {
    fn default() -> Self {
        Self {
            outlines: false,
            outline_width: 0.05,
            textures: false,
            texture_scale: 0.25,
            colors: [Color::srgb(0.11, 0.34, 0.72), Color::srgb(0.30, 0.60, 0.20), Color::srgb(0.62, 0.60, 0.58)],
            water_color: Color::srgb(0.16, 0.42, 0.72),
            texture_paths: ["textures/sea.png".into(), "textures/grass.png".into(), "textures/mountain.png".into()],
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
            sea_floor: true,
            shallow_water_color: Color::srgb(0.09, 0.50, 0.62),
            deep_water_color: Color::srgb(0.02, 0.10, 0.28),
            foam_color: Color::srgb(0.93, 0.96, 0.97),
            sea_floor_color: Color::srgb(0.76, 0.70, 0.52),
            deep_water: 0.3,
            foam_width: 0.035,
            waves: 0.35,
        }
    }
}
