//! The shortest program that shows hex terrain: the plugin and a camera that streams terrain
//! around itself; the plugin lights what a `HexTerrainCamera` shows (sun, shadows, fog).

use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;

mod support;

fn main() {
    App::new()
        .add_plugins((DefaultPlugins, HexTerrainPlugins::default()))
        // Only acts when HEXTERRAIN_SCREENSHOT names a PNG: saves it after some frames and exits.
        .add_plugins(support::screenshot::ScreenshotModePlugin)
        .add_systems(Startup, |mut commands: Commands| {
            commands.spawn((
                Camera3d::default(),
                HexTerrainCamera,
                HexTerrainAgent::default(),
                Transform::from_xyz(0.0, 40.0, 45.0).looking_at(Vec3::ZERO, Vec3::Y),
            ));
        })
        .run();
}
