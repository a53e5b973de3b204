#!/usr/bin/env bash
# The demo, on built-in data (no downloads; ../shared is not needed):
#   1. the exact-predicate validator on its generated hard cases;
#   2. a small dataset: procedurally generated genus-0 surfaces -> TetGen tet meshes -> verified
#      boundary maps to every base domain (volmap-dataset);
#   3. Tutte 3D and volmap-map over it with the exact check and metrics (volmap-run);
#   4. one self-contained HTML report comparing both; its path is printed last.
# Usage: scripts/demo.sh [build_dir] [VOLMAP_folder]   (a VOLMAP folder, e.g. ../shared/data/volmap,
# replaces the built-in dataset; then only group G1 runs unless VOLMAP_DEMO_GROUPS is set).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=$(cd "${1:-build}" && pwd)
BIN=$BUILD/bin
DEMO=$BUILD/demo
JOBS=${VOLMAP_JOBS:-$(nproc)}
mkdir -p "$DEMO"

echo "== 1. exact predicates: validator on built-in hard cases"
"$BIN/volmap-predicates-selftest"

if [ -n "${2:-}" ]; then
  DATASET=$(cd "$2" && pwd)
  GROUP_ARGS=(--groups "${VOLMAP_DEMO_GROUPS:-G1}")
  echo "== 2. dataset: $DATASET (${GROUP_ARGS[1]})"
else
  DATASET=$DEMO/dataset
  GROUP_ARGS=()
  echo "== 2. dataset: built-in shapes -> tet meshes -> boundary maps to all domains"
  rm -rf "$DEMO/surfaces" "$DATASET"
  "$BIN/volmap-shapes" "$DEMO/surfaces" --subdivisions 3 >/dev/null
  "$BIN/volmap-dataset" "$DEMO/surfaces" "$DATASET" --group G1 --jobs "$JOBS" --domains cube,tet,pyr,octa,star \
    --max-volume 0.002
fi

echo "== 3. volume maps with the exact check and VOLMAP metrics"
METHODS=(tutte3d)
[ -x "$BIN/volmap-map" ] && METHODS+=(map)
# The mapper gets 60 s per case (one thread): the demo stays within a few minutes, and a case the
# mapper cannot certify in that time is reported as such (never as certified).
for m in "${METHODS[@]}"; do
  rm -rf "$DEMO/results-$m"
  ARGS=()
  [ "$m" = map ] && ARGS=(--method-args="--threads 1 --time-limit 60")
  "$BIN/volmap-run" "$DATASET" "${GROUP_ARGS[@]}" --method "$m" "${ARGS[@]}" --jobs "$JOBS" --timeout 300 --out "$DEMO/results-$m"
done

echo "== 4. report"
if [ -d "$DEMO/results-map" ]; then
  "$BIN/volmap-run" report "$DEMO/results-map" --compare "$DEMO/results-tutte3d" -o "$DEMO/report.html" --csv "$DEMO/summary.csv"
else
  "$BIN/volmap-run" report "$DEMO/results-tutte3d" -o "$DEMO/report.html" --csv "$DEMO/summary.csv"
fi
echo "demo report: $DEMO/report.html"
