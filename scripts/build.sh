#!/usr/bin/env bash
# Installs missing dependencies, then configures and builds everything in build/ (the Rust
# library through cargo, the C/C++ examples and tests).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2
