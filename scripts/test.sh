#!/usr/bin/env bash
# The project's test command: doc tests, then every crate's unit, property, integration, headless
# Bevy App and rendering tests. Always the whole workspace, so Bevy is built with one feature set.
# The rendering tests open a window: without a display, the script reruns itself under Xvfb
# (Mesa's software Vulkan renders there; scripts/setup.sh installs both).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -z "${DISPLAY:-}" ] && [ -z "${WAYLAND_DISPLAY:-}" ] && command -v xvfb-run >/dev/null 2>&1; then
  exec xvfb-run -a -s "-screen 0 1280x720x24" "$0" "$@"
fi
source scripts/env.sh
cargo test --workspace --doc
cargo nextest run --workspace --no-fail-fast
