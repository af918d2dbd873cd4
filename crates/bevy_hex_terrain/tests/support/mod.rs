//! Helpers for tests that open windows: each scenario runs in a process of its own (winit builds
//! one event loop per process, and libtest runs tests as threads of one process), under
//! `xvfb-run` when there is no display, so plain `cargo test` passes as well as nextest.

/// `#[test]`s each running one ignored scenario in a process of its own:
/// `in_own_process! { test_name => scenario_name, ... }`.
#[allow(unused_macros, reason = "not every test binary that includes this module uses it")]
macro_rules! in_own_process {
    ($($test:ident => $scenario:ident),* $(,)?) => {
        $(
            #[test]
            fn $test() {
                support::in_own_process(stringify!($scenario));
            }
        )*
    };
}

#[allow(dead_code, reason = "not every test binary that includes this module renders")]
pub mod scene;

use std::path::Path;
use std::process::{Command, Output};

/// A command running `program`, under `xvfb-run -a` when there is no display and Xvfb is
/// installed (`scripts/setup.sh` installs it).
pub fn with_display(program: &Path) -> Command {
    let no_display = std::env::var_os("DISPLAY").is_none() && std::env::var_os("WAYLAND_DISPLAY").is_none();
    let xvfb = Command::new("xvfb-run").arg("--help").output().is_ok();
    if no_display && xvfb {
        let mut cmd = Command::new("xvfb-run");
        cmd.args(["-a", "-s", "-screen 0 1280x720x24"]).arg(program);
        cmd
    } else {
        Command::new(program)
    }
}

/// Runs the ignored test `name` of this test binary alone in a new process and fails with its
/// output if it fails.
#[allow(dead_code, reason = "not every test binary that includes this module uses it")]
pub fn in_own_process(name: &str) -> Output {
    let exe = std::env::current_exe().expect("the test binary's path");
    let out = with_display(&exe)
        .args([name, "--exact", "--ignored", "--nocapture", "--test-threads=1"])
        .output()
        .expect("the test binary runs");
    assert!(
        out.status.success(),
        "{name} failed:\n{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("1 passed"), "{name} did not run");
    out
}
