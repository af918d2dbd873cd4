//! The terrain material: `StandardMaterial` (so PBR lighting and shadows still work) extended
//! with a fragment shader that blends sea, land and mountain by height as thesis Algorithm 5
//! does, in flat colors or textures, and draws tile outlines and highlights. The same shader
//! serves forward and deferred cameras.

use crate::tiles::{MAX_OWNERS, TileStates};
use bevy::asset::{AssetPath, embedded_asset, embedded_path};
use bevy::image::{ImageAddressMode, ImageLoaderSettings, ImageSampler, ImageSamplerDescriptor};
use bevy::mesh::MeshVertexBufferLayoutRef;
use bevy::pbr::{ExtendedMaterial, MaterialExtension, MaterialExtensionKey, MaterialExtensionPipeline};
use bevy::prelude::*;
use bevy::render::render_resource::{AsBindGroup, RenderPipelineDescriptor, ShaderType, SpecializedMeshPipelineError};
use bevy::shader::{ShaderDefVal, ShaderRef};
use hex_terrain::MapConfig;
pub use tile_texture::TileStateTexture;

mod tile_texture;

/// The chunk material.
pub type HexTerrainMaterial = ExtendedMaterial<StandardMaterial, HexTerrainExtension>;

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
}

/// The shader defs every terrain pipeline gets: the flag bits and the owner palette size.
const SHADER_DEFS: [(&str, u32); 8] = [
    ("HEX_FLAG_OUTLINES", flags::OUTLINES),
    ("HEX_FLAG_TEXTURES", flags::TEXTURES),
    ("HEX_FLAG_POINTY", flags::POINTY),
    ("HEX_FLAG_FOG", flags::FOG),
    ("HEX_FLAG_BORDERS", flags::BORDERS),
    ("HEX_FLAG_TERRITORY_TINT", flags::TERRITORY_TINT),
    ("HEX_FLAG_LENS", flags::LENS),
    ("HEX_MAX_OWNERS", MAX_OWNERS as u32),
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
    /// Bits of [`flags`].
    pub flags: u32,
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
    /// The render origin of a frame whose origin is at world `(x, z)` (in f64).
    #[must_use]
    pub fn at(terrain: &hex_terrain::Terrain, x: f64, z: f64) -> Self {
        let tile = terrain.unwrapped_tile_at(x, z);
        let [cx, _, cz] = terrain.tile_center(tile);
        Self { tile: IVec2::new(tile.x, tile.y), offset: Vec2::new((x - cx) as f32, (z - cz) as f32) }
    }
}

/// Owner colors (linear), owner `n` at index `n - 1`.
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

/// The extension part of [`HexTerrainMaterial`].
#[derive(Asset, AsBindGroup, Reflect, Debug, Clone)]
pub struct HexTerrainExtension {
    /// Shader parameters.
    #[uniform(100)]
    pub params: TerrainParams,
    /// Sea texture (used in texture mode).
    #[texture(101)]
    #[sampler(102)]
    pub sea_texture: Option<Handle<Image>>,
    /// Grass texture (used in texture mode).
    #[texture(103)]
    #[sampler(104)]
    pub land_texture: Option<Handle<Image>>,
    /// Mountain texture (used in texture mode).
    #[texture(105)]
    #[sampler(106)]
    pub mountain_texture: Option<Handle<Image>>,
    /// The tile states ([`TileStates`]), written in place by `tile_texture.rs`.
    #[texture(107, sample_type = "u_int")]
    pub tile_state: Handle<Image>,
    /// Owner colors.
    #[uniform(108)]
    pub owners: OwnerColors,
}

fn shader() -> ShaderRef {
    ShaderRef::Path(AssetPath::from_path_buf(embedded_path!("terrain.wgsl")).with_source("embedded"))
}

impl MaterialExtension for HexTerrainExtension {
    fn fragment_shader() -> ShaderRef {
        shader()
    }

    fn deferred_fragment_shader() -> ShaderRef {
        shader()
    }

