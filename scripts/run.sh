#!/usr/bin/env bash
# Builds everything, then relocates the bundled meshes into out/:
#   out/airfoil_relocated.vtu   Q9 airfoil mesh, airfoil rotated by 60 degrees
#   out/airfoil_laplacian.vtu   the same, harmonic placement only (no optimization)
#   out/wing_relocated.vtu      H27 wing mesh, twisted wing (takes about half a minute)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/build.sh

relocate=build/examples-c/igaparam_relocate
if [[ ! -x $relocate ]]; then
  echo "run.sh: $relocate was not built (is VTK, libvtk9-dev, installed?)" >&2
  exit 1
fi
mkdir -p out
run() {
  echo
  echo "+ $relocate $*"
  "$relocate" "$@"
}
run tests/data/airfoil_0012_q9.vtu out/airfoil_relocated.vtu
run tests/data/airfoil_0012_q9.vtu out/airfoil_laplacian.vtu --laplacian-only
run tests/data/wing_0012_h27.vtu out/wing_relocated.vtu
