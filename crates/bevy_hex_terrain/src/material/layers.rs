//! The material's texture array: the images of
//! [`HexTerrainMaterialSettings::texture_paths`], loaded and stacked into one array image once
//! all of them have loaded (of one size and format), so a tile's layer is one index in the
//! shader. An image that fails to load, or whose size or format differs from the first one's,
//! turns the textures off with a warning naming it; the ground keeps its flat colors.

use bevy::asset::RenderAssetUsages;
use bevy::image::{ImageAddressMode, ImageSampler, ImageSamplerDescriptor};
use bevy::prelude::*;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureViewDescriptor, TextureViewDimension};

use super::HexTerrainMaterialSettings;

/// Most layers in the material's texture array: as many as a ruleset's texture layers
/// ([`Look::texture`](hex_terrain::Look::texture) is below it).
pub const MAX_TEXTURE_LAYERS: usize = hex_terrain::MAX_TERRAINS;

/// The layers' images and, once they have all loaded, their array.
#[derive(Resource, Debug, Default)]
pub(crate) struct TextureLayers {
    /// The paths the images were loaded from (none with the textures off).
    paths: Vec<String>,
    images: Vec<Handle<Image>>,
    /// The array of the images, in order.
    pub(crate) array: Option<Handle<Image>>,
    /// Its layers.
    pub(crate) count: u32,
}

/// Loads the images of the settings' paths when the textures are turned on or the paths change
/// (and forgets them when the textures are turned off).
pub(super) fn load_layers(
    server: Res<AssetServer>,
    settings: Res<HexTerrainMaterialSettings>,
    mut layers: ResMut<TextureLayers>,
) {
    let paths = &settings.texture_paths;
    let wanted: &[String] = if settings.textures { &paths[..paths.len().min(MAX_TEXTURE_LAYERS)] } else { &[] };
    if wanted == layers.paths.as_slice() {
        return;
    }
    if settings.textures && paths.len() > MAX_TEXTURE_LAYERS {
        warn!("{} terrain textures: the material draws the first {MAX_TEXTURE_LAYERS}", paths.len());
    }
    *layers = TextureLayers {
        images: wanted.iter().map(|p| server.load(p.clone())).collect(),
        paths: wanted.to_vec(),
        array: None,
        count: 0,
    };
}

/// Stacks the images into the array once every one has loaded.
pub(super) fn stack_layers(
    mut images: ResMut<Assets<Image>>,
    mut layers: ResMut<TextureLayers>,
    mut settings: ResMut<HexTerrainMaterialSettings>,
) {
    if layers.array.is_some() || layers.images.is_empty() {
        return;
    }
    let Some(loaded) = layers.images.iter().map(|h| images.get(h)).collect::<Option<Vec<&Image>>>() else {
        return;
    };
    let (size, format) = (loaded[0].size(), loaded[0].texture_descriptor.format);
    let mut data = Vec::with_capacity(loaded.iter().map(|i| i.data.as_ref().map_or(0, Vec::len)).sum());
    for (path, image) in layers.paths.iter().zip(&loaded) {
        let (got, got_format) = (image.size(), image.texture_descriptor.format);
        let bytes = image.data.as_ref().filter(|_| image.texture_descriptor.mip_level_count == 1);
        let Some(bytes) = bytes.filter(|_| got == size && got_format == format) else {
            warn!(
                "terrain texture {path} is {}x{} {got_format:?}, not {}x{} {format:?} like {} (one mip level, \
                 kept in the main world): using flat colors",
                got.x, got.y, size.x, size.y, layers.paths[0]
            );
            settings.textures = false;
            return;
        };
        data.extend_from_slice(bytes);
    }
    let count = loaded.len() as u32;
    let mut array = Image::new(
        Extent3d { width: size.x, height: size.y, depth_or_array_layers: count },
        TextureDimension::D2,
        data,
        format,
        RenderAssetUsages::RENDER_WORLD,
    );
    array.texture_view_descriptor =
        Some(TextureViewDescriptor { dimension: Some(TextureViewDimension::D2Array), ..default() });
    // World-space coordinates run far past [0, 1]: the textures repeat.
    array.sampler = ImageSampler::Descriptor(ImageSamplerDescriptor {
        address_mode_u: ImageAddressMode::Repeat,
        address_mode_v: ImageAddressMode::Repeat,
        ..ImageSamplerDescriptor::linear()
    });
    layers.array = Some(images.add(array));
    layers.count = count;
}