    fn specialize(
        _pipeline: &MaterialExtensionPipeline,
        descriptor: &mut RenderPipelineDescriptor,
        _layout: &MeshVertexBufferLayoutRef,
        _key: MaterialExtensionKey<Self>,
    ) -> Result<(), SpecializedMeshPipelineError> {
        if let Some(fragment) = descriptor.fragment.as_mut() {
            fragment.shader_defs.extend(SHADER_DEFS.map(|(name, value)| ShaderDefVal::UInt(name.into(), value)));
        }
        Ok(())
    }
}

/// How the terrain looks, changed at run time by the game (outlines toggle, textures, fog of
/// war, borders, the lens). Per-tile state itself is in [`TileStates`].
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
    /// Draw fog of war from [`TileStates::visibility`]: unexplored tiles dark, explored ones
    /// desaturated. Off, every tile is drawn as visible.
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
    /// Draw the tiles' overlay colors ([`TileStates::set_overlay`]): the lens.
    pub lens: bool,
    /// Tint of the hovered tile; alpha is the strength.
    pub hover_color: Color,
    /// Tint of selected tiles; alpha is the strength.
    pub selected_color: Color,
    /// Tint of reachable tiles; alpha is the strength.
    pub reachable_color: Color,
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
        }
    }
}

/// The shared material handle of the chunks.
#[derive(Resource, Debug, Clone)]
pub struct HexTerrainMaterialHandle(pub Handle<HexTerrainMaterial>);

fn linear(c: Color) -> Vec4 {
    Vec4::from_array(c.to_linear().to_f32_array())
}

/// The tile state window as the shader reads it: first offset column and row, width, height.
fn window_param((origin, size): (IVec2, UVec2)) -> IVec4 {
    origin.extend(size.x as i32).extend(size.y as i32)
}

/// Builds the shader parameters for a map config, an appearance and the tile state window
/// (first offset column and row, size).
#[must_use]
pub fn params(
    config: &MapConfig,
    appearance: &TerrainAppearance,
    window: (IVec2, UVec2),
    origin: RenderOrigin,
) -> TerrainParams {
    let t = &config.terrain;
    let max = t.max_elevation;
    let mut bits = 0;
    for (on, bit) in [
        (appearance.outlines, flags::OUTLINES),
        (appearance.textures, flags::TEXTURES),
        (config.layout.orientation == hex_terrain::Orientation::Pointy, flags::POINTY),
        (appearance.fog_of_war, flags::FOG),
        (appearance.borders, flags::BORDERS),
        (appearance.territory_tint, flags::TERRITORY_TINT),
        (appearance.lens, flags::LENS),
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
        hover_color: linear(appearance.hover_color),
        selected_color: linear(appearance.selected_color),
        reachable_color: linear(appearance.reachable_color),
        unexplored_color: linear(appearance.unexplored_color),
        outline_color: Vec4::new(0.01, 0.01, 0.01, 0.92),
        water_color: linear(appearance.water_color),
        sea_level: t.sea_threshold * max,
        mountain_level: t.mountain_threshold * max,
        blend: config.appearance.blend.clamp(0.0, 1.0) * max,
        hex_size: config.layout.hex_size,
        outline_width: appearance.outline_width,
        texture_scale: wrapped_texture_scale(config, appearance.texture_scale),
        border_width: finite(appearance.border_width, 0.0, 1.0),
        border_inset: finite(appearance.border_inset, 0.0, 1.0),
        fog_softness: finite(appearance.fog_softness, 0.0, 1.0),
        tint_strength: 0.22,
        flags: bits,
        tile_window: window_param(window),
        map_wrap: IVec4::new(
            config.size.bounds().filter(|_| config.wrap).map_or(0, |(x, _)| x as i32),
            origin.tile.x,
            origin.tile.y,
            0,
        ),
        origin_offset: origin.offset.extend(0.0).extend(0.0),
    }
}

/// The texture scale, on a wrapping map rounded so the map's width holds a whole number of
/// texture repeats: the relief textures continue across the seam.
fn wrapped_texture_scale(config: &MapConfig, scale: f32) -> f32 {
    let Some((columns, _)) = config.size.bounds().filter(|_| config.wrap) else { return scale };
    let column = match config.layout.orientation {
        hex_terrain::Orientation::Flat => 1.5,
        hex_terrain::Orientation::Pointy => 3.0_f32.sqrt(),
    };
    let width = columns as f32 * column * config.layout.hex_size;
    if !(width.is_finite() && width > 0.0 && scale.is_finite()) {
        return scale;
    }
    (width * scale).round().max(1.0) / width
}

