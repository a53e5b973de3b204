#!/usr/bin/env bash
# Build the libFuzzer targets (clang, ASan + UBSan) and run each for a given time.
#   scripts/fuzz.sh [seconds_per_target (default 20)] [target ...]
# Seeds: small files from ../shared/data (read in place, copied only into the scratch build tree)
# plus a few generated ones. Prints per target: executions, coverage, crashes. Exit 1 on a finding
# (the crashing input is kept in build-fuzz/findings/).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
SECONDS_PER=${1:-20}
shift || true
BUILD=${VOLMAP_FUZZ_BUILD_DIR:-$ROOT/build-fuzz}
DATA=${VOLMAP_DATA:-$ROOT/../shared/data}
JOBS=${VOLMAP_JOBS:-$(nproc)}

CC=clang CXX=clang++ cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVOLMAP_BUILD_FUZZ=ON \
  -DVOLMAP_BUILD_TESTS=OFF -DVOLMAP_BUILD_BENCH=OFF -DVOLMAP_BUILD_TOOLS=OFF >/dev/null
TARGETS=("$@")
if ((${#TARGETS[@]} == 0)); then
  TARGETS=()
  for f in "$ROOT"/fuzz/fuzz_*.cpp; do TARGETS+=("$(basename "$f" .cpp)"); done
fi
cmake --build "$BUILD" -j"$JOBS" --target "${TARGETS[@]}" >/dev/null

# seed <target> <find expression...>: small data files as seeds
seed() {
  local target=$1; shift
  local dir=$BUILD/corpus/$target
  mkdir -p "$dir"
  if [ -d "$DATA" ]; then
    find "$DATA" -type f "$@" -size -300k -print0 2>/dev/null | head -z -n 40 | xargs -0 -r cp -t "$dir"
  fi
}
seed fuzz_medit -name '*.mesh'
seed fuzz_vtk -name '*.vtk'
seed fuzz_vtu -name '*.vtu'
seed fuzz_boundary_map -path '*G1_*' -name '*.txt'
seed fuzz_custom_domain -path '*custom_domains*'
seed fuzz_surface \( -name '*.off' -o -name '*.obj' -o -name '*.stl' -o -name '*.ply' \)
mkdir -p "$BUILD/corpus/fuzz_rationals" "$BUILD/corpus/fuzz_predicates" "$BUILD/corpus/fuzz_boundary_map" \
         "$BUILD/corpus/fuzz_tet_mesh"
printf '\x02%s\n' 1/2 3 -4/6 0 5/1 7/3 > "$BUILD/corpus/fuzz_rationals/seed1"
printf '0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n' > "$BUILD/corpus/fuzz_boundary_map/seed1"

mkdir -p "$BUILD/findings"
status=0
printf '%-22s %12s %8s %8s %s\n' target executions cov ft result
for t in "${TARGETS[@]}"; do
  exe=$BUILD/fuzz/$t
  [ -x "$exe" ] || { echo "$t: not built"; status=1; continue; }
  mkdir -p "$BUILD/corpus/$t"
  log=$BUILD/$t.log
  if (cd "$BUILD/findings" && "$exe" "$BUILD/corpus/$t" -max_total_time="$SECONDS_PER" -max_len=65536 \
        -rss_limit_mb=2560 -timeout=10 -print_final_stats=1 >"$log" 2>&1); then
    result=ok
  else
    result="FINDING (see $log)"; status=1
  fi
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo '?')
  ft=$(grep -o 'ft: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo '?')
  printf '%-22s %12s %8s %8s %s\n' "$t" "$execs" "$cov" "$ft" "$result"
done
exit $status
