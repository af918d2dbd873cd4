//! The globe's material: `StandardMaterial` (PBR lighting and shadows, lit by whatever lights the
//! game places: a sun it can move) extended with a fragment shader (`globe.wgsl`) that draws the
//! sea as water where the ground lies below the sea's sphere (the flat map's water look from
//! [`HexWaterSettings`]: shallow to deep colors over the sea floor, foam along the shore, waves
//! that catch the sun) and [`GlobeTileStates`] on each tile: fog of war, owners' borders and
//! tint, the lens and the highlights, styled by [`HexTileStateStyle`]. No mesh is touched when a state changes: the
//! states live in a texture of a texel a tile, the chunks carry each vertex's tile in their
//! first UV (`stream.rs`), and a topology texture holds each tile's center and neighbors.

use bevy::asset::{AssetPath, RenderAssetUsages, embedded_asset, embedded_path};
use bevy::mesh::MeshVertexBufferLayoutRef;
use bevy::pbr::{ExtendedMaterial, MaterialExtension, MaterialExtensionKey, MaterialExtensionPipeline};
use bevy::prelude::*;
use bevy::render::render_asset::RenderAssets;
use bevy::render::render_resource::{
    AsBindGroup, Extent3d, Origin3d, RenderPipelineDescriptor, ShaderType, SpecializedMeshPipelineError,
    TexelCopyBufferLayout, TexelCopyTextureInfo, TextureAspect, TextureDimension, TextureFormat,
};
use bevy::render::renderer::RenderQueue;
use bevy::render::texture::GpuImage;
use bevy::render::{Extract, ExtractSchedule, Render, RenderApp, RenderSystems};
use bevy::shader::{ShaderDefVal, ShaderRef};
use hex_terrain::{GlobeGrid, GlobeTerrain, GlobeTile};

use super::{GLOBE_ROW, GlobeTileStates, HexGlobe, HexGlobeChunk};
use crate::material::{
    HexTerrainMaterialSettings, OwnerColors, SHADER_DEFS, TextureLayers, flags, linear, owner_colors,
};
use crate::tiles::{HexTileStateStyle, Texel};
use crate::water::HexWaterSettings;

/// The globe's chunk material.
pub type HexGlobeMaterial = ExtendedMaterial<StandardMaterial, HexGlobeExtension>;

/// The extension part of [`HexGlobeMaterial`]: the tile states and how they are drawn.
#[derive(Asset, AsBindGroup, Reflect, Debug, Clone)]
pub struct HexGlobeExtension {
    /// How the tile states are drawn, from [`HexTileStateStyle`].
    #[uniform(100)]
    pub params: GlobeParams,
    /// Each tile's state texel ([`GlobeTileStates`]), `GLOBE_ROW` tiles a row.
    #[texture(101, sample_type = "u_int")]
    pub tile_state: Handle<Image>,
    /// Each tile's center and neighbors, three texels a tile.
    #[texture(102, sample_type = "u_int")]
    pub topology: Handle<Image>,
    /// Owner colors.
    #[uniform(103)]
    pub owners: OwnerColors,
    /// The texture array of the layers
    /// ([`HexTerrainMaterialSettings::texture_paths`](crate::HexTerrainMaterialSettings::texture_paths)),
    /// with textures on once its images have loaded: each tile's layer (the chunk mesh's second
    /// UV) modulates its color.
    #[texture(104, dimension = "2d_array")]
    #[sampler(105)]
    pub layer_textures: Option<Handle<Image>>,
}

/// The globe shader's parameters: the style of the tile states and the water's look.
#[derive(Debug, Clone, Copy, PartialEq, ShaderType, Reflect)]
pub struct GlobeParams {
    /// Tint of the hovered tile (linear; alpha is the strength).
    pub hover_color: Vec4,
    /// Tint of selected tiles.
    pub selected_color: Vec4,
    /// Tint of reachable tiles.
    pub reachable_color: Vec4,
    /// Color of unexplored tiles.
    pub unexplored_color: Vec4,
    /// Border line width, a fraction of a tile's radius.
    pub border_width: f32,
    /// Gap between a tile's edge and its border line, a fraction of its radius.
    pub border_inset: f32,
    /// Width of the fog's blend across tile borders, a fraction of a tile's radius.
    pub fog_softness: f32,
    /// How strongly owned tiles are tinted.
    pub tint_strength: f32,
    /// Which states are drawn and how the sea is: the flat material's `FOG`, `BORDERS`,
    /// `TERRITORY_TINT`, `LENS`, `WATER` and `SEA_FLOOR` bits.
    pub flags: u32,
    /// Water color over the shallows (linear).
    pub shallow_water_color: Vec4,
    /// Water color over the deep sea.
    pub deep_water_color: Vec4,
    /// Foam color at the shore.
    pub foam_color: Vec4,
    /// Sea floor color at the coast (darkening with depth).
    pub sea_floor_color: Vec4,
    /// The sea's surface: its distance from the globe's center, in world units.
    pub sea_radius: f32,
    /// Depth of water at which it is fully deep, in world units.
    pub deep_water: f32,
    /// Width of the shore foam, in depth of water (world units).
    pub foam_width: f32,
    /// Strength of the waves' normals, 0 for a still sea.
    pub waves: f32,
    /// The globe's hex size (the waves' length).
    pub hex_size: f32,
    /// Texture repeats per world unit.
    pub texture_scale: f32,
    /// Layers in the texture array (0 without one: flat colors).
    pub texture_layers: u32,
}

