#!/usr/bin/env bash
# Sets up a fresh machine and runs the main job: generate the thesis' reference map, print its
# summary and render it to map00.png.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
source scripts/env.sh
map="${1:-assets/maps/thesis/map00.ron}"
cargo run --release -p hex_terrain_cli -- stats "$map"
cargo run --release -p hex_terrain_cli -- render "$map" -o "$(basename "${map%.ron}").png" --outlines
echo "wrote $(basename "${map%.ron}").png"
