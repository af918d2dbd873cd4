#!/usr/bin/env bash
# The noise bench twice: built with the default flags (the kernels picked at run time), then
# built for this CPU (`-C target-cpu=native`, in a target dir of its own so the default build
# stays), one table each, so ours stands beside every library both ways.
#   scripts/noise-bench.sh [--rounds N]
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/env.sh
echo "## Default build flags"
echo
cargo bench -q -p hex_terrain_bench --bench noise -- "$@"
echo
echo "## Built with -C target-cpu=native"
echo
CARGO_TARGET_DIR="${CARGO_TARGET_DIR}-native" RUSTFLAGS="-C target-cpu=native" \
  cargo bench -q -p hex_terrain_bench --bench noise -- "$@"
