#!/usr/bin/env bash
# Builds everything, then relocates the bundled meshes into out/:
#   out/airfoil_relocated.vtu   Q9 airfoil mesh, airfoil rotated by 60 degrees
#   out/airfoil_laplacian.vtu   the same, harmonic placement only (no optimization)
#   out/wing_relocated.vtu      H27 wing mesh, twisted wing (about ten seconds)
#   out/wing_laplacian.vtu      the same, harmonic placement only
# parameterizes bundled domains with igaparam_param (T-mesh, spline map, G+Smo XML):
#   out/gran_canaria_{tmesh,spline}.vtu, out/gran_canaria.xml   coastline of Gran Canaria
#   out/puzzle_{tmesh,spline}.vtu, out/puzzle.xml               puzzle piece, adaptive loop
#   out/duck3d_{tmesh,spline}.vtu, out/duck3d.xml               3D duck B-rep (about half a minute)
#   out/jacksboro_{tmesh,spline}.vtu, out/jacksboro.xml         air above terrain, axes in km
# solves on the spline maps with igaparam_poisson (adaptive refinement beside uniform) and
# igaparam_wind (wind over the Jacksboro terrain):
#   out/puzzle_adaptive.json, out/puzzle_adaptive_spline.vtu   Helmholtz problem, centre inside the puzzle
#   out/duck_adaptive.json, out/duck_adaptive_spline.vtu       wave front through the duck's OBJ faces (minutes)
#   out/jacksboro_wind.vtu, out/jacksboro_wind.png             adjusted wind, streamlines (needs a display)
# and draws them (cells coloured by quality) with igaparam_render:
#   out/airfoil_relocated.png, out/airfoil_laplacian.png, out/wing_relocated.png,
#   out/airfoil_sorted_quality.png, out/wing_sorted_quality.png (cell qualities sorted ascending,
#   harmonic placement against optimized), out/gran_canaria_spline.png, out/puzzle_spline.png,
#   out/duck3d_spline.png, out/jacksboro_spline.png
#   (spline maps coloured by the mean ratio of their Jacobian), out/puzzle_adaptive_levels.png,
#   out/duck_adaptive_levels.png (the final adaptive spaces coloured by level),
#   out/puzzle_adaptive_convergence.png, out/duck_adaptive_convergence.png (errors against dofs)
# Rendering needs an X display: the real one, else a virtual one through xvfb-run; without
# either, the pictures are skipped with a message.
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
run tests/data/wing_0012_h27.vtu out/wing_laplacian.vtu --laplacian-only

param=build/examples-c/igaparam_param
if [[ -x $param ]]; then
  for args in "tests/data/boundary/gran_canaria.txt out/gran_canaria" \
    "tests/data/boundary/puzzle3_bdry.xml out/puzzle --adapt" \
    "tests/data/boundary/duck3d_BRep.xml out/duck3d --tol 1e-4 --max-level 4" \
    "tests/data/boundary/jacksboro_faces out/jacksboro --tol 1e-3 --scale 89273.3,111200,1"; do
    echo
    echo "+ $param $args"
    # shellcheck disable=SC2086  # the arguments are split on purpose
    "$param" $args
  done
else
  echo "run.sh: $param was not built (is OpenMesh, libopenmesh-dev, installed?)" >&2
fi

poisson=build/examples-c/igaparam_poisson
if [[ -x $poisson ]]; then
  for args in "tests/data/boundary/puzzle3_bdry.xml --problem helmholtz --adaptive --levels 3 --max-dofs 20000
      --json out/puzzle_adaptive.json --spline-vtu out/puzzle_adaptive_spline.vtu" \
    "tests/data/boundary/duck_faces --problem wavefront --alpha 30 --adaptive --levels 2 --max-dofs 12000
      --json out/duck_adaptive.json --spline-vtu out/duck_adaptive_spline.vtu"; do
    echo
    echo "+ $poisson $args"
    # shellcheck disable=SC2086  # the arguments are split on purpose
    "$poisson" $args --threads 2 2>/dev/null
  done
else
  echo "run.sh: $poisson was not built (is Eigen, libeigen3-dev, installed?)" >&2
fi

wind=build/examples-c/igaparam_wind
if [[ -x $wind ]]; then
  # The Jacksboro block in km with its lid moved to 10 km, a logarithmic wind; the streamline
  # picture needs a display (the real one or xvfb-run's).
  wind_args=(tests/data/boundary/jacksboro_faces --scale 89273.3,111200,1 --lid 10 --tol 3e-5 --profile log
    --levels 1 --threads 2 --vtu out/jacksboro_wind.vtu --png out/jacksboro_wind.png --stretch 4)
  wrapper=()
  [[ -z ${DISPLAY:-} ]] && command -v xvfb-run >/dev/null 2>&1 && wrapper=(xvfb-run -a)
  echo
  echo "+ ${wrapper[*]} $wind ${wind_args[*]}"
  "${wrapper[@]}" "$wind" "${wind_args[@]}" || echo "run.sh: igaparam_wind failed (exit $?; 77: no display)" >&2
