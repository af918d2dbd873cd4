#!/usr/bin/env bash
# Frame cost of the strategy demo under software rendering at 1280x720: the look before water,
# light and props (HEXTERRAIN_LOOK=off: no water surface, no props, no shadows, no distance fog)
# beside everything on, in one run of this script, and their ratio. Needs the debug build of
# the examples (scripts/run.sh or the test build makes it).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/env.sh
bin="$CARGO_TARGET_DIR/debug/examples/strategy"
frames="${HEXTERRAIN_FRAMES:-40}"
run() {
    env "$@" BEVY_ASSET_ROOT="$PWD" HEXTERRAIN_SCREENSHOT="/tmp/hexterrain_frame_cost.png" HEXTERRAIN_FRAMES="$frames" \
        xvfb-run -a -s "-screen 0 1280x720x24" "$bin" 2>&1 | sed -n 's/.*mean frame time: \([0-9.]*\) ms.*/\1/p'
}
off=$(run HEXTERRAIN_LOOK=off)
on=$(run HEXTERRAIN_LOOK=on)
echo "look off: ${off} ms a frame"
echo "look on:  ${on} ms a frame"
awk -v a="$on" -v b="$off" 'BEGIN { printf "ratio on/off: %.2f\n", a / b }'
