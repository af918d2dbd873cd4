//! The picture the minimap shows: built on the async compute pool, painted with the tiles'
//! state, repainted where the tile states were written this frame.

use std::sync::Arc;

use bevy::asset::RenderAssetUsages;
use bevy::image::ImageSampler;
use bevy::prelude::*;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat};
use bevy::tasks::futures::check_ready;
use bevy::tasks::{AsyncComputeTaskPool, Task};
use hex_terrain::hexx::Hex;
use hex_terrain::minimap::{Minimap, MinimapStyle, TileLook};
use hex_terrain::{Terrain, TileRect};

use super::HexMinimapSettings;
use super::view::MinimapCameraView;
use crate::HexMap;
use crate::tiles::{HexTileStateStyle, TileStates};

/// The picture shown and what it is built from (the core's picture and the building task are
/// not reflected).
#[derive(Resource, Default, Reflect)]
#[reflect(Resource, Default)]
pub struct MinimapPicture {
    #[reflect(ignore)]
    pub(super) picture: Option<Minimap>,
    /// The painted picture without the outline (RGBA8 sRGB).
    pub(super) painted: Vec<u8>,
    /// The outline's pixels drawn over it.
    pub(super) outline: Vec<u32>,
    pub(super) image: Handle<Image>,
    #[reflect(ignore)]
    pub(super) task: Option<Task<Option<Minimap>>>,
    /// What the shown (or building) picture was made for: the map's generation and the region.
    #[reflect(ignore)]
    pub(super) made_for: Option<(u64, TileRect)>,
    /// Pixels repainted since the start (figures for tests and the stats overlay).
    pub(super) repainted: u64,
    /// Pictures built since the start.
    pub(super) builds: u64,
    /// Where on the node the pointer last pressed (`-0.5..0.5`), for drags.
    pub(super) pressed_at: Option<Vec2>,
}

impl MinimapPicture {
    /// The picture shown, with its pixels' tiles and the world position of every pixel; `None`
    /// until the first is built.
    #[must_use]
    pub fn minimap(&self) -> Option<&Minimap> {
        self.picture.as_ref()
    }

    /// The image the node shows.
    #[must_use]
    pub fn image(&self) -> &Handle<Image> {
        &self.image
    }

    /// Whether a picture is being built.
    #[must_use]
    pub fn is_building(&self) -> bool {
        self.task.is_some()
    }

    /// Pixels repainted from tile state changes since the start (a full paint counts them all).
    #[must_use]
    pub fn repainted_pixels(&self) -> u64 {
        self.repainted
    }

    /// Pictures built since the start (a new map, a hot reload, a change of style, the camera
    /// leaving an unbounded map's region).
    #[must_use]
    pub fn builds(&self) -> u64 {
        self.builds
    }
}

pub(crate) fn new_image([w, h]: [u32; 2], data: Vec<u8>) -> Image {
    let size = Extent3d { width: w, height: h, depth_or_array_layers: 1 };
    let mut image =
        Image::new(size, TextureDimension::D2, data, TextureFormat::Rgba8UnormSrgb, RenderAssetUsages::default());
    image.sampler = ImageSampler::nearest();
    image
}

/// The region a picture shows: a bounded map's tiles, or tiles around the camera's focus on an
/// unbounded world (kept while the focus stays in the middle half).
pub(super) fn region(
    terrain: &Terrain,
    settings: &HexMinimapSettings,
    focus: Option<Hex>,
    current: Option<TileRect>,
) -> TileRect {
    if let Some(bounds) = terrain.bounds() {
        return bounds;
    }
    let size = settings.region.clamp(UVec2::splat(4), UVec2::splat(1024));
    let [col, row] = focus.map_or([0, 0], |t| terrain.offset_of(t));
    if let Some(r) = current {
        let (w, h) = ((r.max[0] - r.min[0]) / 4, (r.max[1] - r.min[1]) / 4);
        if col >= r.min[0] + w
            && col < r.max[0] - w
            && row >= r.min[1] + h
            && row < r.max[1] - h
            && r.max[0] - r.min[0] == size.x as i32
            && r.max[1] - r.min[1] == size.y as i32
        {
            return r;
        }
    }
    TileRect::new([col - size.x as i32 / 2, row - size.y as i32 / 2], [size.x, size.y])
}