/// The owner palette: the appearance's colors, then hues spaced by the golden angle.
#[must_use]
pub fn owner_colors(appearance: &TerrainAppearance) -> OwnerColors {
    let mut owners = OwnerColors::default();
    for (i, slot) in owners.colors.iter_mut().enumerate() {
        let color = appearance
            .owner_colors
            .get(i)
            .copied()
            .unwrap_or_else(|| Color::hsl((i as f32 * 137.508) % 360.0, 0.75, 0.55));
        *slot = linear(color);
    }
    owners
}

/// The terrain material: registers [`HexTerrainMaterial`], gives every chunk mesh the shared
/// material and keeps it in step with the map, [`TerrainAppearance`] and the tile state
/// texture, into which it copies [`TileStates`]' changes (`tile_texture.rs`).
/// Needs Bevy's `PbrPlugin` (in `DefaultPlugins`); a headless app disables this plugin.
#[derive(Debug, Clone, Copy, Default)]
pub struct HexTerrainMaterialPlugin;

impl Plugin for HexTerrainMaterialPlugin {
    fn build(&self, app: &mut App) {
        if !app.is_plugin_added::<bevy::pbr::PbrPlugin>() {
            panic!(
                "HexTerrainMaterialPlugin needs Bevy's PbrPlugin: add DefaultPlugins before the hex terrain \
                 plugins, or in a headless app disable the material: \
                 HexTerrainPlugins::default().build().disable::<HexTerrainMaterialPlugin>()"
            );
        }
        if !app.is_plugin_added::<crate::tiles::HexTileStatePlugin>() {
            panic!("HexTerrainMaterialPlugin needs HexTileStatePlugin: add HexTerrainPlugins");
        }
        embedded_asset!(app, "terrain.wgsl");
        app.add_plugins((MaterialPlugin::<HexTerrainMaterial>::default(), tile_texture::TileTexturePlugin))
            .init_resource::<TerrainAppearance>()
            .init_resource::<RenderOrigin>()
            .register_type::<TerrainAppearance>()
            .register_type::<RenderOrigin>()
            .add_systems(Startup, create_material.after(tile_texture::create_texture))
            .add_systems(
                Update,
                (update_material, attach_material)
                    .chain()
                    .in_set(crate::HexTerrainSystems::Render)
                    .run_if(resource_exists::<HexTerrainMaterialHandle>),
            );
    }
}

fn textures(server: &AssetServer, appearance: &TerrainAppearance) -> [Option<Handle<Image>>; 3] {
    if appearance.textures {
        // World-space coordinates run far past [0, 1]: the textures must repeat.
        std::array::from_fn(|i| {
            Some(
                server
                    .load_builder()
                    .with_settings(|s: &mut ImageLoaderSettings| {
                        s.sampler = ImageSampler::Descriptor(ImageSamplerDescriptor {
                            address_mode_u: ImageAddressMode::Repeat,
                            address_mode_v: ImageAddressMode::Repeat,
                            ..ImageSamplerDescriptor::linear()
                        });
                    })
                    .load(appearance.texture_paths[i].clone()),
            )
        })
    } else {
        [None, None, None]
    }
}

#[expect(clippy::too_many_arguments, reason = "a system's parameters")]
fn create_material(
    mut commands: Commands,
    mut materials: ResMut<Assets<HexTerrainMaterial>>,
    server: Res<AssetServer>,
    map: Res<crate::HexMap>,
    appearance: Res<TerrainAppearance>,
    states: Res<TileStates>,
    texture: Res<TileStateTexture>,
    origin: Res<RenderOrigin>,
) {
    let [sea_texture, land_texture, mountain_texture] = textures(&server, &appearance);
    let handle = materials.add(ExtendedMaterial {
        base: StandardMaterial { base_color: Color::WHITE, perceptual_roughness: 0.92, reflectance: 0.2, ..default() },
        extension: HexTerrainExtension {
            params: params(map.config(), &appearance, states.window(), *origin),
            sea_texture,
            land_texture,
            mountain_texture,
            tile_state: texture.handle.clone(),
            owners: owner_colors(&appearance),
        },
    });
    commands.insert_resource(HexTerrainMaterialHandle(handle));
}