else
  echo "run.sh: $wind was not built (needs Eigen, OpenMesh and VTK's rendering modules)" >&2
fi

render=build/examples-c/igaparam_render
display=()
if [[ ! -x $render ]]; then
  echo "run.sh: $render was not built (VTK's rendering modules missing?): no pictures" >&2
  exit 0
elif [[ -n ${DISPLAY:-} ]]; then
  :
elif command -v xvfb-run >/dev/null 2>&1; then
  display=(xvfb-run -a)
else
  echo "run.sh: no X display and no xvfb-run (Debian package xvfb): no pictures" >&2
  exit 0
fi
draw() {
  echo "+ ${display[*]} $render $*"
  local status=0
  "${display[@]}" "$render" "$@" || status=$?
  if ((status == 77)); then
    echo "run.sh: no X display could be opened: no pictures" >&2
    exit 0
  fi
  return "$status"
}
echo
draw out/airfoil_relocated.vtu out/airfoil_relocated.png --title "airfoil rotated 60 degrees, optimized"
draw out/airfoil_laplacian.vtu out/airfoil_laplacian.png --title "airfoil rotated 60 degrees, harmonic placement" \
  --range 0 1
draw out/wing_relocated.vtu out/wing_relocated.png --cut z 0.52 --view 25 20 \
  --title "wing twisted 18 degrees at the tip, optimized (cut at mid-span)"
draw --sorted-quality out/airfoil_laplacian.vtu out/airfoil_relocated.vtu out/airfoil_sorted_quality.png \
  --labels "harmonic placement,optimized" --title "airfoil (490 Q9 cells): cell quality, sorted"
draw --sorted-quality out/wing_laplacian.vtu out/wing_relocated.vtu out/wing_sorted_quality.png \
  --labels "harmonic placement,optimized" --title "wing (12,250 H27 cells): cell quality, sorted"
if [[ -x $param ]]; then
  draw out/gran_canaria_spline.vtu out/gran_canaria_spline.png --array quality --range 0 1 \
    --no-edges --title "Gran Canaria: spline map, mean ratio of the Jacobian"
  draw out/puzzle_spline.vtu out/puzzle_spline.png --array quality --range 0 1 --no-edges \
    --title "puzzle piece after adaptation: spline map, mean ratio of the Jacobian"
  draw out/duck3d_spline.vtu out/duck3d_spline.png --array quality --range 0 1 --no-edges \
    --view 30 20 --title "3D duck B-rep: untangled spline map, mean ratio of the Jacobian"
  draw out/jacksboro_spline.vtu out/jacksboro_spline.png --array quality --no-edges \
    --stretch 1 1 10 --view 200 -50 \
    --title "Jacksboro block in km (terrain from below, z x10): spline map, mean ratio"
fi
if [[ -x $poisson ]]; then
  draw out/puzzle_adaptive_spline.vtu out/puzzle_adaptive_levels.png --array level --no-edges \
    --title "puzzle piece, Helmholtz problem: the adaptive space by level"
  draw --convergence out/puzzle_adaptive.json out/puzzle_adaptive_convergence.png \
    --title "puzzle piece, Helmholtz problem with its centre inside"
  draw out/duck_adaptive_spline.vtu out/duck_adaptive_levels.png --array level --no-edges --cut x 0.55 --view 30 20 \
    --title "duck OBJ faces, wave front: the adaptive space by level (cut)"
  draw --convergence out/duck_adaptive.json out/duck_adaptive_convergence.png \
    --title "duck OBJ faces, wave front (alpha 30)"
fi
if [[ -x $poisson ]]; then
  draw out/puzzle_adaptive_spline.vtu out/puzzle_adaptive_levels.png --array level --no-edges \
    --title "puzzle piece, Helmholtz problem: the adaptive space by level"
  draw --convergence out/puzzle_adaptive.json out/puzzle_adaptive_convergence.png \
    --title "puzzle piece, Helmholtz problem with its centre inside"
  draw out/duck_adaptive_spline.vtu out/duck_adaptive_levels.png --array level --no-edges --cut x 0.55 --view 30 20 \
    --title "duck OBJ faces, wave front: the adaptive space by level (cut)"
  draw --convergence out/duck_adaptive.json out/duck_adaptive_convergence.png \
    --title "duck OBJ faces, wave front (alpha 30)"
fi
