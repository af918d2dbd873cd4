#!/usr/bin/env bash
# The project's test command: doc tests, then every crate's unit, property, integration and
# headless Bevy App tests. Always the whole workspace, so Bevy is built with one feature set.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/env.sh
cargo test --workspace --doc
cargo nextest run --workspace --no-fail-fast