/// Rewrites the material when the map (hot reload, switch), the appearance or the tile state
/// window change its parameters, and only then (a rewritten material is uploaded again; tile
/// state changes go straight into the texture); a texture that failed to load switches to flat
/// colors with a warning.
#[expect(clippy::too_many_arguments, reason = "a system's parameters")]
fn update_material(
    handle: Res<HexTerrainMaterialHandle>,
    mut materials: ResMut<Assets<HexTerrainMaterial>>,
    server: Res<AssetServer>,
    map: Res<crate::HexMap>,
    mut appearance: ResMut<TerrainAppearance>,
    states: Res<TileStates>,
    texture: Res<TileStateTexture>,
    origin: Res<RenderOrigin>,
    mut failed: MessageReader<bevy::asset::AssetLoadFailedEvent<Image>>,
) {
    for failure in failed.read() {
        if appearance.textures && appearance.texture_paths.iter().any(|p| failure.path.path().ends_with(p)) {
            warn!("terrain texture {} could not be loaded ({}); using flat colors", failure.path, failure.error);
            appearance.textures = false;
        }
    }
    let Some(material) = materials.get(&handle.0) else { return };
    let ext = &material.extension;
    let window_moved = ext.params.tile_window != window_param(states.window());
    if !(map.is_changed() || appearance.is_changed() || texture.is_changed() || origin.is_changed() || window_moved) {
        return;
    }
    // A map whose appearance had to be clamped is drawn in flat colors.
    let mut effective = appearance.clone();
    effective.textures &= !map.appearance_fallback();
    let params = params(map.config(), &effective, states.window(), *origin);
    let owners = owner_colors(&effective);
    let retexture = effective.textures != ext.sea_texture.is_some();
    if params == ext.params && owners == ext.owners && ext.tile_state == texture.handle && !retexture {
        return;
    }
    let Some(mut material) = materials.get_mut(&handle.0) else { return };
    let ext = &mut material.extension;
    ext.params = params;
    ext.owners = owners;
    ext.tile_state = texture.handle.clone();
    if retexture {
        [ext.sea_texture, ext.land_texture, ext.mountain_texture] = textures(&server, &effective);
    }
}

/// Chunks with a mesh and no material yet.
type Unpainted = (With<crate::HexChunk>, With<Mesh3d>, Without<MeshMaterial3d<HexTerrainMaterial>>);

fn attach_material(mut commands: Commands, handle: Res<HexTerrainMaterialHandle>, chunks: Query<Entity, Unpainted>) {
    for e in &chunks {
        commands.entity(e).insert(MeshMaterial3d(handle.0.clone()));
    }
}

#[cfg(test)]
mod tests {
    use hex_terrain::{MapSize, Orientation};

    use super::*;

    /// On a wrapping map the texture scale gives a whole number of repeats across the map's
    /// width (textures continue across the seam), and `map_wrap` carries the width in columns;
    /// elsewhere both are as asked.
    #[test]
    fn wrapping_maps_get_whole_texture_repeats_and_their_width() {
        let appearance = TerrainAppearance::default();
        for (orientation, column) in [(Orientation::Flat, 1.5_f32), (Orientation::Pointy, 3.0_f32.sqrt())] {
            for columns in [44_u32, 84, 106] {
                let mut config = MapConfig { size: MapSize::Bounded { x: columns, z: 20 }, ..MapConfig::default() };
                config.layout.orientation = orientation;
                let plain = params(&config, &appearance, (IVec2::ZERO, UVec2::ONE), RenderOrigin::default());
                assert_eq!(plain.texture_scale, appearance.texture_scale);
                assert_eq!(plain.map_wrap.x, 0);
                config.wrap = true;
                let wrapped = params(&config, &appearance, (IVec2::ZERO, UVec2::ONE), RenderOrigin::default());
                let repeats = wrapped.texture_scale * columns as f32 * column * config.layout.hex_size;
                assert!((repeats - repeats.round()).abs() < 1e-3, "{repeats} repeats across {columns} columns");
                assert!((wrapped.texture_scale / appearance.texture_scale - 1.0).abs() < 0.1);
                assert_eq!(wrapped.map_wrap.x, columns as i32);
            }
        }
    }
}
