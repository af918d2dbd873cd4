#!/usr/bin/env bash
# Remakes the pictures in docs/. Without `--screens`, those the `hexterrain` command draws from a
# map config (the release build of the CLI only, no Bevy, a minute from cold): the map types'
# presets and their contact sheets (12 seeds from 1000, seeds the presets do not use), the World
# preset's biomes with and without winds, its game setup and its terrain rulesets, the edge
# rivers close up and on the Jacksboro relief, the thesis' island with outlines, the strait
# scenario. With `--screens` also the Bevy pictures
# (the build scripts/run.sh makes; under Xvfb without a display, a minute or two each): the
# demo's views through the examples' screenshot mode (every prop spawned first,
# HEXTERRAIN_SETTLE), the other examples', and the rendering tests' pictures, copied from where
# the tests write them. Not remade, on purpose: the look chapter's "before" pair
# (strategy_before.png, minimal_before.png, and strategy_look.png, the demo's opening view when
# that work was done), which show the builds they are named after.
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
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
# The World preset with the moisture fBm's climate instead of winds.
sed -e 's/, winds: Some((pattern: Bands(\[45, 225, 45\]), rain_shadow: 0.6, drying: 0.005))//' assets/maps/world.map.ron > "$scratch/no_winds.map.ron"
grep -q "winds: Some" "$scratch/no_winds.map.ron" && { echo "pictures.sh: the World preset's winds line changed; update the sed above" >&2; exit 1; }
"$cli" render "$scratch/no_winds.map.ron" -o docs/world_biomes_no_winds.png --width 800
"$cli" setup assets/maps/world.map.ron -o docs/setup.png --width 900
# The World preset under the shipped terrain rulesets.
for ruleset in civ5 fantasy; do
  "$cli" render "assets/maps/world_$ruleset.map.ron" -o "docs/world_$ruleset.png" --width 800
