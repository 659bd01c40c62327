# Sourced by scripts/fuzz.sh and scripts/asan.sh: the fuzz targets and their seeds.

# The fuzz targets of fuzz/ (one per file reader, and capi: C-API call sequences).
fuzz_targets=(gismo_xml gismo_thb vtu coastline obj capi)

# Seeds of target $1 from the bundled data (tests/data) and the kept inputs of tests/data/fuzz/,
# in the directory $2 (emptied first).
fuzz_seeds() {
  local target=$1 dir=$2
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
