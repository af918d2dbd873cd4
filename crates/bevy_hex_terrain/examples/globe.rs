//! A hex globe: the Continents globe (a Standard-size Goldberg globe, 4,412 tiles, 12 of them
//! pentagons, with Civilization's Continents map type and a climate by latitude) streamed to the
//! camera's horizon, lit by a sun over the camera's shoulder. Drag with the left button or use the arrow keys (WASD) to turn
//! it, the wheel to zoom from the whole planet to a few tiles; near the ground the view tilts
//! toward the horizon. `HEXTERRAIN_GLOBE_ALTITUDE` sets the camera's first altitude (the
//! screenshots at three zooms use it).

use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;

fn main() {
    let altitude = std::env::var("HEXTERRAIN_GLOBE_ALTITUDE").ok().and_then(|a| a.parse().ok()).unwrap_or(60.0);
    App::new()
        .insert_resource(ClearColor(Color::srgb(0.02, 0.02, 0.05)))
        // With HEXTERRAIN_SCREENSHOT=out.png set, the screenshot plugin saves a picture and exits.
        .add_plugins((
            DefaultPlugins,
            HexGlobePlugin::from_asset("maps/globe/continents.map.ron"),
            HexScreenshotPlugin::default(),
        ))
        .add_systems(Startup, move |mut commands: Commands| {
            // The orbit camera, which keeps the globe streamed to its horizon, with the sun over
            // its shoulder (from the top left of the view, wherever it flies).
            commands.spawn((
                Camera3d::default(),
                // Above the first continent, 130 degrees west and 20 north.
                GlobeCamera { altitude, ..GlobeCamera::above(-130f32.to_radians(), 20f32.to_radians()) },
                HexTerrainAgent::default(),
                children![(
                    DirectionalLight { illuminance: 9_000.0, ..default() },
                    Transform::from_rotation(Quat::from_euler(EulerRot::YXZ, -0.6, -0.5, 0.0)),
                )],
            ));
            commands.insert_resource(GlobalAmbientLight { brightness: 250.0, ..default() });
        })
        .run();
}
