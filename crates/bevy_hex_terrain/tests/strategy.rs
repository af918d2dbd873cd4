//! Runs the strategy example the way a player would, under Xvfb: its scripted mode selects a
//! unit, moves it along an A* path, ends the turn, toggles outlines and regenerates, checking
//! the game state at each step (movement points spent, turn advanced, units on land on the new
//! surface), then saves a screenshot; the globe example's checks territories, fog across a
//! pentagon and picking. Here we check each succeeded, logged no warning but the software
//! renderer's, and the picture is not blank. Under `xvfb-run` when there is no display.

mod support;

use std::path::Path;

/// Warnings that come from the machine, not from the game: Mesa's software Vulkan and a headless
/// X server.
const MACHINE_WARNINGS: [&str; 3] =
    ["only supports software rendering", "error setting XSETTINGS", "XRandR reported that the display's 0mm in size"];

/// `line` without terminal color codes.
fn plain(line: &str) -> String {
    let mut out = String::with_capacity(line.len());
    let mut chars = line.chars();
    while let Some(c) = chars.next() {
        if c == '\u{1b}' {
            // Skip to the end of the escape sequence (a letter).
            for c in chars.by_ref() {
                if c.is_ascii_alphabetic() {
                    break;
                }
            }
        } else {
            out.push(c);
        }
    }
    out
}

/// Warnings and errors the program logged, other than the machine's.
fn game_warnings(stdout: &str, stderr: &str) -> Vec<String> {
    stderr
        .lines()
        .chain(stdout.lines())
        .map(plain)
        .filter(|l| l.contains(" WARN ") || l.contains(" ERROR "))
        .filter(|l| !MACHINE_WARNINGS.iter().any(|w| l.contains(w)))
        .collect()
}

/// An example built next to the test binaries: target/debug/examples/NAME.
fn example(name: &str) -> std::path::PathBuf {
    let exe = std::env::current_exe().unwrap();
    let example = exe.parent().and_then(Path::parent).unwrap().join("examples").join(name);
    assert!(example.exists(), "{} was not built", example.display());
    example
}

#[test]
fn the_other_examples_show_terrain_and_log_no_warnings() {
    for name in ["minimal", "streaming"] {
        let shot = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}.png"));
        let _ = std::fs::remove_file(&shot);
        let out = support::with_display(&example(name))
            .env("BEVY_ASSET_ROOT", env!("CARGO_MANIFEST_DIR"))
            .env("HEXTERRAIN_SCREENSHOT", &shot)
            .env("HEXTERRAIN_FRAMES", "20")
            .output()
            .unwrap();
        let (stdout, stderr) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
        assert!(out.status.success(), "{name} failed: {stderr}");
        let warnings = game_warnings(&stdout, &stderr);
        assert!(warnings.is_empty(), "{name} logged warnings:\n{}", warnings.join("\n"));
        let img = image::open(&shot).unwrap().to_rgb8();
        let colors: std::collections::HashSet<[u8; 3]> = img.pixels().map(|p| p.0).collect();
        assert!(colors.len() > 100, "the {name} screenshot looks blank ({} colors)", colors.len());
    }
}

#[test]
fn strategy_demo_plays_a_scripted_turn() {
    scripted_turn("strategy", "strategy", &[("HEXTERRAIN_SCRIPT", "1")]);
}

/// The globe example's scripted turn: the territories, red's fog before and after its scout
/// crosses a pentagon, the tile picked under the pointer.
#[test]
fn globe_example_plays_a_scripted_turn() {
    let out = scripted_turn("globe", "globe_script", &[("HEXTERRAIN_SCRIPT", "1")]);
    assert!(out.contains("across the pentagon"), "{out}");
}

/// On the wrapping Civ6 Standard preset with the camera on the seam (84 columns of 1.5 units:
/// the seam is at x = 126), the unit's reach crosses the seam and it walks across, the short way.
#[test]
fn strategy_demo_crosses_the_seam_of_a_wrapping_map() {
    let out = scripted_turn(
        "strategy",
        "strategy_seam",
        &[("HEXTERRAIN_SCRIPT", "seam"), ("HEXTERRAIN_PRESET", "6"), ("HEXTERRAIN_FOCUS", "125.25,40")],
    );
    assert!(out.contains("across the seam"), "{out}");
}

/// Runs an example's scripted turn with `env`, checks it succeeded without warnings and its
/// screenshot (`name`.png) is not blank; returns what it printed.
fn scripted_turn(example_name: &str, name: &str, env: &[(&str, &str)]) -> String {
    let example = example(example_name);
    let shot = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}.png"));
    let _ = std::fs::remove_file(&shot);
    let mut command = support::with_display(&example);
    command.env("BEVY_ASSET_ROOT", env!("CARGO_MANIFEST_DIR")).env("HEXTERRAIN_SCREENSHOT", &shot);
    for (key, value) in env {
        command.env(key, value);
    }
    let out = command.output().unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "the scripted turn failed: {stdout}\n{}",
        stderr.lines().filter(|l| l.contains("SCRIPT") || l.contains("panicked")).collect::<Vec<_>>().join("\n")
    );
    assert!(stdout.contains("SCRIPT OK"), "{stdout}");
    let warnings = game_warnings(&stdout, &stderr);
    assert!(warnings.is_empty(), "the demo logged warnings:\n{}", warnings.join("\n"));
    let img = image::open(&shot).unwrap().to_rgb8();
    let colors: std::collections::HashSet<[u8; 3]> = img.pixels().map(|p| p.0).collect();
    assert!(colors.len() > 500, "the screenshot looks blank ({} colors)", colors.len());
    stdout.into_owned()
}

/// Run from a folder without `assets/` (the binary alone, or a wrong `BEVY_ASSET_ROOT`), the
/// examples that load a map file exit with an error naming the path and `BEVY_ASSET_ROOT`,
/// before opening a window, instead of drawing nothing and exiting 0.
#[test]
fn examples_without_their_assets_exit_with_the_path() {
    let nowhere = Path::new(env!("CARGO_TARGET_TMPDIR")).join("no-assets-here");
    std::fs::create_dir_all(&nowhere).unwrap();
    for name in ["strategy", "far"] {
        let out = std::process::Command::new(example(name))
            .current_dir(&nowhere)
            .env("BEVY_ASSET_ROOT", &nowhere)
            .env_remove("CARGO_MANIFEST_DIR")
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {stderr}");
        assert!(stderr.contains("BEVY_ASSET_ROOT") && stderr.contains("asset folder is missing"), "{name}: {stderr}");
        assert!(stderr.contains(&nowhere.join("assets").display().to_string()), "{name}: {stderr}");
    }
}