impl GlobeParams {
    /// The parameters drawing the tile states in `style`, the sea of `globe` as `water` says
    /// and the ground with `layers` layers of textures (0: flat colors) at `material`'s scale.
    #[must_use]
    pub fn of(
        style: &HexTileStateStyle,
        water: &HexWaterSettings,
        material: &HexTerrainMaterialSettings,
        layers: u32,
        globe: &GlobeTerrain,
    ) -> Self {
        let mut bits = 0;
        for (on, bit) in [
            (style.fog_of_war, flags::FOG),
            (style.borders, flags::BORDERS),
            (style.territory_tint, flags::TERRITORY_TINT),
            (style.lens, flags::LENS),
            (water.enabled, flags::WATER),
            (water.sea_floor, flags::SEA_FLOOR),
            (layers > 0, flags::TEXTURES),
        ] {
            if on {
                bits |= bit;
            }
        }
        let finite = |v: f32| if v.is_finite() { v.clamp(0.0, 1.0) } else { 0.0 };
        let terrain = &globe.config().terrain;
        Self {
            hover_color: linear(style.hover_color),
            selected_color: linear(style.selected_color),
            reachable_color: linear(style.reachable_color),
            unexplored_color: linear(style.unexplored_color),
            border_width: finite(style.border_width),
            border_inset: finite(style.border_inset),
            fog_softness: finite(style.fog_softness),
            tint_strength: 0.22,
            flags: bits,
            shallow_water_color: linear(water.shallow_color),
            deep_water_color: linear(water.deep_color),
            foam_color: linear(water.foam_color),
            sea_floor_color: linear(water.sea_floor_color),
            sea_radius: (globe.radius() + f64::from(terrain.sea_threshold * terrain.max_elevation)) as f32,
            deep_water: finite(water.deep_water) * terrain.sea_threshold * terrain.max_elevation,
            foam_width: water.foam_width.max(0.0),
            waves: water.waves.max(0.0),
            hex_size: globe.config().layout.hex_size,
            texture_scale: if material.texture_scale.is_finite() { material.texture_scale.max(0.0) } else { 0.0 },
            texture_layers: layers,
        }
    }
}

fn shader() -> ShaderRef {
    ShaderRef::Path(AssetPath::from_path_buf(embedded_path!("globe.wgsl")).with_source("embedded"))
}

impl MaterialExtension for HexGlobeExtension {
    fn fragment_shader() -> ShaderRef {
        shader()
    }

    fn specialize(
        _pipeline: &MaterialExtensionPipeline,
        descriptor: &mut RenderPipelineDescriptor,
        _layout: &MeshVertexBufferLayoutRef,
        _key: MaterialExtensionKey<Self>,
    ) -> Result<(), SpecializedMeshPipelineError> {
        if let Some(fragment) = descriptor.fragment.as_mut() {
            let defs = SHADER_DEFS.into_iter().chain([("HEX_GLOBE_ROW", GLOBE_ROW)]);
            fragment.shader_defs.extend(defs.map(|(name, value)| ShaderDefVal::UInt(name.into(), value)));
        }
        Ok(())
    }
}

/// The globe's material (one for every chunk) and the frequency its topology was made for.
#[derive(Resource, Debug)]
pub(super) struct GlobeMaterialHandle {
    handle: Handle<HexGlobeMaterial>,
    /// Its tile state texture, which the render world writes the uploads into.
    state: AssetId<Image>,
    frequency: u32,
}

