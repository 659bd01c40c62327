#!/usr/bin/env bash
# Installs the Debian packages the C/C++ build needs (as root, only those missing) and checks
# that cargo is available. Without root, prints the command to run and goes on.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

# xvfb (with xauth for xvfb-run) and Mesa's OpenGL drivers: VTK renders the pictures through X,
# on a virtual display when there is no real one. OpenMPI (libopenmpi-dev, openmpi-bin): the
# example igaparam_relocate_mpi and its tests (the library itself links no MPI). valgrind: the
# memcheck run of the C API tests (scripts/test.sh, scripts/asan.sh).
packages=(cmake g++ pkg-config libvtk9-dev libopenmesh-dev libeigen3-dev xvfb xauth libgl1-mesa-dri
  libopenmpi-dev openmpi-bin valgrind)

if command -v dpkg >/dev/null 2>&1; then
  missing=()
  for package in "${packages[@]}"; do
    dpkg -s "$package" >/dev/null 2>&1 || missing+=("$package")
  done
  if ((${#missing[@]} > 0)); then
    if [[ $(id -u) -eq 0 ]]; then
      echo "deps.sh: installing ${missing[*]}"
      apt-get update
      DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
    else
      echo "deps.sh: missing packages; install them with: sudo apt-get install ${missing[*]}" >&2
    fi
  fi
else
  echo "deps.sh: not a Debian system; make sure these (or their equivalents) are installed: ${packages[*]}" >&2
fi

if ! command -v cargo >/dev/null 2>&1 && [[ ! -x "${CARGO_HOME:-$HOME/.cargo}/bin/cargo" ]]; then
  echo "deps.sh: cargo not found: install Rust from https://rustup.rs" >&2
  exit 1
fi
