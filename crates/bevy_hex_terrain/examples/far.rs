//! A camera flies east over an unbounded world, starting a million units from the origin, and
//! keeps going. With `big_space`'s floating origin (the `big_space` feature of
//! `bevy_hex_terrain`), chunks sit in grid cells and render from the camera's cell: no jitter,
//! no cracks, however far out. The counter shows the camera's f64 position, its cell and the
//! tile under it.

use bevy::math::DVec3;
use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;
use big_space::prelude::*;

mod support;

/// Where the flight starts, in world units east of the origin.
const START_X: f64 = 1.0e6;
/// World units a second: about two 16-column chunks.
const SPEED: f32 = 48.0;

#[derive(Component)]
struct Flyer;

#[derive(Component)]
struct Counter;

fn main() {
    support::require_asset("maps/continent.map.ron");
    App::new()
        .add_plugins((
            DefaultPlugins.build().disable::<TransformPlugin>(),
            BigSpaceDefaultPlugins,
            HexTerrainPlugins::from_asset("maps/continent.map.ron"),
            HexBigSpacePlugin,
        ))
        .add_plugins(HexScreenshotPlugin::default())
        .insert_resource(HexTerrainMaterialSettings { outlines: true, outline_width: 0.04, ..default() })
        .add_systems(Startup, setup)
        .add_systems(Update, (fly, show_position))
        .run();
}

fn setup(mut commands: Commands) {
    commands.spawn_big_space(Grid::default(), |grid| {
        grid.insert(HexTerrainGrid);
        // The camera is the streaming agent and the floating origin. Its cell and small
        // transform come from the f64 start position.
        let (cell, local) = grid.grid().translation_to_grid(DVec3::new(START_X, 40.0, 40.0));
        grid.spawn_spatial((
            Flyer,
            Camera3d::default(),
            FloatingOrigin,
            HexTerrainAgent { radius: Some(3) },
            cell,
            Transform::from_translation(local).looking_to(Vec3::new(0.35, -0.8, -0.6), Vec3::Y),
        ));
        grid.spawn_spatial((
            DirectionalLight { illuminance: 9000.0, shadow_maps_enabled: false, ..default() },
            Transform::default().looking_to(Vec3::new(-0.4, -1.0, -0.3), Vec3::Y),
        ));
    });
    commands.spawn((
        Counter,
        Text::new(""),
        TextFont::from_font_size(18.0),
        Node { position_type: PositionType::Absolute, top: px(10.0), left: px(10.0), ..default() },
    ));
}

/// Moves east by a delta (`big_space` moves the camera to the next cell when it leaves one).
fn fly(time: Res<Time>, mut flyer: Query<&mut Transform, With<Flyer>>) {
    for mut t in &mut flyer {
        t.translation.x += SPEED * time.delta_secs();
    }
}

fn show_position(
    map: Res<HexMap>,
    streamer: Res<ChunkStreamer>,
    grids: Query<&Grid>,
    flyer: Query<(&CellCoord, &Transform, &ChildOf), With<Flyer>>,
    mut counter: Query<&mut Text, With<Counter>>,
) {
    let Ok((cell, transform, parent)) = flyer.single() else { return };
    let Ok(grid) = grids.get(parent.parent()) else { return };
    let at = grid.grid_position_double(cell, transform);
    let Some(tile) = map.tile_at_f64(at) else { return };
    for mut text in &mut counter {
        text.0 = format!(
            "camera x {:.3}  z {:.3}  (cell {} {})\ntile under it {} {}   live chunks {}",
            at.x,
            at.z,
            cell.x,
            cell.z,
            tile.x,
            tile.y,
            streamer.live_chunks()
        );
    }
}
