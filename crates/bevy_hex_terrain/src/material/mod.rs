//! The terrain material: `StandardMaterial` (so PBR lighting and shadows still work) extended
//! with a fragment shader that blends sea, land and mountain by height as thesis Algorithm 5
//! does, in flat colors or textures, and draws tile outlines and highlights. The same shader
//! serves forward and deferred cameras.

use bevy::asset::{AssetPath, embedded_asset, embedded_path};
use bevy::image::{ImageAddressMode, ImageLoaderSettings, ImageSampler, ImageSamplerDescriptor};
use bevy::mesh::MeshVertexBufferLayoutRef;
use bevy::pbr::{ExtendedMaterial, MaterialExtension, MaterialExtensionKey, MaterialExtensionPipeline};
use bevy::prelude::*;
use bevy::render::render_resource::{AsBindGroup, RenderPipelineDescriptor, ShaderType, SpecializedMeshPipelineError};
use bevy::shader::{ShaderDefVal, ShaderRef};
use hex_terrain::MapConfig;
use hex_terrain::hexx::Hex;

/// The chunk material.
pub type HexTerrainMaterial = ExtendedMaterial<StandardMaterial, HexTerrainExtension>;

/// Most tiles [`TileHighlights::selected`] tints at once.
pub const MAX_HIGHLIGHTS: usize = 64;

/// Bits of [`TerrainParams::flags`]. The shader receives these values (and
/// [`MAX_HIGHLIGHTS`]) as shader defs, so Rust and WGSL share one definition.
pub mod flags {
    /// Draw tile outlines.
    pub const OUTLINES: u32 = 1;
    /// Sample the textures instead of flat colors.
    pub const TEXTURES: u32 = 2;
    /// Pointy-topped hexes (flat-topped without).
    pub const POINTY: u32 = 4;
    /// A tile is hovered.
    pub const HOVERED: u32 = 8;
}

/// The shader defs every terrain pipeline gets: the flag bits and the highlight array size.
const SHADER_DEFS: [(&str, u32); 5] = [
    ("HEX_FLAG_OUTLINES", flags::OUTLINES),
    ("HEX_FLAG_TEXTURES", flags::TEXTURES),
    ("HEX_FLAG_POINTY", flags::POINTY),
    ("HEX_FLAG_HOVERED", flags::HOVERED),
    ("HEX_MAX_HIGHLIGHTS", MAX_HIGHLIGHTS as u32),
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
    pub highlight_color: Vec4,
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
    /// Bits of [`flags`].
    pub flags: u32,
    /// How many entries of the highlight list are used.
    pub highlight_count: u32,
    /// Hovered tile (axial `x`, `y`).
    pub hovered: IVec4,
}

/// The tiles to tint.
#[derive(Debug, Clone, Copy, PartialEq, ShaderType, Reflect)]
pub struct HighlightList {
    /// Axial coordinates in `x`, `y`.
    pub tiles: [IVec4; MAX_HIGHLIGHTS],
}

impl Default for HighlightList {
    fn default() -> Self {
        Self { tiles: [IVec4::ZERO; MAX_HIGHLIGHTS] }
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
    /// Selected or reachable tiles.
    #[uniform(107)]
    pub highlights: HighlightList,
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

/// How the terrain looks, changed at run time by the game (outlines toggle, textures).
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
        }
    }
}

/// Tiles the game wants tinted: the hovered one and a set of selected or reachable ones.
/// Writing it updates a uniform; meshes are not rebuilt.
#[derive(Resource, Debug, Clone, Default, Reflect)]
#[reflect(Resource)]
pub struct TileHighlights {
    /// The tile under the cursor.
    pub hovered: Option<Hex>,
    /// Selected or reachable tiles (the first [`MAX_HIGHLIGHTS`] are drawn).
    pub selected: Vec<Hex>,
}

/// The shared material handle of the chunks.
#[derive(Resource, Debug, Clone)]
pub struct HexTerrainMaterialHandle(pub Handle<HexTerrainMaterial>);

