//! The camera on the minimap: the spot it looks at and its view on the ground, drawn as an
//! outline over the picture.

use bevy::ecs::system::SystemParam;
use bevy::math::{DVec2, DVec3, Vec3A};
use bevy::prelude::*;

use super::{HexMinimapSettings, MinimapPicture, redraw_outline};
use crate::HexMap;
use crate::picking::FrameOrigin;

/// Marks the camera whose view the minimap outlines (without one, the first active 3D camera).
#[derive(Component, Debug, Clone, Copy, Default, Reflect)]
#[reflect(Component, Default)]
pub struct HexMinimapCamera;

/// The camera the minimap follows, in the world's f64 frame.
#[derive(SystemParam)]
pub struct MinimapCameraView<'w, 's> {
    cameras: Query<'w, 's, (&'static Camera, &'static GlobalTransform, Has<HexMinimapCamera>), With<Camera3d>>,
    frame: FrameOrigin<'w, 's>,
}

impl MinimapCameraView<'_, '_> {
    fn camera(&self) -> Option<(&Camera, &GlobalTransform)> {
        let active = || self.cameras.iter().filter(|(c, ..)| c.is_active);
        active().find(|(.., marked)| *marked).or_else(|| active().next()).map(|(c, t, _)| (c, t))
    }

    /// A ray's point on the sea-level plane, or `far` world units out along its horizontal
    /// direction when it does not reach the plane.
    fn ground(map: &HexMap, origin: DVec3, direction: DVec3, far: f64) -> DVec2 {
        let level = f64::from(map.terrain().sea_level());
        let flat = DVec2::new(direction.x, direction.z).normalize_or_zero();
        if direction.y < -1e-6 {
            let t = (level - origin.y) / direction.y;
            if t >= 0.0 {
                let hit = origin + direction * t;
                let reach = DVec2::new(hit.x - origin.x, hit.z - origin.z);
                if reach.length() <= far {
                    return DVec2::new(hit.x, hit.z);
                }
            }
        }
        DVec2::new(origin.x, origin.z) + flat * far
    }

    /// World `(x, z)` the camera looks at on the sea-level plane (below it, when it looks up).
    #[must_use]
    pub fn focus(&self, map: &HexMap) -> Option<DVec2> {
        let (_, transform) = self.camera()?;
        let origin = transform.translation().as_dvec3() + self.frame.world();
        let forward = transform.forward().as_dvec3();
        Some(Self::ground(map, origin, forward, 4.0 * origin.y.abs().max(1.0)))
    }

    /// The camera's view on the sea-level plane: the four corner rays of its frustum, each
    /// stopped `far` out when it passes over the horizon.
    #[must_use]
    pub fn footprint(&self, map: &HexMap, far: f64) -> Option<[[f64; 2]; 4]> {
        let (camera, transform) = self.camera()?;
        let offset = self.frame.world();
        let corner = |x: f32, y: f32| {
            // Reverse-z: 1 is the near plane; a point a little farther gives the direction.
            let near = camera.ndc_to_world(transform, Vec3A::new(x, y, 1.0))?;
            let farther = camera.ndc_to_world(transform, Vec3A::new(x, y, 0.5))?;
            let direction = (farther - near).as_dvec3().normalize_or_zero();
            (direction != DVec3::ZERO && near.is_finite())
                .then(|| Self::ground(map, near.as_dvec3() + offset, direction, far).to_array())
        };
        Some([corner(-1.0, 1.0)?, corner(1.0, 1.0)?, corner(1.0, -1.0)?, corner(-1.0, -1.0)?])
    }
}

/// Draws the camera's view over the picture, restoring the pixels under the last outline.
pub(super) fn draw_outline(
    mut picture: ResMut<MinimapPicture>,
    settings: Res<HexMinimapSettings>,
    camera: MinimapCameraView,
    map: Res<HexMap>,
    mut images: ResMut<Assets<Image>>,
) {
    let picture = &mut *picture.bypass_change_detection();
    let Some(shown) = &picture.picture else { return };
    // Rays over the horizon stop a few picture widths out.
    let far = 4.0 * shown.step() * f64::from(shown.size()[0].max(shown.size()[1]));
    let outline = camera.footprint(&map, far).map(|f| shown.outline(&f)).unwrap_or_default();
    // The repaint clears the outline it painted over: an equal outline is drawn already.
    if outline == picture.outline {
        return;
    }
    let Some(mut image) = images.get_mut(&picture.image) else { return };
    let Some(data) = image.data.as_mut() else { return };
    if redraw_outline(data, &picture.painted, &picture.outline, &outline, settings.outline_color) {
        picture.outline = outline;
    }
}
