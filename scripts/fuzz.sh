#!/usr/bin/env bash
# Runs the fuzz targets of fuzz/ (cargo-fuzz, libFuzzer, AddressSanitizer) for SECONDS each
# (default 60), one after the other: bash scripts/fuzz.sh [SECONDS] [TARGET ...]
#
# Each target starts from the seeds assembled from the bundled data (tests/data) and the kept
# inputs of tests/data/fuzz/, and grows its corpus in build/fuzz/corpus/TARGET (kept between
# runs). An input that crashes, hangs (over the per-input timeout) or exhausts memory is saved in
# build/fuzz/artifacts/TARGET/ and makes the script fail; keep it, once fixed, in
# tests/data/fuzz/regressions/TARGET/ so that `cargo test --test fuzz_regressions` replays it.
#
# Needs the nightly toolchain (libFuzzer's instrumentation) and cargo-fuzz, which it installs
# from crates.io when missing; without nightly it says so and exits 0.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
export PATH="$PATH:${CARGO_HOME:-$HOME/.cargo}/bin"

seconds=${1:-60}
shift || true
# shellcheck source=scripts/fuzz_seeds.sh
source scripts/fuzz_seeds.sh
targets=("$@")
((${#targets[@]} > 0)) || targets=("${fuzz_targets[@]}")

if ! cargo +nightly --version >/dev/null 2>&1; then
  echo "fuzz.sh: no nightly Rust toolchain (rustup toolchain install nightly): fuzzing skipped"
  exit 0
fi
if ! cargo fuzz --version >/dev/null 2>&1; then
  echo "fuzz.sh: installing cargo-fuzz"
  cargo install cargo-fuzz --locked || {
    echo "fuzz.sh: cargo-fuzz could not be installed: fuzzing skipped"
    exit 0
  }
fi

echo "+ cargo +nightly fuzz build"
CARGO_BUILD_JOBS=2 cargo +nightly fuzz build

status=0
for target in "${targets[@]}"; do
  fuzz_seeds "$target" "build/fuzz/seeds/$target"
  corpus=build/fuzz/corpus/$target
  artifacts=build/fuzz/artifacts/$target
  mkdir -p "$corpus" "$artifacts"
  echo "+ cargo +nightly fuzz run $target ($seconds s)"
  start=$SECONDS
  if ! CARGO_BUILD_JOBS=2 cargo +nightly fuzz run "$target" "$corpus" "build/fuzz/seeds/$target" -- \
    -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2560 -print_final_stats=1 \
    -artifact_prefix="$artifacts/" 2>"build/fuzz/$target.log"; then
    status=1
    tail -n 60 "build/fuzz/$target.log" >&2
    echo "fuzz.sh: $target FAILED; the input is in $artifacts/ (full log: build/fuzz/$target.log)" >&2
  else
    echo "fuzz.sh: $target: $(grep -c . <(ls "$corpus")) corpus inputs," \
      "$(grep -o 'stat::number_of_executed_units: *[0-9]*' "build/fuzz/$target.log" | grep -o '[0-9]*$') runs" \
      "in $((SECONDS - start)) s, no failure"
  fi
done
exit "$status"
