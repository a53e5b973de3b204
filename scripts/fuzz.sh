#!/usr/bin/env bash
# Build the libFuzzer targets (clang, ASan + UBSan) and run each for a given time.
#   scripts/fuzz.sh [seconds_per_target (default 20)] [target ...]
#   Longer runs in parallel: build once, then e.g.
#   VOLMAP_FUZZ_NO_BUILD=1 scripts/fuzz.sh 600 fuzz_medit fuzz_vtk & VOLMAP_FUZZ_NO_BUILD=1 scripts/fuzz.sh 600 fuzz_vtu ...
# Seeds: small files from ../shared/data (read in place, copied only into the scratch build tree)
# plus a few generated ones (generated only, with a message, when ../shared/data is absent). Prints
# per target: executions, coverage, crashes. Exit 1 on a finding: a non-zero libFuzzer exit or any new
# crash-/leak-/timeout-/oom- artifact (kept in build-fuzz/findings/<target>-*).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
SECONDS_PER=${1:-20}
shift || true
BUILD=${VOLMAP_FUZZ_BUILD_DIR:-$ROOT/build-fuzz}
DATA=${VOLMAP_DATA:-$ROOT/../shared/data}
JOBS=${VOLMAP_JOBS:-$(nproc)}

TARGETS=("$@")
if ((${#TARGETS[@]} == 0)); then
  TARGETS=()
  for f in "$ROOT"/fuzz/fuzz_*.cpp; do TARGETS+=("$(basename "$f" .cpp)"); done
fi
# VOLMAP_FUZZ_NO_BUILD=1: use the targets already built (parallel invocations on one build tree).
if [ "${VOLMAP_FUZZ_NO_BUILD:-0}" != 1 ]; then
  CC=clang CXX=clang++ cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVOLMAP_BUILD_FUZZ=ON \
    -DVOLMAP_BUILD_TESTS=OFF -DVOLMAP_BUILD_BENCH=OFF -DVOLMAP_BUILD_TOOLS=OFF >/dev/null
  cmake --build "$BUILD" -j"$JOBS" --target "${TARGETS[@]}" >/dev/null
fi

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
seed fuzz_ovm -name '*.ovm'
seed fuzz_boundary_map -path '*G1_*' -name '*.txt'
seed fuzz_custom_domain -path '*custom_domains*'
mkdir -p "$BUILD/corpus/fuzz_rationals" "$BUILD/corpus/fuzz_predicates" "$BUILD/corpus/fuzz_boundary_map" \
         "$BUILD/corpus/fuzz_tet_mesh" "$BUILD/corpus/fuzz_surface" "$BUILD/corpus/fuzz_custom_domain" \
         "$BUILD/corpus/fuzz_msh" "$BUILD/corpus/fuzz_ovm"
# Surfaces: the target's first byte picks the format (0 obj, 1 off, 2 stl, 3 ply), so seeds get that
# byte prepended (small files only).
if [ -d "$DATA" ]; then
  i=0
  while IFS= read -r -d '' f; do
    case "${f##*.}" in obj) b='\x00' ;; off) b='\x01' ;; stl) b='\x02' ;; ply) b='\x03' ;; *) continue ;; esac
    { printf "$b"; cat "$f"; } > "$BUILD/corpus/fuzz_surface/data_$i"; i=$((i + 1))
  done < <(find "$DATA/surfaces" "$DATA/negative" -type f \( -name '*.off' -o -name '*.obj' -o -name '*.stl' -o -name '*.ply' \) \
             -size -64k -print0 2>/dev/null | head -z -n 40)
fi
printf '\x00v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' > "$BUILD/corpus/fuzz_surface/tet_obj"
printf '\x01OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' > "$BUILD/corpus/fuzz_surface/tet_off"
printf '\x03ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' > "$BUILD/corpus/fuzz_surface/tet_ply"
printf '\x02solid t\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid t\n' > "$BUILD/corpus/fuzz_surface/tri_stl"
# Custom domains: a tetrahedron and a cube.
printf 'n 0\nn 1\nn 2\nn 4\nnm 0 0 0\nnm 0 0 100\nnm 100 0 50\nnm 30 100 30\na 0 1\na 1 2\na 2 0\na 3 0\na 3 1\na 3 2\n' \
  > "$BUILD/corpus/fuzz_custom_domain/tet"
