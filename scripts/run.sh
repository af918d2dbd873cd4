#!/usr/bin/env bash
# Sets up a fresh machine and runs the main job: the turn-based strategy demo.
# (The first release build compiles Bevy: tens of minutes on two cores.)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
source scripts/env.sh
cargo run --release --example strategy
