#!/usr/bin/env bash
# Sets up a fresh machine and runs the main job: the turn-based strategy demo (or, given its
# name, another example: `scripts/run.sh globe`).
# The dev profile (dependencies and the generator at opt-level 3) is the build scripts/test.sh
# uses too, so the two commands share one build of Bevy. The first build compiles Bevy: about
# 22 minutes on two cores; later runs start in seconds.
# On a machine without a display (no DISPLAY, no WAYLAND_DISPLAY) the demo runs under Xvfb with
# Mesa's software renderer (both installed by scripts/setup.sh), writes a screenshot of its
# opening view and exits; the script prints where the picture is.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
source scripts/env.sh
# `scripts/run.sh globe` (or minimal, streaming, far) runs another example the same way.
example="${1:-strategy}"
case "$example" in
  strategy | globe | minimal | streaming | far) ;;
  *)
    echo "scripts/run.sh [strategy|globe|minimal|streaming|far]: no example \"$example\"" >&2
    exit 2
    ;;
esac
run=(cargo run -p bevy_hex_terrain --features "$HEXTERRAIN_FEATURES" --example "$example")
if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
  exec "${run[@]}"
fi
shot="${HEXTERRAIN_SCREENSHOT:-${TMPDIR:-/tmp}/hexterrain-demo.png}"
mkdir -p "$(dirname "$shot")"
rm -f "$shot"
echo "No display here: running the demo under Xvfb (software rendering, a few seconds a frame)."
HEXTERRAIN_SCREENSHOT="$shot" xvfb-run -a -s "-screen 0 1280x720x24" "${run[@]}"
if [ ! -s "$shot" ]; then
  echo "The demo ran but wrote no screenshot at $shot." >&2
  exit 1
fi
echo "The demo's opening view: $shot"
echo "On a desktop (with DISPLAY or WAYLAND_DISPLAY set), scripts/run.sh opens the demo's window instead."
