#!/usr/bin/env bash
# The C API test programs (tests/c/test_capi.c, test_domain.c, test_spline.c, test_handles.c,
# test_morph.c, test_sensitivity.c) under AddressSanitizer and under valgrind memcheck, and a short
# run of every fuzz target: bash scripts/asan.sh [asan|fuzz|valgrind ...] (default: all three).
#
# - asan: the library built by nightly Rust with -Zsanitizer=address (the `asan` profile at
#   opt-level 1, debug assertions and overflow checks on) and the programs with -fsanitize=address,
#   leaks reported (LeakSanitizer); any error fails the run.
# - fuzz: every target of fuzz/ (libFuzzer, AddressSanitizer) for IGAPARAM_FUZZ_RUNS inputs
#   (default 1000) and at most IGAPARAM_FUZZ_SECONDS (default 60), from the seeds of the bundled
#   data and the kept inputs, with a fresh corpus and a fixed random seed (the same inputs in the
#   same order at every run); a crash, a timeout or running out of memory fails the run (the
#   input is kept in build/asan/fuzz/TARGET/). scripts/fuzz.sh runs them for longer, optimized.
#   The asan and fuzz modes share one nightly build: the fuzz workspace's targets and the
#   library's C API, with the same flags (ASan and libFuzzer's coverage instrumentation), so
#   every dependency is compiled once.
# - valgrind: the programs against the ordinary release library under memcheck, zero errors and
#   zero definite leaks required.
#
# scripts/test.sh runs all three: asan on test_capi, test_handles, test_morph and
# test_sensitivity, fuzz with the defaults (about 2.5 minutes to build, 1 + 3.5 to run), valgrind on
# test_capi and test_handles (half a minute); the domain and spline programs take several minutes
# more (30 times slower under valgrind), so the full run is this script's. A tool that is
# missing is reported and skipped, or fails the run under IGAPARAM_NO_SKIP (as scripts/test.sh
# sets it).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
export PATH="$PATH:${CARGO_HOME:-$HOME/.cargo}/bin"
root=$PWD