/// Registers the material; its systems run in [`HexTerrainSystems::Render`](crate::HexTerrainSystems::Render).
pub(super) fn build(app: &mut App) {
    embedded_asset!(app, "globe.wgsl");
    crate::material::load_shared_libraries(app);
    crate::material::add_texture_layers(app);
    app.add_plugins(MaterialPlugin::<HexGlobeMaterial>::default())
        .register_type::<GlobeParams>()
        .configure_sets(Update, crate::HexTerrainSystems::Render.after(crate::HexTerrainSystems::Insert))
        .add_systems(
            Update,
            (make_material, update_material, attach_material).chain().in_set(crate::HexTerrainSystems::Render),
        );
    if let Some(render_app) = app.get_sub_app_mut(RenderApp) {
        render_app
            .init_resource::<PendingRows>()
            .add_systems(ExtractSchedule, extract_upload)
            .add_systems(Render, write_rows.in_set(RenderSystems::PrepareResources));
    }
}

/// The rows of a texture holding `tiles` tiles, `GLOBE_ROW` a row.
fn rows(tiles: u32) -> u32 {
    tiles.div_ceil(GLOBE_ROW).max(1)
}

/// The tile state texture's bytes for `texels` from the start of a row: each tile's texel at
/// its id, the last row filled with zeros.
pub(crate) fn state_bytes(texels: &[Texel]) -> Vec<u8> {
    let mut bytes = vec![0; texels.len().div_ceil(GLOBE_ROW as usize).max(1) * GLOBE_ROW as usize * 8];
    for (texel, out) in texels.iter().zip(bytes.chunks_exact_mut(8)) {
        for (word, b) in texel.iter().zip(out.chunks_exact_mut(2)) {
            b.copy_from_slice(&word.to_le_bytes());
        }
    }
    bytes
}

/// The tile state texture's rows written in a frame (after `Update`), which the globe's material
/// copies into its texture in place in the render world (an image asset modified would be
/// uploaded whole and the material bound again).
#[derive(Resource, Debug, Clone, Default)]
pub(crate) struct GlobeStateUpload {
    /// Each row written, and its bytes (`GLOBE_ROW` texels).
    rows: Vec<(u32, Vec<u8>)>,
    /// Grows with each upload.
    serial: u64,
}

impl GlobeStateUpload {
    /// The rows and their bytes.
    pub(crate) fn rows(&self) -> &[(u32, Vec<u8>)] {
        &self.rows
    }

    /// Grows with each upload: a new one to take.
    pub(crate) fn serial(&self) -> u64 {
        self.serial
    }
}

/// Packs the rows written this frame for the GPU (a frame without writes packs nothing).
pub(super) fn pack_upload(mut states: ResMut<GlobeTileStates>, mut upload: ResMut<GlobeStateUpload>) {
    let rows = states.bypass_change_detection().take_dirty_rows();
    if rows.is_empty() {
        return;
    }
    let texels = states.texels();
    upload.rows = rows
        .into_iter()
        .map(|row| {
            let start = (row * GLOBE_ROW) as usize;
            (row, state_bytes(&texels[start.min(texels.len())..(start + GLOBE_ROW as usize).min(texels.len())]))
        })
        .collect();
    upload.serial += 1;
}

/// The topology texture's words, four a texel and three texels a tile: the center's `x, y, z`
/// (as `f32` bits) and the neighbor count, then the neighbors (unused entries 0).
pub(super) fn topology_words(grid: &GlobeGrid) -> Vec<[u32; 4]> {
    let tiles = grid.tile_count();
    let mut words = vec![[0; 4]; (rows(tiles) * GLOBE_ROW * 3) as usize];
    for t in 0..tiles {
        let tile = GlobeTile(t);
        let (Some(c), Some(n)) = (grid.center(tile), grid.neighbors(tile)) else { continue };
        let n = n.as_slice();
        let mut list = [0; 8];
        for (slot, nb) in list.iter_mut().zip(n) {
            *slot = nb.0;
        }
        let at = 3 * t as usize;
        words[at] = [(c[0] as f32).to_bits(), (c[1] as f32).to_bits(), (c[2] as f32).to_bits(), n.len() as u32];
        words[at + 1] = [list[0], list[1], list[2], list[3]];
        words[at + 2] = [list[4], list[5], 0, 0];
    }
    words
}

fn image(width: u32, height: u32, format: TextureFormat, data: Vec<u8>) -> Image {
    Image::new(
        Extent3d { width, height, depth_or_array_layers: 1 },
        TextureDimension::D2,
        data,
        format,
        RenderAssetUsages::RENDER_WORLD,
    )
}

