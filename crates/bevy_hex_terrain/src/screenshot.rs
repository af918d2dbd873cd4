//! [`HexScreenshotPlugin`]: a picture of the primary window after some frames, then exit: how a
//! program, run headless under `xvfb-run` (Mesa's software Vulkan renders there), shows what it
//! draws. The examples, the README's pictures and the windowed tests are made with it.

use std::path::PathBuf;

use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured, save_to_disk};

/// Saves a screenshot of the primary window to `path` after `frames` frames, once the terrain
/// has been on screen for ten frames (every wanted chunk showing the map: in an
/// unoptimised build the first chunks take a while), logs the mean frame time of the frames
/// after the first ten (which compile pipelines), and exits the app with status 0. A terrain
/// that has not settled by four times `frames` is taken as it is. Without a `path` it does
/// nothing, so a game may keep it in every build.
///
/// Its default reads the environment: `HEXTERRAIN_SCREENSHOT` (the picture's path; PNG needs
/// Bevy's `png` feature, one of its defaults) and `HEXTERRAIN_FRAMES` (default 60). Not part of
/// [`HexTerrainPlugins`](crate::HexTerrainPlugins): add it yourself.
///
/// ```no_run
/// use bevy::prelude::*;
/// use bevy_hex_terrain::prelude::*;
///
/// // HEXTERRAIN_SCREENSHOT=out.png xvfb-run -a cargo run: writes out.png and exits.
/// App::new()
///     .add_plugins((DefaultPlugins, HexTerrainPlugins::default(), HexScreenshotPlugin::default()))
///     .run();
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct HexScreenshotPlugin {
    /// Where the picture goes (its extension names the format); `None`: no picture.
    pub path: Option<PathBuf>,
    /// Frames to run before taking it (at least 1).
    pub frames: u32,
}

impl Default for HexScreenshotPlugin {
    fn default() -> Self {
        Self {
            path: std::env::var_os("HEXTERRAIN_SCREENSHOT").map(PathBuf::from),
            frames: std::env::var("HEXTERRAIN_FRAMES").ok().and_then(|f| f.parse().ok()).unwrap_or(60),
        }
    }
}

impl Plugin for HexScreenshotPlugin {
    fn build(&self, app: &mut App) {
        let Some(path) = self.path.clone() else { return };
        let mode = ScreenshotMode {
            path,
            frames: self.frames.max(1),
            seen: 0,
            settled_at: None,
            requested: false,
            timing_from: None,
        };
        app.insert_resource(mode).add_systems(Last, screenshot_after_frames);
    }
}

/// Frames a screenshot waits after the terrain first settled (new meshes' pipelines compile).
const SETTLE_FRAMES: u32 = 10;

#[derive(Resource)]
struct ScreenshotMode {
    path: PathBuf,
    frames: u32,
    seen: u32,
    /// The frame the terrain first settled on.
    settled_at: Option<u32>,
    requested: bool,
    /// Start of the eleventh frame, once reached.
    timing_from: Option<std::time::Instant>,
}

/// The screenshot was written (or failed, logged): the app exits.
#[derive(Resource)]
struct Saved;

fn screenshot_after_frames(
    mut commands: Commands,
    mut mode: ResMut<ScreenshotMode>,
    streamer: Option<Res<crate::ChunkStreamer>>,
    globe: Option<Res<crate::GlobeStreamer>>,
    saved: Option<Res<Saved>>,
    mut exit: MessageWriter<AppExit>,
) {
    if saved.is_some() {
        exit.write(AppExit::Success);
        return;
    }
    mode.seen += 1;
    if mode.seen == 10 {
        mode.timing_from = Some(std::time::Instant::now());
    }
    let settled = streamer.is_some_and(|s| s.is_settled()) || globe.is_some_and(|g| g.is_settled());
    if mode.settled_at.is_none() && settled {
        mode.settled_at = Some(mode.seen);
    }
    let settled = mode.settled_at.is_some_and(|at| mode.seen >= at + SETTLE_FRAMES);
    if mode.requested || mode.seen < mode.frames || !(settled || mode.seen >= mode.frames.saturating_mul(4)) {
        return;
    }
    mode.requested = true;
    if let Some(from) = mode.timing_from {
        let frames = mode.seen - 10;
        if frames > 0 {
            let ms = from.elapsed().as_secs_f64() * 1e3 / f64::from(frames);
            info!("mean frame time: {ms:.1} ms over {frames} frames");
        }
    }
    commands
        .spawn(Screenshot::primary_window())
        .observe(save_to_disk(mode.path.clone()))
        .observe(|_: On<ScreenshotCaptured>, mut commands: Commands| commands.insert_resource(Saved));
}
