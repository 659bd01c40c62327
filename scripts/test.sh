#!/usr/bin/env bash
# Builds everything and runs all tests: the lints (cargo fmt --check, cargo clippy, cargo doc,
# warnings as errors), the Rust tests (cargo test --release), then the C/C++ tests and example
# runs (ctest), the C API tests under valgrind memcheck and AddressSanitizer and a short run of
# every fuzz target, then the Python bindings' tests (pytest, in the virtual environment
# build/venv).
# Runs every suite, and exits non-zero if any of them failed.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

# IGAPARAM_NO_SKIP=1: a dependency the README installs that is missing fails the CMake
# configuration (rather than leaving its tests unregistered), a picture test without a display
# fails instead of skipping, and so does a skipped pytest test.
export IGAPARAM_NO_SKIP=1

bash scripts/build.sh
export PATH="$PATH:${CARGO_HOME:-$HOME/.cargo}/bin"  # where rustup puts cargo
# The cargo commands below share the CMake build's target directory, so that the dependencies
# the build compiled in the release profile are not compiled a second time for the tests.
export CARGO_TARGET_DIR="$PWD/build/cargo"
library="$CARGO_TARGET_DIR/release/libigaparam.so"  # what valgrind and the Python tests load

status=0

# A cargo subcommand of a rustup component (rustfmt for `cargo fmt`, clippy for `cargo clippy`):
# added through rustup when it is missing, else an error naming what to install.
component() {
  local name=$1 subcommand=$2
  cargo "$subcommand" --version >/dev/null 2>&1 && return 0
  if command -v rustup >/dev/null 2>&1; then
    echo "+ rustup component add $name"
    rustup component add "$name" && cargo "$subcommand" --version >/dev/null 2>&1 && return 0
  fi
  echo "test.sh: cargo $subcommand is not available: install the $name component" \
    "(rustup component add $name)" >&2
  return 1
}

# Lints, before the tests, each failing on any warning: the formatting, clippy on every target
# (release profile, as the tests), and the API docs (broken or private links). The docs are
# built in the release profile too, so that they reuse the dependencies' metadata clippy made.
lints() {
  local failed=0
  if component rustfmt fmt; then
    echo "+ cargo fmt --check"
    cargo fmt --check || failed=1
  else
    failed=1
  fi
  if component clippy clippy; then
    echo "+ cargo clippy --release --all-targets -- -D warnings"
    cargo clippy --release --all-targets -- -D warnings || failed=1
  else
    failed=1
  fi
  echo "+ RUSTDOCFLAGS=\"-D warnings\" cargo doc --release --no-deps"
  RUSTDOCFLAGS="-D warnings" cargo doc --release --no-deps || failed=1
  return "$failed"
}
lints || { status=1; echo "test.sh: lints failed" >&2; }

echo "+ cargo test --release --no-fail-fast"
cargo test --release --no-fail-fast || { status=1; echo "test.sh: cargo test failed" >&2; }
# Two at a time: each test writes its own files under build/tests-out, and the fixtures
# (the relocated airfoil, the adaptive series) order the tests that read what another wrote.
echo "+ ctest --test-dir build --output-on-failure -j2"
ctest --test-dir build --output-on-failure -j2 || { status=1; echo "test.sh: ctest failed" >&2; }

# The C API's own tests and its handle tests under valgrind memcheck (zero errors, zero definite
# leaks), and with the loop and sensitivity tests under AddressSanitizer; then every fuzz target
# for a short run (1000 inputs, at most 60 s, each). The last two share one nightly build
# (-Zsanitizer=address and libFuzzer's coverage); scripts/asan.sh runs all the C programs.
IGAPARAM_SANITIZE_PROGRAMS="test_capi test_handles" \
  IGAPARAM_SANITIZE_LIBRARY="$library" bash scripts/asan.sh valgrind ||
  { status=1; echo "test.sh: valgrind memcheck failed" >&2; }
IGAPARAM_SANITIZE_PROGRAMS="test_capi test_handles test_morph test_sensitivity" \
  bash scripts/asan.sh asan fuzz ||
  { status=1; echo "test.sh: AddressSanitizer or fuzz run failed" >&2; }

# Python bindings: bindings/python installed into build/venv, tested against the library just built.
python_tests() {
  local venv=build/venv
  if [[ ! -x "$venv/bin/python" ]]; then
    echo "+ python3 -m venv $venv"
    python3 -m venv "$venv" || return 1
  fi
  echo "+ $venv/bin/python -m pip install -q pytest numpy; pip install -q bindings/python"
  "$venv/bin/python" -m pip install -q pytest numpy || return 1
  # meshio: the tests compare the Python and C++ results on the airfoil read by it, and run the
  # README's Python example. pygismo (G+Smo): the tests read the library's G+Smo XML with it.
  # vtk and gmsh: the .vtu and node-order tests check the library against them. scipy: the
  # shape-optimization example's optimizer.
  "$venv/bin/python" -m pip install -q meshio pygismo vtk gmsh scipy || return 1
  # The package bundles the library the CMake build made (no second cargo build); the wheel test
  # installs it again into a new venv the way a user does, with cargo's cache.
  IGAPARAM_PREBUILT_LIBRARY="$library" \
    "$venv/bin/python" -m pip install -q --force-reinstall --no-deps bindings/python || return 1
  # IGAPARAM_NO_SKIP=1 (exported above): a skipped test (no meshio, no pygismo, no C++ example) fails.
  echo "+ IGAPARAM_LIBRARY=build/cargo/release/libigaparam.so IGAPARAM_NO_SKIP=1 python -m pytest -q tests/python"
  IGAPARAM_LIBRARY="$library" IGAPARAM_BUILD_DIR="$PWD/build" \
    "$venv/bin/python" -m pytest -q -rs -p no:cacheprovider tests/python
}
python_tests || { status=1; echo "test.sh: Python tests failed" >&2; }
exit "$status"
