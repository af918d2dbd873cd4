//! The terrain material: `StandardMaterial` (so PBR lighting and shadows still work) extended
//! with a fragment shader that blends sea, land and mountain by height as thesis Algorithm 5
//! does, in flat colors or textures (on maps with a climate, each tile's terrain color and its
//! own layer of the texture array), and draws tile outlines and highlights. The same shader
//! serves forward and deferred cameras.

use crate::tiles::{HexTileStateStyle, TileStates};
use crate::water::HexWaterSettings;
use bevy::asset::{AssetPath, embedded_asset, embedded_path};
use bevy::mesh::MeshVertexBufferLayoutRef;
use bevy::pbr::{ExtendedMaterial, MaterialExtension, MaterialExtensionKey, MaterialExtensionPipeline};
use bevy::prelude::*;
use bevy::render::render_resource::{AsBindGroup, RenderPipelineDescriptor, SpecializedMeshPipelineError};
use bevy::shader::{ShaderDefVal, ShaderRef, load_shader_library};
pub use layers::MAX_TEXTURE_LAYERS;
pub(crate) use layers::TextureLayers;
use params::{Look, params, window_param};
pub use params::{OwnerColors, RenderOrigin, TerrainParams};
pub(crate) use params::{SHADER_DEFS, flags, linear, owner_colors};
pub use settings::HexTerrainMaterialSettings;
use tile_texture::TileStateTexture;

mod layers;
mod params;
mod settings;
mod tile_texture;

/// The chunk material.
pub type HexTerrainMaterial = ExtendedMaterial<StandardMaterial, HexTerrainExtension>;

/// The extension part of [`HexTerrainMaterial`].
#[derive(Asset, AsBindGroup, Reflect, Debug, Clone)]
#[bind_group_data(HexTerrainKey)]
pub struct HexTerrainExtension {
    /// Shader parameters.
    #[uniform(100)]
    pub params: TerrainParams,
    /// The texture array of the layers ([`HexTerrainMaterialSettings::texture_paths`]), in
    /// texture mode once its images have loaded.
    #[texture(101, dimension = "2d_array")]
    #[sampler(102)]
    pub layer_textures: Option<Handle<Image>>,
    /// The tile states ([`TileStates`]), written in place by `tile_texture.rs`.
    #[texture(107, sample_type = "u_int")]
    pub tile_state: Handle<Image>,
    /// Owner colors.
    #[uniform(108)]
    pub owners: OwnerColors,
    /// This instance draws the water surface (transparent, colored by depth) instead of the
    /// ground. The same parameters and tile states serve both, so fog, borders, highlights and
    /// outlines lie on the water as on the land.
    pub water: bool,
}

/// The pipeline key of [`HexTerrainExtension`]: the ground or the water pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct HexTerrainKey {
    /// The water pass.
    pub water: bool,
}

impl From<&HexTerrainExtension> for HexTerrainKey {
    fn from(ext: &HexTerrainExtension) -> Self {
        Self { water: ext.water }
    }
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
        key: MaterialExtensionKey<Self>,
    ) -> Result<(), SpecializedMeshPipelineError> {
        if let Some(fragment) = descriptor.fragment.as_mut() {
            fragment.shader_defs.extend(SHADER_DEFS.map(|(name, value)| ShaderDefVal::UInt(name.into(), value)));
            if key.bind_group_data.water {
                fragment.shader_defs.push("HEX_WATER".into());
            }
        }
        Ok(())
    }
}

/// The shared material handle of the chunks.
#[derive(Resource, Debug, Clone, Reflect)]
#[reflect(Resource, Debug)]
pub struct HexTerrainMaterialHandle(pub Handle<HexTerrainMaterial>);

/// The shared material handle of the water surfaces ([`HexWater`](crate::HexWater)): the terrain
/// material's water instance, alpha-blended.
#[derive(Resource, Debug, Clone, Reflect)]
#[reflect(Resource, Debug)]
pub struct HexWaterMaterialHandle(pub Handle<HexTerrainMaterial>);