fn topology_image(grid: &GlobeGrid) -> Image {
    let bytes = topology_words(grid).iter().flat_map(|w| w.iter().flat_map(|v| v.to_le_bytes())).collect();
    image(3 * GLOBE_ROW, rows(grid.tile_count()), TextureFormat::Rgba32Uint, bytes)
}

fn state_image(states: &GlobeTileStates) -> Image {
    image(GLOBE_ROW, rows(states.tile_count()), TextureFormat::Rgba16Uint, state_bytes(states.texels()))
}

/// Makes the material once the globe is known, and again for a globe of another frequency.
fn make_material(
    mut commands: Commands,
    globe: Res<HexGlobe>,
    look: GlobeLook,
    mut states: ResMut<GlobeTileStates>,
    mut images: ResMut<Assets<Image>>,
    mut materials: ResMut<Assets<HexGlobeMaterial>>,
    handle: Option<Res<GlobeMaterialHandle>>,
) {
    let Some(terrain) = globe.globe() else { return };
    let frequency = terrain.grid().frequency();
    if handle.is_some_and(|h| h.frequency == frequency) {
        return;
    }
    let state = images.add(state_image(&states));
    let extension = HexGlobeExtension {
        params: look.params(terrain),
        tile_state: state.clone(),
        topology: images.add(topology_image(terrain.grid())),
        owners: owner_colors(&look.style),
        layer_textures: look.array(),
    };
    // The new texture holds every tile's state already.
    states.bypass_change_detection().take_dirty_rows();
    let base = StandardMaterial { perceptual_roughness: 0.9, reflectance: 0.2, ..default() };
    let handle = materials.add(ExtendedMaterial { base, extension });
    commands.insert_resource(GlobeMaterialHandle { handle, state: state.id(), frequency });
}

/// What the material's look is made of: the tile states' style, the water's and the material's
/// settings, and the texture array.
#[derive(bevy::ecs::system::SystemParam)]
struct GlobeLook<'w> {
    style: Res<'w, HexTileStateStyle>,
    water: Res<'w, HexWaterSettings>,
    settings: Res<'w, HexTerrainMaterialSettings>,
    layers: Res<'w, TextureLayers>,
}

impl GlobeLook<'_> {
    /// The texture array, with textures on once it is stacked.
    fn array(&self) -> Option<Handle<Image>> {
        self.layers.array.clone().filter(|_| self.settings.textures)
    }

    /// The shader's parameters for `globe`.
    fn params(&self, globe: &GlobeTerrain) -> GlobeParams {
        let layers = self.array().map_or(0, |_| self.layers.count);
        GlobeParams::of(&self.style, &self.water, &self.settings, layers, globe)
    }

    /// Whether any of it changed since the system last ran.
    fn is_changed(&self) -> bool {
        self.style.is_changed() || self.water.is_changed() || self.settings.is_changed() || self.layers.is_changed()
    }
}

/// Keeps the material's parameters in step with its look and the globe (a hot reload may move
/// its sea), rewritten when they change.
fn update_material(
    look: GlobeLook,
    globe: Res<HexGlobe>,
    mut materials: ResMut<Assets<HexGlobeMaterial>>,
    handle: Option<Res<GlobeMaterialHandle>>,
) {
    let (Some(handle), Some(terrain)) = (handle, globe.globe()) else { return };
    if look.is_changed() || globe.is_changed() {
        let (params, owners, array) = (look.params(terrain), owner_colors(&look.style), look.array());
        if let Some(material) = materials.get(&handle.handle)
            && (material.extension.params != params
                || material.extension.owners != owners
                || material.extension.layer_textures != array)
            && let Some(mut material) = materials.get_mut(&handle.handle)
        {
            material.extension.params = params;
            material.extension.owners = owners;
            material.extension.layer_textures = array;
        }
    }
}

/// The uploads the render world has not written yet (their texture not on the GPU yet), each
/// with the texture it is for.
#[derive(Resource, Default)]
struct PendingRows {
    serial: u64,
    uploads: Vec<(AssetId<Image>, GlobeStateUpload)>,
}

/// Takes a new upload for the material's texture (one packed before there is a material is
/// dropped: the texture is made with every tile's state).
fn extract_upload(
    upload: Extract<Res<GlobeStateUpload>>,
    handle: Extract<Option<Res<GlobeMaterialHandle>>>,
    mut pending: ResMut<PendingRows>,
) {
    if upload.serial() != pending.serial {
        pending.serial = upload.serial();
        if let Some(handle) = handle.as_ref() {
            pending.uploads.push((handle.state, upload.clone()));
        }
    }
}

