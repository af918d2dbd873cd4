#!/usr/bin/env bash
# Remakes the pictures in docs/ that the `hexterrain` command draws from a map config: the map
# types' presets and their contact sheets (12 seeds from 1000, seeds the presets do not use),
# the World preset's biomes with and without winds, and its game setup. With `--screens` also the
# demo's opening view (docs/strategy.png, the README's first picture) through the examples'
# screenshot mode, under Xvfb without a display (the Bevy build scripts/run.sh makes). The other
# Bevy screenshots in docs/ are not remade here yet. Without `--screens`: the release build of
# the CLI only (no Bevy), a minute from cold.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/env.sh
cargo build --release -p hex_terrain_cli
cli="$CARGO_TARGET_DIR/release/hexterrain"
for type in pangaea continents small_continents archipelago fractal inland_sea; do
  "$cli" render "assets/maps/types/$type.map.ron" -o "docs/map_type_$type.png" --width 400
  "$cli" gallery "assets/maps/types/$type.map.ron" --seeds 12 --first 1000 --width 320 -o "docs/gallery_$type.png"
done
"$cli" render assets/maps/world.map.ron -o docs/world_biomes.png --width 800
# The World preset with the moisture fBm's climate instead of winds.
no_winds="$(mktemp --suffix .map.ron)"
trap 'rm -f "$no_winds"' EXIT
sed -e 's/, winds: Some((pattern: Bands(\[45, 225, 45\])))//' assets/maps/world.map.ron > "$no_winds"
grep -q "winds: Some" "$no_winds" && { echo "pictures.sh: the World preset's winds line changed; update the sed above" >&2; exit 1; }
"$cli" render "$no_winds" -o docs/world_biomes_no_winds.png --width 800
"$cli" setup assets/maps/world.map.ron -o docs/setup.png --width 900
if [ "${1:-}" = "--screens" ]; then
  run=(cargo run -q -p bevy_hex_terrain --features "$HEXTERRAIN_FEATURES" --example strategy)
  if [ -z "${DISPLAY:-}" ] && [ -z "${WAYLAND_DISPLAY:-}" ]; then
    run=(xvfb-run -a -s "-screen 0 1280x720x24" "${run[@]}")
  fi
  # Every prop at once (HEXTERRAIN_SETTLE), so the picture does not catch them spawning.
  HEXTERRAIN_SETTLE=1 HEXTERRAIN_SCREENSHOT="$PWD/docs/strategy.png" "${run[@]}" > /dev/null
fi