/// The terrain material: registers [`HexTerrainMaterial`], gives every chunk mesh the shared
/// material and keeps it in step with the map, its [`HexTerrainMaterialSettings`], the
/// [`HexTileStateStyle`], the [`HexWaterSettings`] and the tile state texture, into which it copies
/// [`TileStates`]' changes (`tile_texture.rs`).
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
        // The shader's import modules (`#define_import_path hex_terrain::...`).
        load_shader_library!(app, "shaders/bindings.wgsl");
        load_shader_library!(app, "shaders/hex.wgsl");
        load_shader_library!(app, "shaders/ground.wgsl");
        load_shader_library!(app, "shaders/water.wgsl");
        load_shader_library!(app, "shaders/tile_state.wgsl");
        load_shared_libraries(app);
        add_texture_layers(app);
        app.add_plugins((MaterialPlugin::<HexTerrainMaterial>::default(), tile_texture::TileTexturePlugin))
            .init_resource::<RenderOrigin>()
            .register_type::<RenderOrigin>()
            .register_type::<HexTerrainMaterialHandle>()
            .register_type::<HexWaterMaterialHandle>()
            .add_systems(Startup, create_material.after(tile_texture::create_texture))
            .add_systems(
                Update,
                (update_material, attach_material)
                    .chain()
                    .after(layers::stack_layers)
                    .in_set(crate::HexTerrainSystems::Render)
                    .run_if(resource_exists::<HexTerrainMaterialHandle>),
            );
    }
}

/// The material settings and the loading of their texture array, which the flat map's material
/// and the globe's both draw with: added by the first of them.
pub(crate) fn add_texture_layers(app: &mut App) {
    if app.world().contains_resource::<TextureLayers>() {
        return;
    }
    app.init_resource::<HexTerrainMaterialSettings>()
        .init_resource::<TextureLayers>()
        .register_type::<HexTerrainMaterialSettings>()
        .add_systems(
            Update,
            (layers::load_layers, layers::stack_layers).chain().in_set(crate::HexTerrainSystems::Render),
        );
}

/// Loads the import modules the flat map's material and the globe's both read: the tile state
/// texel (`hex_terrain::texel`) and the triplanar sampling of the texture array
/// (`hex_terrain::triplanar`).
pub(crate) fn load_shared_libraries(app: &mut App) {
    load_shader_library!(app, "shaders/texel.wgsl");
    load_shader_library!(app, "shaders/triplanar.wgsl");
}

/// The ground and the water instances of the material share everything but the water key and
/// the base's blending: the water is transparent over the shallows and glossy.
fn base(water: bool) -> StandardMaterial {
    if water {
        StandardMaterial {
            base_color: Color::WHITE,
            perceptual_roughness: 0.12,
            // Water's F0 (about 0.02).
            reflectance: 0.35,
            alpha_mode: AlphaMode::Blend,
            ..default()
        }
    } else {
        StandardMaterial { base_color: Color::WHITE, perceptual_roughness: 0.92, reflectance: 0.2, ..default() }
    }
}

/// The material settings the shader draws: textures off on a map whose appearance had to be
/// clamped.
fn effective(appearance: &HexTerrainMaterialSettings, map: &crate::HexMap) -> HexTerrainMaterialSettings {
    let mut effective = appearance.clone();
    effective.textures &= !map.appearance_fallback();
    effective
}

/// What the materials are made from besides their own settings: the map, the tile states and
/// their style, the water's settings (absent without the water plugin), the tile state texture,
/// the render origin and the texture array.
#[derive(bevy::ecs::system::SystemParam)]
struct MaterialSources<'w> {
    layers: Res<'w, TextureLayers>,
    map: Res<'w, crate::HexMap>,
    style: Res<'w, HexTileStateStyle>,
    water: Option<Res<'w, HexWaterSettings>>,
    states: Res<'w, TileStates>,
    texture: Res<'w, TileStateTexture>,
    origin: Res<'w, RenderOrigin>,
}

