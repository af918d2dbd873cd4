# Sourced by the project's scripts: one target directory outside the clone, so every clone on
# this machine (and CI) reuses the same build of Bevy.
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/hexterrain-target}"
