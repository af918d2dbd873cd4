#!/usr/bin/env bash
# Coverage-guided fuzzing with cargo-fuzz (libFuzzer), one target at a time:
#   scripts/fuzz.sh <map_text|heightmap|map_asset|tile_save|fog_save|edits|ruleset> [seconds=1800] [runs=1000000]
# Stops after `runs` executions or `seconds`, whichever comes first; an input that takes more
# than 10 s counts as a hang. Then minimises the corpus into fuzz/corpus/<target> (commit it:
# tests replay it). A crash input lands in fuzz/artifacts/<target>: fix the bug and move the
# input into fuzz/regressions/<target>.
# cargo-fuzz needs a nightly compiler for its sanitizer flags: the machine's nightly toolchain
# when rustup has one, otherwise the stable one with RUSTC_BOOTSTRAP=1.
set -euo pipefail
cd "$(dirname "$0")/.."
target="${1:?usage: scripts/fuzz.sh <map_text|heightmap|map_asset|tile_save|fog_save|edits|ruleset> [seconds] [runs]}"
seconds="${2:-1800}"
runs="${3:-1000000}"
if ! cargo fuzz --version >/dev/null 2>&1; then
  cargo install --locked cargo-fuzz
fi
toolchain=()
if rustup toolchain list 2>/dev/null | grep -q '^nightly'; then
  toolchain=(+nightly)
else
  export RUSTC_BOOTSTRAP=1
fi
# Its own target dir: a sanitizer build shares nothing with the Bevy build.
export CARGO_TARGET_DIR="${HEXTERRAIN_FUZZ_TARGET:-$HOME/.cache/hexterrain-fuzz-target}"
corpus="fuzz/corpus/$target"
work="fuzz/work/$target"
mkdir -p "$corpus" "$work"
cargo "${toolchain[@]}" fuzz build --release "$target"
cargo "${toolchain[@]}" fuzz run --release "$target" "$work" "$corpus" "fuzz/seeds/$target" -- \
  -max_total_time="$seconds" -runs="$runs" -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 2>&1 |
  tee "fuzz/work/$target.log" | grep -E '^(#[0-9]+ +(DONE|INITED)|Done|stat::|==|SUMMARY|artifact)' || true
# Minimise everything seen into the kept corpus.
rm -rf "$corpus.new" && mkdir -p "$corpus.new"
cargo "${toolchain[@]}" fuzz run --release "$target" "$corpus.new" "$corpus" "$work" "fuzz/seeds/$target" -- \
  -merge=1 -timeout=10 -rss_limit_mb=4096 2>&1 | tail -1
rm -rf "$corpus" && mv "$corpus.new" "$corpus"
echo "corpus: $(ls "$corpus" | wc -l) inputs, $(du -sh "$corpus" | cut -f1)"
