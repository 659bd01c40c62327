#!/usr/bin/env bash
# Benchmark of the relocation of a partitioned mesh: runs igaparam_relocate_mpi (built by
# scripts/build.sh when MPI is found) serially and at 1-4 ranks, and prints a Markdown table of
# the wall-clock time and the largest fraction of it a rank spent in exchanges (waiting for the
# other ranks included).
#
#   bash scripts/bench_mpi.sh [MESH.vtu [example options...]]   (default: the wing, 1 thread per rank)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
exe=build/examples-c/igaparam_relocate_mpi
[[ -x $exe ]] || { echo "bench_mpi.sh: $exe is not built (is MPI installed?)" >&2; exit 1; }
mesh=${1:-tests/data/wing_0012_h27.vtu}
shift || true
options=("$@")
((${#options[@]})) || options=(--threads 1)
flags=(--oversubscribe)
[[ $(id -u) -eq 0 ]] && flags+=(--allow-run-as-root)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
field() { sed -n "s/.*\"$1\": \"\{0,1\}\([^,\"}]*\).*/\1/p" <<<"$2"; }
echo "| ranks | seconds | in exchanges | sweeps | min quality | checksum |"
echo "|---|---|---|---|---|---|"
line=$("$exe" "$mesh" - --serial "${options[@]}" | tail -1)
echo "| serial | $(field seconds "$line") | – | $(field sweeps "$line") | $(field min_quality "$line") | $(field checksum "$line") |"
for n in 1 2 3 4; do
  line=$(mpirun "${flags[@]}" -np "$n" "$exe" "$mesh" "$out/part.pvtu" "${options[@]}" | tail -1)
  fraction=$(field exchange_fraction "$line")
  echo "| $n | $(field seconds "$line") | $(awk -v f="$fraction" 'BEGIN{printf "%.0f%%", 100*f}') | $(field sweeps "$line") | $(field min_quality "$line") | $(field checksum "$line") |"
done
