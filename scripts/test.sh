#!/usr/bin/env bash
# Builds everything and runs all tests: the Rust tests (cargo test --release), then the C/C++
# tests and example runs (ctest). Runs every suite, and exits non-zero if any test failed.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/build.sh
export PATH="$PATH:${CARGO_HOME:-$HOME/.cargo}/bin"  # where rustup puts cargo

status=0
echo "+ cargo test --release --no-fail-fast"
cargo test --release --no-fail-fast || { status=1; echo "test.sh: cargo test failed" >&2; }
echo "+ ctest --test-dir build --output-on-failure"
ctest --test-dir build --output-on-failure || { status=1; echo "test.sh: ctest failed" >&2; }
exit "$status"
