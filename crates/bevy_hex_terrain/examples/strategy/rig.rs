//! The camera rig: a pivot on the ground the camera orbits, moved by keys, the screen edge, the
//! wheel and the minimap.

use bevy::input::mouse::AccumulatedMouseScroll;
use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;

use crate::Game;

/// The camera's pivot on the ground; the streaming agent.
#[derive(Component)]
pub(crate) struct Rig {
    pub(crate) focus: Vec3,
    pub(crate) yaw: f32,
    pub(crate) distance: f32,
    pub(crate) target_focus: Vec3,
    pub(crate) target_yaw: f32,
    pub(crate) target_distance: f32,
}

/// A press or drag on the minimap sends the camera there.
pub(crate) fn follow_minimap(mut go: MessageReader<MinimapNavigate>, mut rigs: Query<&mut Rig>) {
    for go in go.read() {
        for mut rig in &mut rigs {
            rig.target_focus = Vec3::new(go.world.x as f32, 0.0, go.world.y as f32);
        }
    }
}

pub(crate) fn camera_controls(
    time: Res<Time>,
    game: Res<Game>,
    keys: Res<ButtonInput<KeyCode>>,
    scroll: Res<AccumulatedMouseScroll>,
    windows: Query<&Window>,
    mut rigs: Query<(&mut Rig, &mut Transform, &Children, &mut HexTerrainAgent)>,
    mut cameras: Query<&mut Transform, (With<Camera3d>, Without<Rig>)>,
) {
    let dt = time.delta_secs();
    for (mut rig, mut t, children, mut agent) in &mut rigs {
        let mut pan = Vec2::ZERO;
        for (key, d) in [
            (KeyCode::KeyW, Vec2::NEG_Y),
            (KeyCode::ArrowUp, Vec2::NEG_Y),
            (KeyCode::KeyS, Vec2::Y),
            (KeyCode::ArrowDown, Vec2::Y),
            (KeyCode::KeyA, Vec2::NEG_X),
            (KeyCode::ArrowLeft, Vec2::NEG_X),
            (KeyCode::KeyD, Vec2::X),
            (KeyCode::ArrowRight, Vec2::X),
        ] {
            if keys.pressed(key) {
                pan += d;
            }
        }
        // Screen-edge panning.
        if let Some(cursor) = windows.iter().next().and_then(|w| w.cursor_position().map(|c| (c, w.size()))) {
            let (c, size) = cursor;
            let m = 8.0;
            if c.x < m {
                pan.x -= 1.0;
            } else if c.x > size.x - m {
                pan.x += 1.0;
            }
            if c.y < m {
                pan.y -= 1.0;
            } else if c.y > size.y - m {
                pan.y += 1.0;
            }
        }
        if game.auto_pan {
            pan.x += 1.0;
        }
        let speed = rig.target_distance * 0.9;
        let rotated = Vec2::from_angle(-rig.target_yaw).rotate(pan.normalize_or_zero());
        rig.target_focus += Vec3::new(rotated.x, 0.0, rotated.y) * speed * dt;
        if keys.pressed(KeyCode::KeyQ) {
            rig.target_yaw += 1.5 * dt;
        }
        if keys.pressed(KeyCode::KeyE) {
            rig.target_yaw -= 1.5 * dt;
        }
        rig.target_distance = (rig.target_distance * (1.0 - scroll.delta.y * 0.1)).clamp(8.0, 120.0);
        // Smooth: ease towards the targets.
        let k = 1.0 - (-10.0 * dt).exp();
        let (tf, ty, td) = (rig.target_focus, rig.target_yaw, rig.target_distance);
        rig.focus = rig.focus.lerp(tf, k);
        rig.yaw += (ty - rig.yaw) * k;
        rig.distance += (td - rig.distance) * k;
        // Zoomed out the camera sees farther: keep terrain loaded as far (a chunk is about 24
        // units across), and let levels of detail keep what that costs down.
        let radius = Some(2 + (rig.distance / 40.0) as u32);
        if agent.radius != radius {
            agent.radius = radius;
        }
        t.translation = rig.focus;
        for child in children.iter() {
            if let Ok(mut cam) = cameras.get_mut(child) {
                let offset = Quat::from_rotation_y(rig.yaw) * Vec3::new(0.0, rig.distance, rig.distance * 0.8);
                *cam = Transform::from_translation(offset).looking_at(Vec3::ZERO, Vec3::Y);
            }
        }
    }
}