/// Builds the shader parameters for a map config and appearance.
#[must_use]
pub fn params(config: &MapConfig, appearance: &TerrainAppearance, highlights: &TileHighlights) -> TerrainParams {
    let t = &config.terrain;
    let max = t.max_elevation;
    let lin = |c: Color| Vec4::from_array(c.to_linear().to_f32_array());
    let mut bits = 0;
    if appearance.outlines {
        bits |= flags::OUTLINES;
    }
    if appearance.textures {
        bits |= flags::TEXTURES;
    }
    if config.layout.orientation == hex_terrain::Orientation::Pointy {
        bits |= flags::POINTY;
    }
    if highlights.hovered.is_some() {
        bits |= flags::HOVERED;
    }
    let hovered = highlights.hovered.map_or(IVec4::ZERO, |h| IVec4::new(h.x, h.y, 0, 0));
    TerrainParams {
        sea_color: lin(appearance.colors[0]),
        land_color: lin(appearance.colors[1]),
        mountain_color: lin(appearance.colors[2]),
        hover_color: Vec4::new(1.0, 0.95, 0.55, 0.45),
        highlight_color: Vec4::new(0.35, 0.75, 1.0, 0.4),
        outline_color: Vec4::new(0.01, 0.01, 0.01, 0.92),
        water_color: lin(appearance.water_color),
        sea_level: t.sea_threshold * max,
        mountain_level: t.mountain_threshold * max,
        blend: config.appearance.blend.clamp(0.0, 1.0) * max,
        hex_size: config.layout.hex_size,
        outline_width: appearance.outline_width,
        texture_scale: appearance.texture_scale,
        flags: bits,
        highlight_count: highlights.selected.len().min(MAX_HIGHLIGHTS) as u32,
        hovered,
    }
}

/// The terrain material: registers [`HexTerrainMaterial`], gives every chunk mesh the shared
/// material and keeps it in step with the map, [`TerrainAppearance`] and [`TileHighlights`].
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
        embedded_asset!(app, "terrain.wgsl");
        app.add_plugins(MaterialPlugin::<HexTerrainMaterial>::default())
            .init_resource::<TerrainAppearance>()
            .init_resource::<TileHighlights>()
            .register_type::<TerrainAppearance>()
            .register_type::<TileHighlights>()
            .add_systems(Startup, create_material)
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

fn create_material(
    mut commands: Commands,
    mut materials: ResMut<Assets<HexTerrainMaterial>>,
    server: Res<AssetServer>,
    map: Res<crate::HexMap>,
    appearance: Res<TerrainAppearance>,
    highlights: Res<TileHighlights>,
) {
    let [sea_texture, land_texture, mountain_texture] = textures(&server, &appearance);
    let handle = materials.add(ExtendedMaterial {
        base: StandardMaterial { base_color: Color::WHITE, perceptual_roughness: 0.92, reflectance: 0.2, ..default() },
        extension: HexTerrainExtension {
            params: params(map.config(), &appearance, &highlights),
            sea_texture,
            land_texture,
            mountain_texture,
            highlights: HighlightList::default(),
        },
    });
    commands.insert_resource(HexTerrainMaterialHandle(handle));
}

/// Rewrites the material when the map (hot reload, switch), the appearance or the highlights
/// change its parameters, and only then (a rewritten material is uploaded again); a texture that
/// failed to load switches to flat colors with a warning.
fn update_material(
    handle: Res<HexTerrainMaterialHandle>,
    mut materials: ResMut<Assets<HexTerrainMaterial>>,
    server: Res<AssetServer>,
    map: Res<crate::HexMap>,
    mut appearance: ResMut<TerrainAppearance>,
    highlights: Res<TileHighlights>,
    mut failed: MessageReader<bevy::asset::AssetLoadFailedEvent<Image>>,
) {
    for failure in failed.read() {
        if appearance.textures && appearance.texture_paths.iter().any(|p| failure.path.path().ends_with(p)) {
            warn!("terrain texture {} could not be loaded ({}); using flat colors", failure.path, failure.error);
            appearance.textures = false;
        }
    }
    if !(map.is_changed() || appearance.is_changed() || highlights.is_changed()) {
        return;
    }
    let Some(material) = materials.get(&handle.0) else { return };
    // A map whose appearance had to be clamped is drawn in flat colors.
    let mut effective = appearance.clone();
    effective.textures &= !map.appearance_fallback();
    let params = params(map.config(), &effective, &highlights);
    let mut list = material.extension.highlights;
    for (slot, hex) in list.tiles.iter_mut().zip(&highlights.selected) {
        *slot = IVec4::new(hex.x, hex.y, 0, 0);
    }
    let retexture = effective.textures != material.extension.sea_texture.is_some();
    if params == material.extension.params && list == material.extension.highlights && !retexture {
        return;
    }
    let Some(mut material) = materials.get_mut(&handle.0) else { return };
    let ext = &mut material.extension;
    ext.params = params;
    ext.highlights = list;
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