done
# Edge rivers close up: a 28x18 island under an east wind, rivers from its hills to the sea.
cat > "$scratch/close.map.ron" <<'RON'
(
    name: "Edge rivers, close up",
    seed: 15,
    size: Bounded(x: 28, z: 18),
    noise: (octaves: 6, persistence: 0.45, lacunarity: 2.0, scale: 30.0),
    terrain: (max_elevation: 5.0, sea_threshold: 0.3, mountain_threshold: 0.66, interpolation_tolerance: 0.03, inner_rings: 2),
    shape: Island(a: 2.0, b: 5.0),
    chunk_size: (16, 16),
    appearance: (blend: 0.1),
    climate: (enabled: true, winds: Some((pattern: One(90)))),
    rivers: (enabled: true, min_lake_depth: 0.02, model: Edges, sources: Relief(tiles_per_edge: 6.0)),
    relief: (peaks: 0.8, ridges: 0.45, hills: 0.45),
)
RON
"$cli" render "$scratch/close.map.ron" -o docs/edge_rivers.png --width 1000
"$cli" render assets/maps/jacksboro.map.ron -o docs/jacksboro_edge_rivers.png --width 1000
"$cli" render assets/maps/thesis/map01.map.ron -o docs/island.png --outlines
# The scenario made with the world builder (the World map cut by a strait, with a pass).
"$cli" render assets/maps/strait.map.ron -o docs/strait.png --outlines --width 640
# The Standard globe: its equirectangular map, and seen from above the pentagon U0 (longitude 0,
# latitude atan(1/2)) with the tiles' outlines.
"$cli" render assets/maps/globe/standard.map.ron -o docs/globe_equirectangular.png --width 1000
"$cli" render assets/maps/globe/standard.map.ron -o docs/globe_orthographic.png --width 640 --outlines --from 0,26.565
# The Continents globe with its climate, in its biomes' colors, and seen from above its first
# continent.
"$cli" render assets/maps/globe/continents.map.ron -o docs/globe_continents.png --width 1000
"$cli" render assets/maps/globe/continents.map.ron -o docs/globe_continents_view.png --width 640 --from -150,15
# Twelve Continents globes from seed 1000, to judge the type by eye.
"$cli" gallery assets/maps/globe/continents.map.ron --seeds 12 --first 1000 --columns 3 --width 320 -o docs/gallery_globe_continents.png
if [ "${1:-}" = "--screens" ]; then
  xvfb=()
  if [ -z "${DISPLAY:-}" ] && [ -z "${WAYLAND_DISPLAY:-}" ]; then
    xvfb=(xvfb-run -a -s "-screen 0 1280x720x24")
  fi
  # shot PICTURE EXAMPLE [VAR=VALUE...]: the example's screenshot, every prop spawned first.
  shot() {
    local out="$PWD/docs/$1" name="$2"
    shift 2
    env HEXTERRAIN_SETTLE=1 HEXTERRAIN_SCREENSHOT="$out" "$@" "${xvfb[@]}" \
      cargo run -q -p bevy_hex_terrain --features "$HEXTERRAIN_FEATURES" --example "$name" > /dev/null
  }
  # The demo's opening view (the README's first picture), with the fairness report open, with
  # the fog off (the minimap whole), the world builder painting on the scenario (7) beside the
  # start, the wrapping Civ6 Standard map across its seam (x = 126), the whole Civ6 Huge map
  # zoomed out.
  shot strategy.png strategy
  shot strategy_setup.png strategy HEXTERRAIN_REPORT=1
  shot minimap.png strategy HEXTERRAIN_FOG=off
  shot editor.png strategy HEXTERRAIN_PRESET=7 HEXTERRAIN_EDITOR=1 HEXTERRAIN_EDIT=33,27 HEXTERRAIN_FOG=off
  shot wrap_seam.png strategy HEXTERRAIN_PRESET=6 HEXTERRAIN_FOCUS=126,40 HEXTERRAIN_FOG=off
  shot lod_huge.png strategy HEXTERRAIN_MAP=maps/civ6/huge.map.ron HEXTERRAIN_FOCUS=80,57 HEXTERRAIN_ZOOM=120 \
    HEXTERRAIN_FOG=off
  # The World preset in the demo under Civilization V's terrain and as The Shattered Realms,
  # each tile drawn with its terrain's texture layer.
  shot strategy_civ5.png strategy HEXTERRAIN_MAP=maps/world_civ5.map.ron HEXTERRAIN_FOG=off HEXTERRAIN_TEXTURES=on
  shot strategy_fantasy.png strategy HEXTERRAIN_MAP=maps/world_fantasy.map.ron HEXTERRAIN_FOG=off \
    HEXTERRAIN_TEXTURES=on
  shot minimal.png minimal
  shot streaming.png streaming HEXTERRAIN_STILL=1
  shot far_example.png far
  # The globe example at three zooms: the planet (without the fog) over red's city (its start of
  # the map's game setup), red's region in its fog, the ground tilted to the horizon beside red's
  # city; then the sea as water along the coast east of it with the terrain textures on.
  shot globe_planet.png globe HEXTERRAIN_GLOBE_ALTITUDE=60 HEXTERRAIN_FOG=off
  shot globe_region.png globe HEXTERRAIN_GLOBE_ALTITUDE=14
  shot globe_ground.png globe HEXTERRAIN_GLOBE_AT=66,-43 HEXTERRAIN_GLOBE_ALTITUDE=3
  shot globe_water.png globe HEXTERRAIN_GLOBE_AT=86,-36 HEXTERRAIN_GLOBE_ALTITUDE=8 HEXTERRAIN_FOG=off \
    HEXTERRAIN_TEXTURES=on
  # Straight down on a pentagon on land, picked (under Xvfb the pointer rests at the middle of
  # the screen, and the example names the tile under it), red's scout walking across it.
  shot globe_pentagon.png globe HEXTERRAIN_GLOBE_AT=36,-26.565 HEXTERRAIN_GLOBE_ALTITUDE=25
  # The rendering tests' pictures: each test writes its frame where the tests keep files.
  "${xvfb[@]}" cargo test -q -p bevy_hex_terrain --features "$HEXTERRAIN_FEATURES" \
    --test render --test render_tile_state --test render_far > /dev/null
  tmp="$CARGO_TARGET_DIR/tmp"
  for pair in fog:tile_state_fog borders:tile_state_borders lens_on:tile_state_lens \
    outlines_off:material_outlines_off outlines_on:material_outlines_on \
    textures_highlights:material_textures_highlights far:far; do
    cp "$tmp/${pair%%:*}.png" "docs/${pair#*:}.png"
  done
fi
