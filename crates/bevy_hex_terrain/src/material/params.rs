//! The terrain shader's uniform parameters, built from the map config and the three plugins'
//! settings that say how the terrain looks ([`Look`]).

use super::HexTerrainMaterialSettings;
use crate::tiles::{FOG_MASK, FogState, HexTileStateStyle, Highlight, MAX_OWNERS, highlight_bit};
use crate::water::HexWaterSettings;
use bevy::prelude::*;
use bevy::render::render_resource::ShaderType;
use hex_terrain::Terrain;

/// Bits of [`TerrainParams::flags`]. The shader receives these values (and
/// [`MAX_OWNERS`]) as shader defs, so Rust and WGSL share one definition.
pub mod flags {
    /// Draw tile outlines.
    pub const OUTLINES: u32 = 1;
    /// Sample the textures instead of flat colors.
    pub const TEXTURES: u32 = 2;
    /// Pointy-topped hexes (flat-topped without).
    pub const POINTY: u32 = 4;
    /// Draw fog of war from the tile states.
    pub const FOG: u32 = 8;
    /// Draw territory borders.
    pub const BORDERS: u32 = 16;
    /// Tint owned tiles in their owner's color.
    pub const TERRITORY_TINT: u32 = 32;
    /// Draw the tiles' overlay colors (the lens).
    pub const LENS: u32 = 64;
    /// Color the sea floor as a floor under a water surface, not as the sea.
    pub const SEA_FLOOR: u32 = 128;
    /// Draw the sea as water in the ground's own pass (the globe's material, which has no water
    /// surface of its own).
    pub const WATER: u32 = 256;
}

/// The shader defs every terrain pipeline gets: the flag bits, the owner palette size and the
/// tile state texel's layout (`tiles/window.rs`), so Rust and WGSL share one definition of each.
pub(crate) const SHADER_DEFS: [(&str, u32); 16] = [
    ("HEX_FLAG_OUTLINES", flags::OUTLINES),
    ("HEX_FLAG_TEXTURES", flags::TEXTURES),
    ("HEX_FLAG_POINTY", flags::POINTY),
    ("HEX_FLAG_FOG", flags::FOG),
    ("HEX_FLAG_BORDERS", flags::BORDERS),
    ("HEX_FLAG_TERRITORY_TINT", flags::TERRITORY_TINT),
    ("HEX_FLAG_LENS", flags::LENS),
    ("HEX_FLAG_SEA_FLOOR", flags::SEA_FLOOR),
    ("HEX_FLAG_WATER", flags::WATER),
    ("HEX_MAX_OWNERS", MAX_OWNERS),
    ("HEX_TEXEL_FOG_MASK", FOG_MASK as u32),
    ("HEX_TEXEL_HOVERED", highlight_bit(Highlight::Hovered) as u32),
    ("HEX_TEXEL_SELECTED", highlight_bit(Highlight::Selected) as u32),
    ("HEX_TEXEL_REACHABLE", highlight_bit(Highlight::Reachable) as u32),
    ("HEX_FOG_EXPLORED", FogState::Explored as u32),
    ("HEX_FOG_VISIBLE", FogState::Visible as u32),
];

