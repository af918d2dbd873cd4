#!/usr/bin/env bash
# Sets up a fresh machine and runs the main job: generate the thesis' reference map and print
# its summary.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
source scripts/env.sh
cargo run --release -p hex_terrain --example summary -- "${1:-assets/maps/thesis/map00.ron}"
