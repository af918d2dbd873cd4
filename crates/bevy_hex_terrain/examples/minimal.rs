//! The shortest program that shows hex terrain, the README's: the plugins and a camera that
//! streams terrain around itself; the plugin lights what a `HexTerrainCamera` shows (sun,
//! shadows, fog).

use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;

fn main() {
    App::new()
        // An unbounded continent; `HexTerrainPlugins::from_asset("maps/my.map.ron")` loads a map file.
        // With HEXTERRAIN_SCREENSHOT=out.png set, the screenshot plugin saves a picture and exits.
        .add_plugins((DefaultPlugins, HexTerrainPlugins::default(), HexScreenshotPlugin::default()))
        .add_systems(Startup, |mut commands: Commands| {
            // A camera that is lit and fogged, and keeps the terrain streamed around itself.
            commands.spawn((
                HexTerrainCamera,
                HexTerrainAgent::default(),
                Transform::from_xyz(0.0, 40.0, 45.0).looking_at(Vec3::ZERO, Vec3::Y),
            ));
        })
        .run();
}