modes=("$@")
((${#modes[@]} > 0)) || modes=(asan fuzz valgrind)
# IGAPARAM_SANITIZE_PROGRAMS: the programs to run (names separated by spaces), default all four.
read -r -a programs <<<"${IGAPARAM_SANITIZE_PROGRAMS:-test_capi test_domain test_spline test_handles test_morph test_sensitivity}"
work=build/asan
# The release library's target directory (CARGO_TARGET_DIR when set, as scripts/test.sh does);
# the ASan build goes to its asan/ subdirectory.
cargo_dir=${CARGO_TARGET_DIR:-$root/target}
mkdir -p "$work"
cc=${CC:-cc}

# Builds the programs in DIR against the library LIB (copied in under its SONAME), with FLAGS.
build() {
  local dir=$1 lib=$2
  shift 2
  mkdir -p "$dir"
  cp "$lib" "$dir/libigaparam.so.0"
  local p
  for p in "${programs[@]}"; do
    "$cc" -std=c11 -g -O1 "$@" -Iinclude -Iexamples-c "tests/c/$p.c" -o "$dir/$p" \
      "$dir/libigaparam.so.0" "-Wl,-rpath,$PWD/$dir" -lpthread -lm
  done
}

# Runs every program in DIR with PREFIX (a command line, possibly empty); fails on any failure.
run_all() {
  local dir=$1
  shift
  local p status=0
  for p in "${programs[@]}"; do
    local out="$dir/$p.out"
    mkdir -p "$dir/$p-files"
    echo "+ $* $p"
    if ! (cd "$dir" && "$@" "./$p" "$root/tests/data/boundary" "$PWD/$p-files") \
      >"$out" 2>&1; then
      status=1
      tail -n 40 "$out" >&2
      echo "asan.sh: $p FAILED (full output: $out)" >&2
    else
      grep -E " passed, | 0 failed|ERROR SUMMARY|definitely lost" "$out" | tail -n 3
    fi
  done
  return "$status"
}

# The nightly build shared by the asan and fuzz modes, made once: the fuzz targets and the
# library (cdylib) in the fuzz workspace, with AddressSanitizer and the coverage instrumentation
# that cargo-fuzz gives libFuzzer. Returns 0 when built, 1 when the build failed or nightly is
# missing under IGAPARAM_NO_SKIP, 2 when nightly is missing otherwise (the run is skipped).
nightly_dir="$cargo_dir/asan/x86_64-unknown-linux-gnu/asan"
nightly_built=
nightly_build() {
  [[ -z $nightly_built ]] || return "$nightly_built"
  nightly_built=1
  if ! cargo +nightly --version >/dev/null 2>&1; then
    echo "asan.sh: no nightly Rust toolchain: AddressSanitizer and fuzz runs skipped"
    # IGAPARAM_NO_SKIP (scripts/test.sh): a missing tool fails.
    [[ -n ${IGAPARAM_NO_SKIP:-} ]] || nightly_built=2
    return "$nightly_built"
  fi
  local coverage="-Cpasses=sancov-module -Cllvm-args=-sanitizer-coverage-level=4"
  coverage+=" -Cllvm-args=-sanitizer-coverage-inline-8bit-counters"
  coverage+=" -Cllvm-args=-sanitizer-coverage-pc-table"
  coverage+=" -Cllvm-args=-sanitizer-coverage-trace-compares --cfg fuzzing"
  echo "+ cargo +nightly build --profile asan (-Zsanitizer=address, libFuzzer coverage)"
  RUSTFLAGS="-Zsanitizer=address $coverage" CARGO_TARGET_DIR="$cargo_dir/asan" \
    CARGO_BUILD_JOBS=2 cargo +nightly build --manifest-path fuzz/Cargo.toml --profile asan \
    --target x86_64-unknown-linux-gnu -p igaparam-fuzz -p igaparam || return 1
  nightly_built=0
}

# Whether the nightly build is there (made on first use); a failed build, or a missing nightly
# under IGAPARAM_NO_SKIP, fails the run.
nightly_ready() {
  local built=0
  nightly_build || built=$?
  ((built == 0)) && return 0
  ((built == 2)) || status=1
  return 1
}

# Runs every fuzz target from its seeds for IGAPARAM_FUZZ_RUNS inputs, at most
# IGAPARAM_FUZZ_SECONDS; fails on any failure.
fuzz_all() {
  # shellcheck source=scripts/fuzz_seeds.sh
  source scripts/fuzz_seeds.sh
  local seconds=${IGAPARAM_FUZZ_SECONDS:-60} runs=${IGAPARAM_FUZZ_RUNS:-1000} target status=0
  for target in "${fuzz_targets[@]}"; do
    local dir=$work/fuzz/$target
    fuzz_seeds "$target" "$dir/seeds"
    rm -rf "$dir/corpus" "$dir/artifacts"
    mkdir -p "$dir/corpus" "$dir/artifacts"
    echo "+ fuzz $target ($runs inputs, at most $seconds s)"
    # A fixed seed and number of runs: the same inputs at every run (scripts/fuzz.sh draws them);
    # the time limit only caps a slow machine.
    if ! "$nightly_dir/$target" "$dir/corpus" "$dir/seeds" -seed=1 -runs="$runs" \
      -max_total_time="$seconds" \
      -timeout=20 -rss_limit_mb=2560 -print_final_stats=1 -artifact_prefix="$dir/artifacts/" \
      >"$dir/log" 2>&1; then
      status=1
      tail -n 60 "$dir/log" >&2
      echo "asan.sh: fuzz target $target FAILED; the input is in $dir/artifacts/" >&2
    else
      echo "asan.sh: fuzz $target:" \
        "$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$dir/log" | grep -o '[0-9]*$') runs," \
        "no failure"
    fi
  done
  return "$status"
}

status=0
for mode in "${modes[@]}"; do
  case $mode in
    asan)
      nightly_ready || continue
      build "$work/asan" "$nightly_dir/libigaparam.so" -fsanitize=address -fno-omit-frame-pointer
      ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 run_all "$work/asan" env || status=1
      ;;
    fuzz)
      nightly_ready || continue
      fuzz_all || status=1
      ;;
    valgrind)
      if ! command -v valgrind >/dev/null; then
        echo "asan.sh: valgrind not found: memcheck run skipped"
        # IGAPARAM_NO_SKIP (scripts/test.sh): a missing tool the README installs fails.
        [[ -z ${IGAPARAM_NO_SKIP:-} ]] || status=1
        continue
      fi
      # IGAPARAM_SANITIZE_LIBRARY: a release library already built (scripts/test.sh passes the
      # one its other tests ran against), else cargo builds it.
      lib=${IGAPARAM_SANITIZE_LIBRARY:-}
      if [[ -z $lib ]]; then
        echo "+ cargo build --release"
        CARGO_BUILD_JOBS=2 cargo build --release --lib
        lib="$cargo_dir/release/libigaparam.so"
      fi
      build "$work/valgrind" "$lib"
      run_all "$work/valgrind" valgrind --error-exitcode=99 --leak-check=full \
        --errors-for-leak-kinds=definite --show-leak-kinds=definite || status=1
      ;;
    *)
      echo "asan.sh: unknown mode $mode (asan, valgrind)" >&2
      exit 2
      ;;
  esac
done
exit "$status"
