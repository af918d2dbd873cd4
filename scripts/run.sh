#!/usr/bin/env bash
# Sets up a fresh machine and runs the main job: the turn-based strategy demo.
# The dev profile (dependencies and the generator at opt-level 3) is the build scripts/test.sh
# uses too, so the two commands share one build of Bevy. The first build compiles Bevy: about
# 22 minutes on two cores; later runs start in seconds.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
source scripts/env.sh
cargo run -p bevy_hex_terrain --features "$HEXTERRAIN_FEATURES" --example strategy