/// Uniform parameters of the terrain shader.
#[derive(Debug, Clone, Copy, PartialEq, ShaderType, Reflect)]
pub struct TerrainParams {
    /// Sea layer color (linear).
    pub sea_color: Vec4,
    /// Land layer color (linear).
    pub land_color: Vec4,
    /// Mountain layer color (linear).
    pub mountain_color: Vec4,
    /// Hovered tile tint; alpha is the strength.
    pub hover_color: Vec4,
    /// Selected tiles tint; alpha is the strength.
    pub selected_color: Vec4,
    /// Reachable tiles tint; alpha is the strength.
    pub reachable_color: Vec4,
    /// Unexplored tiles' color (linear).
    pub unexplored_color: Vec4,
    /// Outline color; alpha is the strength.
    pub outline_color: Vec4,
    /// River and lake water color (linear), on meshes with vertex colors.
    pub water_color: Vec4,
    /// Water surface color over the shallows (linear).
    pub shallow_water_color: Vec4,
    /// Water surface color over the deep (linear).
    pub deep_water_color: Vec4,
    /// Shore foam color (linear).
    pub foam_color: Vec4,
    /// Sea floor color at the coast (linear).
    pub sea_floor_color: Vec4,
    /// Depth of water (world units) at which it is fully deep.
    pub deep_water: f32,
    /// Width of the shore foam, in depth of water (world units).
    pub foam_width: f32,
    /// Strength of the waves' normals.
    pub waves: f32,
    /// World height of the sea threshold.
    pub sea_level: f32,
    /// World height of the mountain threshold.
    pub mountain_level: f32,
    /// Blend distance in world height.
    pub blend: f32,
    /// Hex circumradius.
    pub hex_size: f32,
    /// Outline width in world units.
    pub outline_width: f32,
    /// Texture repeats per world unit.
    pub texture_scale: f32,
    /// Territory border width, a fraction of the hex radius.
    pub border_width: f32,
    /// Gap between a tile's edge and its border, a fraction of the hex radius.
    pub border_inset: f32,
    /// Width of the fog's blend across tile borders, a fraction of the hex radius.
    pub fog_softness: f32,
    /// Strength of the territory tint.
    pub tint_strength: f32,
    /// Bits of the drawing switches (outlines, textures, pointy hexes, fog, borders, tint, lens,
    /// sea floor), as the shader defs `HEX_FLAG_*` name them.
    pub flags: u32,
    /// Layers in the texture array (0 without textures).
    pub texture_layers: u32,
    /// The tiles the tile state texture holds: first offset column and row, width and height.
    pub tile_window: IVec4,
    /// `x`: a wrapping map's width in columns (0 when it does not wrap); `y`, `z`: the axial
    /// tile nearest the render frame's origin ([`RenderOrigin`]).
    pub map_wrap: IVec4,
    /// `x`, `y`: the render frame's origin relative to that tile's center, in world `(x, z)`.
    pub origin_offset: Vec4,
}

/// Where the render frame's origin lies in the world: world zero, unless a floating origin (the
/// `big_space` feature) renders positions relative to a far-away cell. The shader finds a
/// fragment's tile from its render position plus this, in integers and small floats, so tile
/// state and outlines stay exact at any distance.
#[derive(Resource, Debug, Clone, Copy, Default, PartialEq, Reflect)]
#[reflect(Resource, Default)]
pub struct RenderOrigin {
    /// The axial tile whose center is nearest the render origin.
    pub tile: IVec2,
    /// The render origin relative to that tile's center, world `(x, z)`.
    pub offset: Vec2,
}

impl RenderOrigin {
    /// The render origin of a frame whose origin is at world `(x, z)` (in f64); `None` past the
    /// world's edge.
    #[must_use]
    pub fn at(terrain: &hex_terrain::Terrain, x: f64, z: f64) -> Option<Self> {
        let tile = terrain.unwrapped_tile_at(x, z)?;
        let [cx, _, cz] = terrain.tile_center(tile)?;
        Some(Self { tile: IVec2::new(tile.x, tile.y), offset: Vec2::new((x - cx) as f32, (z - cz) as f32) })
    }
}

/// Owner colors (linear), player `n` at index `n` (the texel holds `n + 1`, the shader reads
/// index `texel - 1`).
#[derive(Debug, Clone, Copy, PartialEq, ShaderType, Reflect)]
pub struct OwnerColors {
    /// One color an owner.
    pub colors: [Vec4; MAX_OWNERS as usize],
}

impl Default for OwnerColors {
    fn default() -> Self {
        Self { colors: [Vec4::ONE; MAX_OWNERS as usize] }
    }
}

pub(crate) fn linear(c: Color) -> Vec4 {
    Vec4::from_array(c.to_linear().to_f32_array())
}

/// The tile state window as the shader reads it: first offset column and row, width, height.
pub(super) fn window_param((origin, size): (IVec2, UVec2)) -> IVec4 {
    origin.extend(size.x as i32).extend(size.y as i32)
}

