#!/usr/bin/env bash
# The C API test programs (tests/c/test_capi.c, test_domain.c, test_spline.c) under
# AddressSanitizer and under valgrind memcheck: bash scripts/asan.sh [asan|valgrind ...]
# (default: both).
#
# - asan: the library built with -Zsanitizer=address (nightly Rust) and the programs with
#   -fsanitize=address, leaks reported (LeakSanitizer); any error fails the run.
# - valgrind: the programs against the ordinary release library under memcheck, zero errors and
#   zero definite leaks required.
#
# scripts/test.sh runs the valgrind mode on test_capi and test_handles (half a minute); the ASan
# build of the library and the valgrind runs of the domain and spline programs take several
# minutes more on a 2-core machine, so the full run is this script's. A tool that is missing is
# reported and skipped.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
export PATH="$PATH:${CARGO_HOME:-$HOME/.cargo}/bin"
root=$PWD

modes=("$@")
((${#modes[@]} > 0)) || modes=(asan valgrind)
# IGAPARAM_SANITIZE_PROGRAMS: the programs to run (names separated by spaces), default all four.
read -r -a programs <<<"${IGAPARAM_SANITIZE_PROGRAMS:-test_capi test_domain test_spline test_handles}"
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

status=0
for mode in "${modes[@]}"; do
  case $mode in
    asan)
      if ! cargo +nightly --version >/dev/null 2>&1; then
        echo "asan.sh: no nightly Rust toolchain: AddressSanitizer run skipped"
        continue
      fi
      echo "+ cargo +nightly build --release (-Zsanitizer=address)"
      RUSTFLAGS="-Zsanitizer=address" CARGO_TARGET_DIR="$cargo_dir/asan" CARGO_BUILD_JOBS=2 \
        cargo +nightly build --release --lib --target x86_64-unknown-linux-gnu
      build "$work/asan" "$cargo_dir/asan/x86_64-unknown-linux-gnu/release/libigaparam.so" \
        -fsanitize=address -fno-omit-frame-pointer
      ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 run_all "$work/asan" env || status=1
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
