# Sourced by the project's scripts: one target directory outside the clone, so every clone on
# this machine (and CI) reuses the same build of Bevy.
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/hexterrain-target}"
# The plugin's features the examples and the windowed tests need besides the default ones
# (`minimap` brings `render` and `picking`). Every script builds with exactly these, so the demo,
# the tests, clippy and the docs all use one feature set of Bevy.
export HEXTERRAIN_FEATURES="bevy_hex_terrain/minimap,bevy_hex_terrain/big_space"
