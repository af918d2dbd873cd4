//! An agent walks a straight line east across an unbounded map; terrain streams in ahead of it
//! and is dropped behind. The camera follows; a counter shows live chunks, chunk latency and
//! what each frame draws (draw calls, instances, triangles, coarse chunks). Far chunks are drawn
//! coarse (see `HexStreamingSettings::coarse_distance`); `HEXTERRAIN_LOD=off` draws every chunk
//! full, to compare. In screenshot mode the counter is printed too. `HEXTERRAIN_STILL=1` keeps
//! the walker where it starts and spawns every prop at once: a settled view, for figures.

use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;

mod support;

/// World units the walker covers a second: about one 16-column chunk.
const SPEED: f32 = 24.0;

#[derive(Component)]
struct Walker;

#[derive(Component)]
struct Counter;

/// The walker stands still (`HEXTERRAIN_STILL`).
#[derive(Resource)]
struct Still(bool);

fn main() {
    let streaming = support::streaming_from_env();
    let still = std::env::var_os("HEXTERRAIN_STILL").is_some();
    let props = HexPropSettings { max_spawns_per_frame: if still { usize::MAX } else { 64 }, ..default() };
    App::new()
        .add_plugins((DefaultPlugins, HexTerrainPlugins::default()))
        .insert_resource(streaming)
        .insert_resource(props)
        .insert_resource(Still(still))
        .add_plugins(HexScreenshotPlugin::default())
        .add_plugins(support::render_figures::RenderFiguresPlugin)
        .insert_resource(HexTerrainMaterialSettings { outlines: true, outline_width: 0.04, ..default() })
        .add_systems(Startup, setup)
        .add_systems(Update, (walk, show_figures))
        .run();
}

fn setup(mut commands: Commands, mut meshes: ResMut<Assets<Mesh>>, mut materials: ResMut<Assets<StandardMaterial>>) {
    // The walker is the streaming agent; the camera is its child and follows it.
    commands
        .spawn((
            Walker,
            HexTerrainAgent::default(),
            Mesh3d(meshes.add(Capsule3d::new(0.4, 1.2))),
            MeshMaterial3d(materials.add(Color::srgb(0.85, 0.2, 0.15))),
            Transform::from_xyz(0.0, 5.0, 0.0),
        ))
        .with_child((HexTerrainCamera, Transform::from_xyz(-30.0, 45.0, 40.0).looking_at(Vec3::ZERO, Vec3::Y)));
    commands.spawn((
        Counter,
        Text::new(""),
        TextFont::from_font_size(18.0),
        Node { position_type: PositionType::Absolute, top: px(10.0), left: px(10.0), ..default() },
    ));
}

/// Walks east and stands on the real surface.
fn walk(time: Res<Time>, still: Res<Still>, map: Res<HexMap>, mut walker: Query<&mut Transform, With<Walker>>) {
    let speed = if still.0 { 0.0 } else { SPEED };
    for mut t in &mut walker {
        t.translation.x += speed * time.delta_secs();
        // The world ends 2^24 tiles out: the walker stops at its edge.
        match map.surface_height(t.translation) {
            Some(y) => t.translation.y = y + 0.9,
            None => t.translation.x -= speed * time.delta_secs(),
        }
    }
}

fn show_figures(
    streamer: Res<ChunkStreamer>,
    stats: Res<HexStreamingStats>,
    frame: Res<support::render_figures::RenderFigures>,
    props: Query<(), With<HexProp>>,
    mut counter: Query<&mut Text, With<Counter>>,
) {
    let mut latencies: Vec<f32> = stats.latencies().collect();
    latencies.sort_by(f32::total_cmp);
    let at = |p: f32| latencies.get(((latencies.len().max(1) - 1) as f32 * p) as usize).map_or(0.0, |s| s * 1e3);
    for mut text in &mut counter {
        text.0 = format!(
            "live chunks: {}   chunks built: {}   cancelled: {}   props: {}\nchunk latency p50 {:.0} ms, p99 {:.0} ms\n\
             frame: {}",
            streamer.live_chunks(),
            stats.tasks_started(),
            stats.tasks_cancelled(),
            props.iter().len(),
            at(0.5),
            at(0.99),
            *frame,
        );
        if std::env::var_os("HEXTERRAIN_SCREENSHOT").is_some() {
            println!("{}", text.0.replace('\n', " | "));
        }
    }
}