impl MaterialSources<'_> {
    /// Whether anything the parameters are made of changed since the system last ran.
    fn changed(&self) -> bool {
        self.map.is_changed()
            || self.style.is_changed()
            || self.water.as_ref().is_some_and(|w| w.is_changed())
            || self.texture.is_changed()
            || self.origin.is_changed()
            || self.layers.is_changed()
    }

    /// The shader parameters and owner colors for the material settings.
    fn params(&self, material: &HexTerrainMaterialSettings) -> (TerrainParams, OwnerColors) {
        let look = Look { material, tiles: &self.style, water: self.water.as_deref() };
        let mut params = params(self.map.terrain(), look, self.states.window(), *self.origin);
        params.texture_layers = self.textures(material).map_or(0, |_| self.layers.count);
        (params, owner_colors(&self.style))
    }

    /// The texture array the material draws with: in texture mode, once it is stacked.
    fn textures(&self, material: &HexTerrainMaterialSettings) -> Option<Handle<Image>> {
        self.layers.array.clone().filter(|_| material.textures)
    }
}

fn create_material(
    mut commands: Commands,
    mut materials: ResMut<Assets<HexTerrainMaterial>>,
    sources: MaterialSources,
    appearance: Res<HexTerrainMaterialSettings>,
) {
    let appearance = effective(&appearance, &sources.map);
    let (params, owners) = sources.params(&appearance);
    let extension = HexTerrainExtension {
        params,
        layer_textures: sources.textures(&appearance),
        tile_state: sources.texture.handle.clone(),
        owners,
        water: false,
    };
    let water = HexTerrainExtension { water: true, ..extension.clone() };
    let handle = materials.add(ExtendedMaterial { base: base(false), extension });
    commands.insert_resource(HexTerrainMaterialHandle(handle));
    let handle = materials.add(ExtendedMaterial { base: base(true), extension: water });
    commands.insert_resource(HexWaterMaterialHandle(handle));
}

/// Rewrites the materials when the map (hot reload, switch), the material settings, the tile
/// state style, the water settings or the tile state window change their parameters, and only then (a rewritten material is
/// uploaded again; tile state changes go straight into the texture); a texture that failed to
/// load switches to flat colors with a warning.
fn update_material(
    handles: (Res<HexTerrainMaterialHandle>, Res<HexWaterMaterialHandle>),
    mut materials: ResMut<Assets<HexTerrainMaterial>>,
    sources: MaterialSources,
    mut appearance: ResMut<HexTerrainMaterialSettings>,
    mut failed: MessageReader<bevy::asset::AssetLoadFailedEvent<Image>>,
) {
    for failure in failed.read() {
        if appearance.textures && appearance.texture_paths.iter().any(|p| failure.path.path().ends_with(p)) {
            warn!("terrain texture {} could not be loaded ({}); using flat colors", failure.path, failure.error);
            appearance.textures = false;
        }
    }
    let Some(material) = materials.get(&handles.0.0) else { return };
    let ext = &material.extension;
    let window_moved = ext.params.tile_window != window_param(sources.states.window());
    if !(sources.changed() || appearance.is_changed() || window_moved) {
        return;
    }
    let effective = effective(&appearance, &sources.map);
    let (params, owners) = sources.params(&effective);
    let texture = &sources.texture;
    let layers = sources.textures(&effective);
    if params == ext.params && owners == ext.owners && ext.tile_state == texture.handle && ext.layer_textures == layers
    {
        return;
    }
    for handle in [&handles.0.0, &handles.1.0] {
        let Some(mut material) = materials.get_mut(handle) else { continue };
        let ext = &mut material.extension;
        ext.params = params;
        ext.owners = owners;
        ext.tile_state = texture.handle.clone();
        ext.layer_textures.clone_from(&layers);
    }
}

/// Chunks with a mesh and no material yet.
type Unpainted = (With<crate::HexChunk>, With<Mesh3d>, Without<MeshMaterial3d<HexTerrainMaterial>>);

/// Water surfaces with no material yet.
type UnpaintedWater = (With<crate::HexWater>, With<Mesh3d>, Without<MeshMaterial3d<HexTerrainMaterial>>);

fn attach_material(
    mut commands: Commands,
    handle: Res<HexTerrainMaterialHandle>,
    water: Res<HexWaterMaterialHandle>,
    chunks: Query<Entity, Unpainted>,
    waters: Query<Entity, UnpaintedWater>,
) {
    for e in &chunks {
        commands.entity(e).insert(MeshMaterial3d(handle.0.clone()));
    }
    for e in &waters {
        commands.entity(e).insert(MeshMaterial3d(water.0.clone()));
    }
}