printf 'n 0\nn 1\nn 2\nn 3\nn 4\nn 5\nn 6\nn 7\nnm 0 0 0\nnm 0 0 100\nnm 100 0 100\nnm 100 0 0\nnm 0 100 0\nnm 0 100 100\nnm 100 100 100\nnm 100 100 0\na 0 1\na 1 2\na 2 3\na 0 3\na 0 4\na 1 5\na 2 6\na 3 7\na 4 5\na 5 6\na 6 7\na 4 7\n' \
  > "$BUILD/corpus/fuzz_custom_domain/cube"
# Gmsh: one tet plus a triangle, MSH 2.2 and 4.1 (ASCII; binary variants come from mutation).
printf '$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n$Elements\n2\n1 2 2 0 1 1 2 3\n2 4 2 7 1 1 2 3 4\n$EndElements\n' \
  > "$BUILD/corpus/fuzz_msh/tet22"
printf '$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 0 0 1\n1 0 0 0 1 1 1 1 7 0\n$EndEntities\n$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n$EndElements\n' \
  > "$BUILD/corpus/fuzz_msh/tet41"
printf 'OVM ASCII\nVertices\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\nEdges\n6\n0 1\n1 2\n0 2\n0 3\n1 3\n2 3\nFaces\n4\n3 0 2 5\n3 6 9 1\n3 4 10 7\n3 8 11 3\nPolyhedra\n1\n4 0 2 4 6\n' \
  > "$BUILD/corpus/fuzz_ovm/tet"
# TetMesh from arrays: byte 0 = vertex count, then 4 ids per tet (two tets sharing a face; a Kuhn cube).
printf '\x05\x00\x01\x02\x03\x01\x00\x02\x04' > "$BUILD/corpus/fuzz_tet_mesh/two_tets"
printf '\x08\x00\x01\x03\x07\x00\x01\x05\x07\x00\x02\x03\x07\x00\x02\x06\x07\x00\x04\x05\x07\x00\x04\x06\x07' > "$BUILD/corpus/fuzz_tet_mesh/kuhn_cube"
printf '\x02%s\n' 1/2 3 -4/6 0 5/1 7/3 > "$BUILD/corpus/fuzz_rationals/seed1"
printf '0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n' > "$BUILD/corpus/fuzz_boundary_map/seed1"

if [ -d "$DATA" ]; then echo "== fuzz seeds: $DATA and generated files"
else echo "== fuzz seeds: $DATA absent, generated seeds only"; fi
mkdir -p "$BUILD/findings"
# artifacts <target>: how many crash/leak/timeout/oom artifacts this target has left so far
artifacts() { find "$BUILD/findings" -maxdepth 1 -type f \( -name "$1-crash-*" -o -name "$1-leak-*" -o -name "$1-timeout-*" -o -name "$1-oom-*" \) | wc -l; }
status=0
printf '%-22s %12s %8s %8s %s\n' target executions cov ft result
for t in "${TARGETS[@]}"; do
  exe=$BUILD/fuzz/$t
  [ -x "$exe" ] || { echo "$t: not built"; status=1; continue; }
  mkdir -p "$BUILD/corpus/$t"
  log=$BUILD/$t.log
  before=$(artifacts "$t")
  if (cd "$BUILD/findings" && "$exe" "$BUILD/corpus/$t" -max_total_time="$SECONDS_PER" -max_len=65536 \
        -rss_limit_mb=2560 -timeout=10 -print_final_stats=1 -artifact_prefix="$BUILD/findings/$t-" >"$log" 2>&1) &&
     [ "$(artifacts "$t")" = "$before" ]; then
    result=ok
  else
    result="FINDING (see $log and $BUILD/findings/$t-*)"; status=1
  fi
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo '?')
  ft=$(grep -o 'ft: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo '?')
  printf '%-22s %12s %8s %8s %s\n' "$t" "$execs" "$cov" "$ft" "$result"
done
exit $status