/// Writes the pending rows into their texture once it is on the GPU, in order.
fn write_rows(mut pending: ResMut<PendingRows>, images: Res<RenderAssets<GpuImage>>, queue: Res<RenderQueue>) {
    pending.uploads.retain(|(image, upload)| {
        let Some(gpu) = images.get(*image) else { return true };
        for (row, bytes) in upload.rows() {
            if *row >= gpu.texture_descriptor.size.height {
                continue;
            }
            queue.write_texture(
                TexelCopyTextureInfo {
                    texture: &gpu.texture,
                    mip_level: 0,
                    origin: Origin3d { x: 0, y: *row, z: 0 },
                    aspect: TextureAspect::All,
                },
                bytes,
                TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(GLOBE_ROW * 8), rows_per_image: None },
                Extent3d { width: GLOBE_ROW, height: 1, depth_or_array_layers: 1 },
            );
        }
        false
    });
}

/// The chunks with a mesh, and their material.
type Meshed<'w, 's> =
    Query<'w, 's, (Entity, Option<&'static MeshMaterial3d<HexGlobeMaterial>>), (With<HexGlobeChunk>, With<Mesh3d>)>;

/// Gives each chunk that has its mesh the globe's material (the new one after a globe of another
/// frequency).
fn attach_material(mut commands: Commands, handle: Option<Res<GlobeMaterialHandle>>, chunks: Meshed) {
    let Some(handle) = handle else { return };
    for (e, material) in &chunks {
        if material.is_none_or(|m| m.0 != handle.handle) {
            commands.entity(e).insert(MeshMaterial3d(handle.handle.clone()));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What the shader reads (`globe.wgsl`: a tile's state texel at column `id % GLOBE_ROW` and
    /// row `id / GLOBE_ROW`, its topology at columns `3 (id % GLOBE_ROW) + k`) is the tile's:
    /// read back from the bytes the textures are made of, as the shader addresses them, on
    /// globes of one row and of several.
    #[test]
    fn the_shader_reads_each_tiles_state_center_and_neighbors_where_they_are_written() {
        for frequency in [3, 11, 26] {
            let grid = GlobeGrid::new(frequency).unwrap();
            let tiles = grid.tile_count();
            let texels: Vec<Texel> = (0..tiles).map(|t| [t as u16, (t >> 16) as u16, 7, t as u16 ^ 0x5a5a]).collect();
            let state = state_bytes(&texels);
            let topology = topology_words(&grid);
            let width = GLOBE_ROW as usize;
            assert_eq!(state.len(), width * rows(tiles) as usize * 8);
            assert_eq!(topology.len(), 3 * width * rows(tiles) as usize);
            for t in (0..tiles).step_by(7).chain([tiles - 1]) {
                let (x, y) = ((t % GLOBE_ROW) as usize, (t / GLOBE_ROW) as usize);
                let at = (y * width + x) * 8;
                let read: Vec<u16> = state[at..at + 8].chunks(2).map(|b| u16::from_le_bytes([b[0], b[1]])).collect();
                assert_eq!(read, texels[t as usize]);
                let word = |k: usize| topology[y * 3 * width + 3 * x + k];
                let center = grid.center(GlobeTile(t)).unwrap();
                for (axis, c) in center.iter().enumerate() {
                    assert!((f64::from(f32::from_bits(word(0)[axis])) - c).abs() < 1e-6);
                }
                let neighbors = grid.neighbors(GlobeTile(t)).unwrap();
                let count = word(0)[3] as usize;
                assert_eq!(count, neighbors.as_slice().len());
                let listed: Vec<u32> = [word(1), word(2)].concat()[..count].to_vec();
                assert_eq!(listed, neighbors.as_slice().iter().map(|n| n.0).collect::<Vec<_>>());
            }
        }
    }

    /// Every value the globe shader and the texel module it imports take from Rust
    /// (`#{HEX_...}`) is a shader def they are given.
    #[test]
    fn the_globe_shader_reads_its_layout_from_the_shader_defs() {
        let source = [include_str!("globe.wgsl"), include_str!("../material/shaders/texel.wgsl")].concat();
        let given: Vec<&str> = SHADER_DEFS.iter().map(|(name, _)| *name).chain(["HEX_GLOBE_ROW"]).collect();
        let mut used = 0;
        for (i, _) in source.match_indices("#{HEX_") {
            let name = &source[i + 2..];
            let name = &name[..name.find('}').unwrap()];
            assert!(given.contains(&name), "{name} is not a shader def");
            used += 1;
        }
        assert!(used >= 10);
    }
}
