//! Screenshot mode for examples and tests: with `HEXTERRAIN_SCREENSHOT=out.png` in the
//! environment, the app saves a screenshot of the primary window after `HEXTERRAIN_FRAMES`
//! frames (default 60), prints the mean frame time of the frames after the first ten (which
//! compile pipelines) and exits with status 0. Without it, the plugin does nothing.

use std::path::PathBuf;

use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};

/// Saves one screenshot and exits when `HEXTERRAIN_SCREENSHOT` is set.
pub struct ScreenshotModePlugin;

#[derive(Resource)]
struct ScreenshotMode {
    path: PathBuf,
    frames: u32,
    seen: u32,
    requested: bool,
    /// Start of the eleventh frame, once reached.
    timing_from: Option<std::time::Instant>,
}

/// The screenshot was written.
#[derive(Resource)]
struct Saved;

impl Plugin for ScreenshotModePlugin {
    fn build(&self, app: &mut App) {
        let Some(path) = std::env::var_os("HEXTERRAIN_SCREENSHOT") else { return };
        let frames = std::env::var("HEXTERRAIN_FRAMES").ok().and_then(|f| f.parse().ok()).unwrap_or(60);
        app.insert_resource(ScreenshotMode { path: path.into(), frames, seen: 0, requested: false, timing_from: None })
            .add_systems(Last, screenshot_after_frames);
    }
}

fn screenshot_after_frames(
    mut commands: Commands,
    mut mode: ResMut<ScreenshotMode>,
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
    if mode.seen >= mode.frames && !mode.requested {
        mode.requested = true;
        if let Some(from) = mode.timing_from {
            let frames = mode.seen - 10;
            if frames > 0 {
                let ms = from.elapsed().as_secs_f64() * 1e3 / f64::from(frames);
                info!("mean frame time: {ms:.1} ms over {frames} frames");
            }
        }
        let path = mode.path.clone();
        commands.spawn(Screenshot::primary_window()).observe(
            move |captured: On<ScreenshotCaptured>, mut commands: Commands| {
                match captured.image.clone().try_into_dynamic() {
                    Ok(img) => match img.to_rgb8().save(&path) {
                        Ok(()) => info!("screenshot saved to {}", path.display()),
                        Err(e) => error!("cannot save screenshot {}: {e}", path.display()),
                    },
                    Err(e) => error!("cannot convert screenshot: {e}"),
                }
                commands.insert_resource(Saved);
            },
        );
    }
}