/// What the shader draws, from the plugins that own each part: the material's palette and
/// outlines, the tile states' style, the water's look (`None`: no water plugin, so no surface
/// and the sea floor drawn as the sea).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Look<'a> {
    /// The palette, textures and outlines.
    pub material: &'a HexTerrainMaterialSettings,
    /// Fog, borders, tint, lens, highlights.
    pub tiles: &'a HexTileStateStyle,
    /// The water's look.
    pub water: Option<&'a HexWaterSettings>,
}

/// Builds the shader parameters for a map, the look and the tile state window (first offset
/// column and row, size). The map's wrap is the core's ([`hex_terrain::Geometry::wrap`]).
#[must_use]
pub(crate) fn params(terrain: &Terrain, look: Look, window: (IVec2, UVec2), origin: RenderOrigin) -> TerrainParams {
    let config = terrain.config();
    let wrap = terrain.wrap();
    let (appearance, style) = (look.material, look.tiles);
    let water = look.water.copied().unwrap_or(HexWaterSettings { enabled: false, ..HexWaterSettings::default() });
    let t = &config.terrain;
    let max = t.max_elevation;
    let mut bits = 0;
    for (on, bit) in [
        (appearance.outlines, flags::OUTLINES),
        (appearance.textures, flags::TEXTURES),
        (config.layout.orientation == hex_terrain::Orientation::Pointy, flags::POINTY),
        (style.fog_of_war, flags::FOG),
        (style.borders, flags::BORDERS),
        (style.territory_tint, flags::TERRITORY_TINT),
        (style.lens, flags::LENS),
        // The sea floor is drawn as a floor only under a shown water surface.
        (water.sea_floor && water.enabled, flags::SEA_FLOOR),
    ] {
        if on {
            bits |= bit;
        }
    }
    let finite = |v: f32, lo: f32, hi: f32| if v.is_finite() { v.clamp(lo, hi) } else { lo };
    TerrainParams {
        sea_color: linear(appearance.colors[0]),
        land_color: linear(appearance.colors[1]),
        mountain_color: linear(appearance.colors[2]),
        hover_color: linear(style.hover_color),
        selected_color: linear(style.selected_color),
        reachable_color: linear(style.reachable_color),
        unexplored_color: linear(style.unexplored_color),
        outline_color: Vec4::new(0.01, 0.01, 0.01, 0.92),
        water_color: linear(appearance.water_color),
        shallow_water_color: linear(water.shallow_color),
        deep_water_color: linear(water.deep_color),
        foam_color: linear(water.foam_color),
        sea_floor_color: linear(water.sea_floor_color),
        deep_water: finite(water.deep_water, 0.01, 1.0) * t.sea_threshold * max,
        foam_width: finite(water.foam_width, 0.0, 1e3),
        waves: finite(water.waves, 0.0, 4.0),
        sea_level: t.sea_threshold * max,
        mountain_level: t.mountain_threshold * max,
        blend: config.appearance.blend.clamp(0.0, 1.0) * max,
        hex_size: config.layout.hex_size,
        outline_width: appearance.outline_width,
        texture_scale: wrapped_texture_scale(wrap.map(|w| w.width), appearance.texture_scale),
        border_width: finite(style.border_width, 0.0, 1.0),
        border_inset: finite(style.border_inset, 0.0, 1.0),
        fog_softness: finite(style.fog_softness, 0.0, 1.0),
        tint_strength: 0.22,
        flags: bits,
        texture_layers: 0,
        tile_window: window_param(window),
        map_wrap: IVec4::new(wrap.map_or(0, |w| w.columns), origin.tile.x, origin.tile.y, 0),
        origin_offset: origin.offset.extend(0.0).extend(0.0),
    }
}

/// The texture scale, on a wrapping map (one period `width` world units wide) rounded so the
/// map's width holds a whole number of texture repeats: the relief textures continue across the
/// seam.
fn wrapped_texture_scale(width: Option<f64>, scale: f32) -> f32 {
    let Some(width) = width.map(|w| w as f32) else { return scale };
    if !(width.is_finite() && width > 0.0 && scale.is_finite()) {
        return scale;
    }
    (width * scale).round().max(1.0) / width
}