/// Starts building a picture when the map, the style or an unbounded map's region changed.
pub(super) fn build_picture(
    map: Res<HexMap>,
    settings: Res<HexMinimapSettings>,
    palette: Option<Res<crate::HexTerrainMaterialSettings>>,
    tile_style: Res<HexTileStateStyle>,
    camera: MinimapCameraView,
    mut picture: ResMut<MinimapPicture>,
) {
    let terrain: &Arc<Terrain> = map.terrain();
    let focus = camera.focus(&map).and_then(|p| terrain.tile_at(p.x, p.y));
    let current = picture.made_for.map(|(_, r)| r);
    let region = region(terrain, &settings, focus, current);
    let restyled = settings.is_changed() || tile_style.is_changed() || palette.as_ref().is_some_and(|a| a.is_changed());
    if !restyled && picture.made_for == Some((map.generation(), region)) {
        return;
    }
    let mut style = settings.style();
    match_terrain(&mut style, palette.as_deref(), &tile_style);
    let (terrain, size) = (Arc::clone(terrain), settings.size.to_array());
    picture.made_for = Some((map.generation(), region));
    picture.task = Some(AsyncComputeTaskPool::get().spawn(async move { Minimap::new(&terrain, region, size, style) }));
}

/// The terrain's colors (the material's palette, when it is there) and the tile states' style
/// (fog on or off, owner colors), so the minimap matches the terrain.
pub(crate) fn match_terrain(
    style: &mut MinimapStyle,
    palette: Option<&crate::HexTerrainMaterialSettings>,
    tiles: &HexTileStateStyle,
) {
    let rgb = |c: Color| {
        let [r, g, b, _] = c.to_srgba().to_u8_array();
        [r, g, b]
    };
    if let Some(palette) = palette {
        style.kind_colors = palette.colors.map(rgb);
    }
    style.fog_of_war &= tiles.fog_of_war;
    style.owner_colors = (0..crate::tiles::MAX_OWNERS).map(|owner| rgb(tiles.owner_color(owner))).collect();
}

/// Shows a finished picture: painted whole with the tiles' state.
pub(super) fn finish_picture(
    mut picture: ResMut<MinimapPicture>,
    states: Res<TileStates>,
    mut images: ResMut<Assets<Image>>,
) {
    let Some(task) = picture.task.as_mut() else { return };
    let Some(built) = check_ready(task) else { return };
    let picture = &mut *picture;
    picture.task = None;
    let Some(built) = built else { return };
    let painted = built.paint(|t| look(&states, t));
    picture.repainted += (painted.len() / 4) as u64;
    picture.builds += 1;
    picture.outline.clear();
    if let Some(mut image) = images.get_mut(&picture.image) {
        *image = new_image(built.size(), painted.clone());
    }
    picture.painted = painted;
    picture.picture = Some(built);
}

/// A tile's look from the tile states.
pub(super) fn look(states: &TileStates, tile: Hex) -> TileLook {
    TileLook { fog: states.visibility(tile), owner: states.owner(tile) }
}

/// Repaints the tiles written this frame (and their neighbors) in the shown picture.
pub(super) fn repaint(mut picture: ResMut<MinimapPicture>, states: Res<TileStates>, mut images: ResMut<Assets<Image>>) {
    if !states.is_changed() {
        return;
    }
    let picture = &mut *picture;
    let Some(shown) = &picture.picture else { return };
    let written = match states.changed_tiles() {
        None => {
            picture.painted = shown.paint(|t| look(&states, t));
            picture.painted.len() / 4
        }
        Some(tiles) => shown.repaint(tiles, |t| look(&states, t), &mut picture.painted),
    };
    if written == 0 {
        return;
    }
    picture.repainted += written as u64;
    if let Some(mut image) = images.get_mut(&picture.image)
        && let Some(data) = image.data.as_mut()
    {
        data.copy_from_slice(&picture.painted);
        // The outline is drawn again over the repainted picture.
        picture.outline.clear();
    }
}
