//! A hex globe: the Continents globe (a Standard-size Goldberg globe, 4,412 tiles, 12 of them
//! pentagons, with Civilization's Continents map type and a climate by latitude) streamed to the
//! camera's horizon, lit by a sun over the camera's shoulder. Drag with the left button or use
//! the arrow keys (WASD) to turn it, the wheel to zoom from the whole planet to a few tiles; near
//! the ground the view tilts toward the horizon. The line at the top names the tile under the
//! mouse (picked on the globe's surface; its biome, latitude and longitude, and whether it is a
//! pentagon), or, with no mouse over the globe, the tile at the center of the view.
//! `HEXTERRAIN_GLOBE_ALTITUDE` sets the camera's first altitude and `HEXTERRAIN_GLOBE_AT=LON,LAT`
//! its first place in degrees (the screenshots use them: `0,90` looks down on the north pole, a
//! pentagon).

use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;
use bevy_hex_terrain::{HexGlobe, HoveredGlobeTile};

/// The text naming the tile under the mouse.
#[derive(Component)]
struct TileLabel;

fn main() {
    let altitude = std::env::var("HEXTERRAIN_GLOBE_ALTITUDE").ok().and_then(|a| a.parse().ok()).unwrap_or(60.0);
    // Above the first continent, 130 degrees west and 20 north, unless told otherwise.
    let at = std::env::var("HEXTERRAIN_GLOBE_AT")
        .ok()
        .and_then(|at| {
            at.split_once(',').and_then(|(lon, lat)| Some((lon.trim().parse().ok()?, lat.trim().parse().ok()?)))
        })
        .unwrap_or((-130f32, 20f32));
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
                GlobeCamera { altitude, ..GlobeCamera::above(at.0.to_radians(), at.1.to_radians()) },
                HexTerrainAgent::default(),
                children![(
                    DirectionalLight { illuminance: 9_000.0, ..default() },
                    Transform::from_rotation(Quat::from_euler(EulerRot::YXZ, -0.6, -0.5, 0.0)),
                )],
            ));
            commands.insert_resource(GlobalAmbientLight { brightness: 250.0, ..default() });
            commands.spawn((
                Text::default(),
                TextFont::from_font_size(16.0),
                Node { position_type: PositionType::Absolute, top: px(10.0), left: px(10.0), ..default() },
                TileLabel,
            ));
        })
        .add_systems(Update, name_the_tile)
        .run();
}

/// Names the tile under the mouse, else the one at the center of the view.
fn name_the_tile(
    hovered: Res<HoveredGlobeTile>,
    globe: Res<HexGlobe>,
    cameras: Query<&GlobalTransform, With<GlobeCamera>>,
    mut labels: Query<&mut Text, With<TileLabel>>,
) {
    let (Some(globe), Ok(camera), Ok(mut label)) = (globe.globe(), cameras.single(), labels.single_mut()) else {
        return;
    };
    let center = || {
        let (origin, forward) = (camera.translation().as_dvec3(), camera.forward().as_dvec3());
        globe.raycast(origin.to_array(), forward.to_array(), f64::MAX).map(|hit| hit.tile)
    };
    let (tile, where_) = match hovered.tile() {
        Some(tile) => (Some(tile), "under the mouse"),
        None => (center(), "at the center of the view"),
    };
    let text = tile.and_then(|t| globe.tile_info(t)).map_or_else(String::new, |info| {
        format!(
            "Tile {} {where_}: {}, latitude {:.1}, longitude {:.1}{}",
            info.tile.0,
            info.biome.name(),
            info.latitude,
            info.longitude,
            if info.pentagon { ", a pentagon (five neighbors)" } else { "" }
        )
    });
    if label.0 != text {
        label.0 = text;
    }
}