/// The owner palette of the style ([`HexTileStateStyle::owner_color`]), player `n` at index `n`.
#[must_use]
pub(crate) fn owner_colors(style: &HexTileStateStyle) -> OwnerColors {
    OwnerColors { colors: std::array::from_fn(|i| linear(style.owner_color(i as u32))) }
}

#[cfg(test)]
mod tests {
    use hex_terrain::{MapConfig, MapSize, Orientation};

    use super::*;

    /// On a wrapping map the texture scale gives a whole number of repeats across the map's
    /// width (textures continue across the seam), and `map_wrap` carries the width in columns;
    /// elsewhere both are as asked.
    #[test]
    fn wrapping_maps_get_whole_texture_repeats_and_their_width() {
        let appearance = HexTerrainMaterialSettings::default();
        let style = HexTileStateStyle::default();
        let look = Look { material: &appearance, tiles: &style, water: None };
        for (orientation, column) in [(Orientation::Flat, 1.5_f32), (Orientation::Pointy, 3.0_f32.sqrt())] {
            for columns in [44_u32, 84, 106] {
                let mut config = MapConfig { size: MapSize::Bounded { x: columns, z: 20 }, ..MapConfig::default() };
                config.layout.orientation = orientation;
                let plain = params(
                    &Terrain::new(config.clone()).unwrap(),
                    look,
                    (IVec2::ZERO, UVec2::ONE),
                    RenderOrigin::default(),
                );
                assert_eq!(plain.texture_scale, appearance.texture_scale);
                assert_eq!(plain.map_wrap.x, 0);
                config.wrap = true;
                let wrapped = params(
                    &Terrain::new(config.clone()).unwrap(),
                    look,
                    (IVec2::ZERO, UVec2::ONE),
                    RenderOrigin::default(),
                );
                let repeats = wrapped.texture_scale * columns as f32 * column * config.layout.hex_size;
                assert!((repeats - repeats.round()).abs() < 1e-3, "{repeats} repeats across {columns} columns");
                assert!((wrapped.texture_scale / appearance.texture_scale - 1.0).abs() < 0.1);
                assert_eq!(wrapped.map_wrap.x, columns as i32);
            }
        }
    }

    /// Every value the shaders take from Rust (`#{HEX_...}`) in any of their modules (the flat
    /// map's, the shared ones and the globe's) is one of the shader defs, and every shader def
    /// is used: WGSL never holds a copy of a Rust layout.
    #[test]
    fn the_shader_reads_every_layout_from_the_shader_defs() {
        let sources = [
            include_str!("terrain.wgsl"),
            include_str!("shaders/bindings.wgsl"),
            include_str!("shaders/hex.wgsl"),
            include_str!("shaders/ground.wgsl"),
            include_str!("shaders/water.wgsl"),
            include_str!("shaders/tile_state.wgsl"),
            include_str!("shaders/texel.wgsl"),
            include_str!("shaders/triplanar.wgsl"),
            include_str!("../globe/globe.wgsl"),
        ];
        let mut used = std::collections::BTreeSet::new();
        for source in sources {
            for (i, _) in source.match_indices("#{HEX_") {
                let name = &source[i + 2..];
                used.insert(&name[..name.find('}').unwrap()]);
            }
        }
        // The globe's material gives its shader one def more, its state texture's row.
        let defined: std::collections::BTreeSet<&str> =
            SHADER_DEFS.iter().map(|(name, _)| *name).chain(["HEX_GLOBE_ROW"]).collect();
        assert_eq!(used, defined);
        // The texel bits do not overlap, and the fog states fit the fog's mask.
        let bits = [FOG_MASK, highlight_bit(Highlight::Hovered), highlight_bit(Highlight::Selected)];
        let bits = [bits[0], bits[1], bits[2], highlight_bit(Highlight::Reachable)];
        for (i, a) in bits.iter().enumerate() {
            for b in &bits[i + 1..] {
                assert_eq!(a & b, 0, "{a:#b} and {b:#b} overlap");
            }
        }
        assert_eq!(FogState::Visible as u16 & !FOG_MASK, 0);
    }
}
