//! Pressing and dragging on the minimap: the pixel under the pointer, its tile and world
//! position, sent as [`MinimapNavigate`].

use bevy::math::DVec2;
use bevy::picking::events::{Drag, Pointer, Press};
use bevy::prelude::*;

use super::view::MinimapCameraView;
use super::{HexMinimap, MinimapNavigate, MinimapPicture};
use crate::HexMap;

/// Sends the camera where the pointer pressed.
pub(super) fn press(
    press: On<Pointer<Press>>,
    mut picture: ResMut<MinimapPicture>,
    camera: MinimapCameraView,
    map: Res<HexMap>,
    mut go: MessageWriter<MinimapNavigate>,
) {
    let Some(at) = press.hit.position.map(|p| p.truncate()) else { return };
    // The drag observer goes on from here.
    picture.pressed_at = Some(at);
    if let Some(message) = navigate(&picture, &camera, &map, at) {
        go.write(message);
    }
}

/// Keeps sending the camera under the pointer while it drags.
pub(super) fn drag(
    drag: On<Pointer<Drag>>,
    picture: Res<MinimapPicture>,
    nodes: Query<&ComputedNode, With<HexMinimap>>,
    camera: MinimapCameraView,
    map: Res<HexMap>,
    mut go: MessageWriter<MinimapNavigate>,
) {
    let (Some(start), Ok(node)) = (picture.pressed_at, nodes.get(drag.entity)) else { return };
    let size = node.size() * node.inverse_scale_factor();
    if size.min_element() <= 0.0 {
        return;
    }
    if let Some(message) = navigate(&picture, &camera, &map, start + drag.distance / size) {
        go.write(message);
    }
}

/// Where a position on the node (`-0.5..0.5` on each axis, the center at zero, as Bevy's UI
/// picking reports it) sends the camera.
fn navigate(picture: &MinimapPicture, camera: &MinimapCameraView, map: &HexMap, at: Vec2) -> Option<MinimapNavigate> {
    let shown = picture.picture.as_ref()?;
    let [w, h] = shown.size().map(f64::from);
    let at = at.as_dvec2() + DVec2::splat(0.5);
    let (px, py) = (at.x.clamp(0.0, 1.0) * w, at.y.clamp(0.0, 1.0) * h);
    let tile = shown.tile_at_pixel((px as u32).min(shown.size()[0] - 1), (py as u32).min(shown.size()[1] - 1))?;
    let [mut x, z] = shown.pixel_to_world(px, py);
    if let (Some(wrap), Some(focus)) = (map.terrain().wrap(), camera.focus(map)) {
        // The copy of the spot nearest the camera.
        x += ((focus.x - x) / wrap.width).round() * wrap.width;
    }
    Some(MinimapNavigate { tile, world: DVec2::new(x, z) })
}
