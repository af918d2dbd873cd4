//! Runs the strategy example the way a player would, under Xvfb: its scripted mode selects a
//! unit, moves it along an A* path, ends the turn, toggles outlines and regenerates, checking
//! the game state at each step (movement points spent, turn advanced, units on land on the new
//! surface), then saves a screenshot. Here we check it succeeded, logged no warning but the
//! software renderer's, and the picture is not blank. Under `xvfb-run` when there is no display.

mod support;

use std::path::Path;

/// Warnings that come from the machine, not from the game: Mesa's software Vulkan and a headless
/// X server without input devices or audio.
const MACHINE_WARNINGS: [&str; 0] = [];

#[test]
fn strategy_demo_plays_a_scripted_turn() {
    // Examples are built next to the test binaries: target/debug/examples/strategy.
    let exe = std::env::current_exe().unwrap();
    let example = exe.parent().and_then(Path::parent).unwrap().join("examples").join("strategy");
    assert!(example.exists(), "{} was not built", example.display());
    let shot = Path::new(env!("CARGO_TARGET_TMPDIR")).join("strategy.png");
    let _ = std::fs::remove_file(&shot);
    let out = support::with_display(&example)
        .env("BEVY_ASSET_ROOT", env!("CARGO_MANIFEST_DIR"))
        .env("HEXTERRAIN_SCRIPT", "1")
        .env("HEXTERRAIN_SCREENSHOT", &shot)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "the scripted turn failed: {stdout}\n{}",
        stderr.lines().filter(|l| l.contains("SCRIPT") || l.contains("panicked")).collect::<Vec<_>>().join("\n")
    );
    assert!(stdout.contains("SCRIPT OK"), "{stdout}");
    let warnings: Vec<&str> = stderr
        .lines()
        .chain(stdout.lines())
        .filter(|l| l.contains(" WARN ") || l.contains("ERROR"))
        .filter(|l| !MACHINE_WARNINGS.iter().any(|w| l.contains(w)))
        .collect();
    assert!(warnings.is_empty(), "the demo logged warnings:\n{}", warnings.join("\n"));
    let img = image::open(&shot).unwrap().to_rgb8();
    let colors: std::collections::HashSet<[u8; 3]> = img.pixels().map(|p| p.0).collect();
    assert!(colors.len() > 500, "the screenshot looks blank ({} colors)", colors.len());
}
