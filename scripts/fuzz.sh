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
targets=("$@")
((${#targets[@]} > 0)) || targets=(gismo_xml gismo_thb vtu coastline obj capi)

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

# Seeds of each target from the bundled data, in build/fuzz/seeds/TARGET.
seeds() {
  local target=$1 dir=build/fuzz/seeds/$1
  rm -rf "$dir"
  mkdir -p "$dir"
  case $target in
    gismo_xml) cp tests/data/boundary/*.xml "$dir" ;;
    coastline) cp tests/data/boundary/*.txt "$dir" ;;
    vtu) cp tests/data/airfoil_0012_q9.vtu "$dir" ;;
    obj)
      # One face alone, and the six faces of the duck separated by NUL bytes (a solid).
      cp tests/data/boundary/duck_faces/xmin.obj "$dir"
      local face
      for face in xmin xmax ymin ymax zmin zmax; do
        cat "tests/data/boundary/duck_faces/$face.obj"
        [[ $face == zmax ]] || printf '\0'
      done >"$dir/duck_faces"
      ;;
  esac
  local kept
  for kept in "tests/data/fuzz/seeds/$target" "tests/data/fuzz/regressions/$target"; do
    [[ -d $kept ]] && cp "$kept"/* "$dir" 2>/dev/null || true
  done
}

echo "+ cargo +nightly fuzz build"
CARGO_BUILD_JOBS=2 cargo +nightly fuzz build

status=0
for target in "${targets[@]}"; do
  seeds "$target"
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
