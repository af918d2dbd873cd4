#!/usr/bin/env bash
# The project's test command: doc tests, then every crate's unit, property, integration, headless
# Bevy App and rendering tests. Always the whole workspace in the dev profile, the build
# scripts/run.sh uses too, so Bevy is built once with one feature set for both commands.
# It first runs scripts/setup.sh (a no-op when everything is installed). The rendering tests open
# a window: without a display, the script reruns itself under Xvfb (Mesa's software Vulkan
# renders there).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -z "${HEXTERRAIN_SETUP_DONE:-}" ]; then
  scripts/setup.sh
  export HEXTERRAIN_SETUP_DONE=1
fi
if [ -z "${DISPLAY:-}" ] && [ -z "${WAYLAND_DISPLAY:-}" ] && command -v xvfb-run >/dev/null 2>&1; then
  exec xvfb-run -a -s "-screen 0 1280x720x24" "$0" "$@"
fi
source scripts/env.sh
cargo test --workspace --features "$HEXTERRAIN_FEATURES" --doc
cargo nextest run --workspace --features "$HEXTERRAIN_FEATURES" --no-fail-fast
