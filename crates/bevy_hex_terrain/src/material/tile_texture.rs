//! The tile state texture: an `Rgba16Uint` image holding [`TileStates`]' window, made in the
//! main world (a new one when the window size changes) and written in place in the render world
//! with the rows [`TileStateUpload`] carries, so a frame's changes cost their own bytes and a
//! frame without changes costs nothing. The image asset itself is never modified, which would
//! upload it whole.

use bevy::asset::RenderAssetUsages;
use bevy::prelude::*;
use bevy::render::render_asset::RenderAssets;
use bevy::render::render_resource::{
    Extent3d, Origin3d, TexelCopyBufferLayout, TexelCopyTextureInfo, TextureAspect, TextureDimension, TextureFormat,
};
use bevy::render::renderer::RenderQueue;
use bevy::render::texture::GpuImage;
use bevy::render::{Extract, ExtractSchedule, Render, RenderApp, RenderSystems};

use crate::tiles::{TEXEL_BYTES, TileStateUpload, TileStates};

/// The image the terrain material reads tile states from, and the texture generation of
/// [`TileStates`] it was made for.
#[derive(Resource, Debug, Clone, Reflect)]
#[reflect(Resource)]
pub struct TileStateTexture {
    /// The image (its pixels live in the render world only).
    pub handle: Handle<Image>,
    /// [`TileStates::texture_generation`] it holds.
    pub generation: u64,
}

/// Makes the texture and keeps the render world's copy of it current.
pub(super) struct TileTexturePlugin;

impl Plugin for TileTexturePlugin {
    fn build(&self, app: &mut App) {
        app.register_type::<TileStateTexture>().add_systems(Startup, create_texture).add_systems(
            Update,
            create_texture.in_set(crate::HexTerrainSystems::Render).before(super::update_material),
        );
        if let Some(render_app) = app.get_sub_app_mut(RenderApp) {
            render_app
                .init_resource::<PendingUploads>()
                .add_systems(ExtractSchedule, extract_uploads)
                .add_systems(Render, write_uploads.in_set(RenderSystems::PrepareResources));
        }
    }
}

/// Makes a texture of the window's size when there is none or the size changed.
pub(super) fn create_texture(
    mut commands: Commands,
    mut images: ResMut<Assets<Image>>,
    states: Res<TileStates>,
    texture: Option<Res<TileStateTexture>>,
) {
    let generation = states.texture_generation();
    if texture.is_some_and(|t| t.generation == generation) {
        return;
    }
    let size = states.window().1;
    let image = Image::new(
        Extent3d { width: size.x, height: size.y, depth_or_array_layers: 1 },
        TextureDimension::D2,
        vec![0; size.x as usize * size.y as usize * TEXEL_BYTES],
        TextureFormat::Rgba16Uint,
        RenderAssetUsages::RENDER_WORLD,
    );
    commands.insert_resource(TileStateTexture { handle: images.add(image), generation });
}

/// Uploads waiting for their texture, in order.
#[derive(Resource, Default)]
struct PendingUploads {
    uploads: Vec<TileStateUpload>,
    texture: Option<(AssetId<Image>, u64)>,
    bytes: Vec<u8>,
}

fn extract_uploads(
    upload: Extract<Res<TileStateUpload>>,
    texture: Extract<Option<Res<TileStateTexture>>>,
    mut pending: ResMut<PendingUploads>,
) {
    if let Some(texture) = texture.as_ref() {
        pending.texture = Some((texture.handle.id(), texture.generation));
    }
    if upload.is_changed() && !upload.spans.is_empty() {
        pending.uploads.push(upload.clone());
    }
}

/// Copies the pending rows into the texture once it exists on the GPU; uploads for an older
/// texture are dropped (the new one was filled whole). Runs of whole rows go in one copy.
fn write_uploads(mut pending: ResMut<PendingUploads>, images: Res<RenderAssets<GpuImage>>, queue: Res<RenderQueue>) {
    let Some((id, generation)) = pending.texture else { return };
    if pending.uploads.is_empty() {
        return;
    }
    pending.uploads.retain(|u| u.texture >= generation);
    let Some(gpu) = images.get(id) else { return };
    let PendingUploads { uploads, bytes, .. } = &mut *pending;
    let size = gpu.texture_descriptor.size;
    let (width, height) = (size.width, size.height);
    // Uploads for a texture not made yet wait; the others are written now.
    let ready = |u: &TileStateUpload| u.texture == generation && u.size == UVec2::new(width, height);
    for upload in uploads.iter().filter(|u| ready(u)) {
        let mut at = 0;
        let mut spans = upload.spans.iter().peekable();
        while let Some(&first) = spans.next() {
            // A span and the whole rows right below it, when it is a whole row itself.
            let (mut rows, mut texels) = (1, first.z);
            while first.x == 0
                && first.z == width
                && spans.peek().is_some_and(|s| s.x == 0 && s.z == width && s.y == first.y + rows)
            {
                spans.next();
                rows += 1;
                texels += width;
            }
            let data = &upload.data[at..at + texels as usize];
            at += texels as usize;
            if first.x + first.z > width || first.y + rows > height {
                continue;
            }
            bytes.clear();
            bytes.extend(data.iter().flat_map(|t| t.iter().flat_map(|v| v.to_le_bytes())));
            queue.write_texture(
                TexelCopyTextureInfo {
                    texture: &gpu.texture,
                    mip_level: 0,
                    origin: Origin3d { x: first.x, y: first.y, z: 0 },
                    aspect: TextureAspect::All,
                },
                bytes,
                TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(first.z * TEXEL_BYTES as u32),
                    rows_per_image: None,
                },
                Extent3d { width: first.z, height: rows, depth_or_array_layers: 1 },
            );
        }
    }
    uploads.retain(|u| !ready(u));
}
