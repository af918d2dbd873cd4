//! [`GlobeCamera`]: an orbit camera for a globe. Its place is a rotation (no angles, so no gimbal
//! lock at the poles) and an altitude; keys, a drag and the wheel turn the globe under it and
//! zoom, and near the ground the view tilts toward the horizon as a strategy game's camera does.

#[cfg(feature = "picking")]
use bevy::input::mouse::{AccumulatedMouseMotion, AccumulatedMouseScroll, MouseScrollUnit};
use bevy::prelude::*;

use super::HexGlobe;

/// An orbit camera around the [`HexGlobe`] (put it on the entity with the `Camera3d`, and a
/// [`HexTerrainAgent`](crate::HexTerrainAgent) to stream the globe to its horizon). The arrow
/// keys or WASD turn the globe under it (slower the lower it flies), a drag with the left button
/// turns it by the pointer's motion, the wheel zooms between `min_altitude` and `max_altitude`
/// (with the `picking` feature, on by default, which brings Bevy's keyboard and mouse input);
/// [`GlobeCamera::place`] gives its transform (the plugin writes it every frame). A game may
/// set `orientation` and `altitude` itself (to fly to a tile).
#[derive(Component, Debug, Clone, Copy, PartialEq, Reflect)]
#[reflect(Component, Default)]
#[require(Transform)]
pub struct GlobeCamera {
    /// The rotation taking a view from the world's `+z` (`+y` up) to the camera's: the camera
    /// lies on `orientation * Z` from the globe's center, and the top of its view is toward
    /// `orientation * Y` ([`GlobeCamera::above`] makes one from a longitude and latitude).
    pub orientation: Quat,
    /// Height above the globe's radius (its height 0), world units.
    pub altitude: f32,
    /// The lowest altitude the wheel zooms to.
    pub min_altitude: f32,
    /// The highest.
    pub max_altitude: f32,
    /// Radians a second the keys turn the globe at `max_altitude` (less lower down).
    pub key_speed: f32,
    /// Radians a pixel of drag turns the globe at `max_altitude` (less lower down).
    pub drag_speed: f32,
    /// The share of the altitude one wheel line zooms.
    pub zoom_speed: f32,
    /// How far the view tilts from straight down toward the horizon at `min_altitude`, radians.
    pub max_tilt: f32,
    /// The altitude under which the view starts to tilt (straight down above it: the whole
    /// planet in view).
    pub tilt_below: f32,
}

impl Default for GlobeCamera {
    /// Above longitude 0, latitude 20 north, at twice a Standard globe's radius.
    fn default() -> Self {
        Self::above(0.0, 20f32.to_radians())
    }
}

impl GlobeCamera {
    /// The camera above a longitude and a latitude (radians, east and north positive; the
    /// core's [`GlobeTileInfo`](hex_terrain::GlobeTileInfo) convention: longitude 0 toward the
    /// world's `+x`, 90 east toward `-z`), north up, at the default altitude.
    #[must_use]
    pub fn above(longitude: f32, latitude: f32) -> Self {
        Self {
            orientation: Quat::from_rotation_y(longitude + std::f32::consts::FRAC_PI_2)
                * Quat::from_rotation_x(-latitude),
            altitude: 60.0,
            min_altitude: 3.0,
            max_altitude: 150.0,
            key_speed: 1.2,
            drag_speed: 0.004,
            zoom_speed: 0.1,
            max_tilt: 50f32.to_radians(),
            tilt_below: 24.0,
        }
    }

    /// The camera's transform around a globe of radius `radius` centered at the origin: at
    /// `radius + altitude` along `orientation * Z`, looking at the center with `orientation * Y`
    /// up, tilted toward the horizon from `tilt_below` down, by `max_tilt` at `min_altitude`.
    #[must_use]
    pub fn place(&self, radius: f32) -> Transform {
        let out = self.orientation * Vec3::Z;
        let up = self.orientation * Vec3::Y;
        let mut transform = Transform::from_translation(out * (radius + self.altitude)).looking_at(Vec3::ZERO, up);
        let span = (self.tilt_below - self.min_altitude).max(f32::EPSILON);
        let low = 1.0 - ((self.altitude - self.min_altitude) / span).clamp(0.0, 1.0);
        transform.rotate_local_x(self.max_tilt * low * low);
        transform
    }

    /// Turns the globe under the camera: `east` radians toward the right of the view, `north`
    /// toward its top.
    pub fn turn(&mut self, east: f32, north: f32) {
        self.orientation = (self.orientation * Quat::from_rotation_y(east) * Quat::from_rotation_x(-north)).normalize();
    }
}

/// Reads the keys, the drag and the wheel into every [`GlobeCamera`] (Bevy's keyboard and mouse
/// input come with the `picking` feature).
#[cfg(feature = "picking")]
pub(super) fn orbit(
    keys: Option<Res<ButtonInput<KeyCode>>>,
    buttons: Option<Res<ButtonInput<MouseButton>>>,
    motion: Option<Res<AccumulatedMouseMotion>>,
    scroll: Option<Res<AccumulatedMouseScroll>>,
    time: Res<Time>,
    mut cameras: Query<&mut GlobeCamera>,
) {
    let dt = time.delta_secs();
    let held = |codes: [KeyCode; 2]| keys.as_ref().is_some_and(|k| k.any_pressed(codes));
    let axis = |plus, minus| f32::from(u8::from(plus)) - f32::from(u8::from(minus));
    let east = axis(held([KeyCode::ArrowRight, KeyCode::KeyD]), held([KeyCode::ArrowLeft, KeyCode::KeyA]));
    let north = axis(held([KeyCode::ArrowUp, KeyCode::KeyW]), held([KeyCode::ArrowDown, KeyCode::KeyS]));
    let drag = match (buttons, motion) {
        (Some(b), Some(m)) if b.pressed(MouseButton::Left) => m.delta,
        _ => Vec2::ZERO,
    };
    let lines = scroll.map_or(0.0, |s| match s.unit {
        MouseScrollUnit::Line => s.delta.y,
        MouseScrollUnit::Pixel => s.delta.y / 40.0,
    });
    for mut camera in &mut cameras {
        // Turning slows down with the altitude: a share of the speed at `max_altitude`.
        let pace = (camera.altitude / camera.max_altitude.max(f32::EPSILON)).clamp(0.02, 1.0);
        let (key, mouse) = (camera.key_speed * pace * dt, camera.drag_speed * pace);
        // Dragging moves the globe with the pointer: the view goes the other way.
        let (e, n) = (east * key - drag.x * mouse, north * key + drag.y * mouse);
        if e != 0.0 || n != 0.0 {
            camera.turn(e, n);
        }
        if lines != 0.0 {
            let altitude = camera.altitude * (1.0 - camera.zoom_speed).powf(lines);
            camera.altitude = altitude.clamp(camera.min_altitude, camera.max_altitude);
        }
    }
}

/// Writes every [`GlobeCamera`]'s transform around the globe (radius 1 before a globe is shown).
pub(super) fn place(globe: Res<HexGlobe>, mut cameras: Query<(&GlobeCamera, &mut Transform)>) {
    let radius = globe.globe().map_or(1.0, |g| g.radius() as f32);
    for (camera, mut transform) in &mut cameras {
        let placed = camera.place(radius);
        if *transform != placed {
            *transform = placed;
        }
    }
}
