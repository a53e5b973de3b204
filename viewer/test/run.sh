#!/usr/bin/env bash
# Headless browser test of volmap-view pages (what the lead / CI calls):
#   viewer/test/run.sh [build-dir]
# Needs Debian's chromium (/usr/bin/chromium, or $CHROMIUM) and viewer/node_modules (npm ci);
# skips with a message (exit 0) when either is absent. Builds viewer/dist/viewer.js when missing,
# writes pages with build/bin/volmap-view from ../shared/data (each skipped when its data is absent)
# and runs view.test.mjs on each; screenshots and pages land in <build>/view-test/.
# $VOLMAP_VIEW_CASES (space-separated names) runs a subset: bunny-map hand-map duck-star-boundary
# bunny-cube-boundary buste-mesh max-map buste-tutte-map (buste onto the cube by volmap-tutte3d).
# Last line: "N passed, N failed".
set -euo pipefail
VIEWER=$(cd "$(dirname "$0")/.." && pwd)
ROOT=$(dirname "$VIEWER")
BUILD=$(cd "${1:-$ROOT/build}" && pwd)
DATA=${VOLMAP_DATA:-$ROOT/../shared/data}
OUT=$BUILD/view-test
CHROMIUM=${CHROMIUM:-/usr/bin/chromium}
export CHROMIUM

if [ ! -x "$CHROMIUM" ]; then echo "view test skipped: $CHROMIUM is absent (apt-get install chromium)"; echo "0 passed, 0 failed, 1 skipped"; exit 0; fi
if [ ! -d "$VIEWER/node_modules/playwright-core" ] || [ ! -d "$VIEWER/node_modules/three" ]; then
  echo "view test skipped: viewer/node_modules is absent (cd viewer && npm ci)"; echo "0 passed, 0 failed, 1 skipped"; exit 0
fi
if [ ! -x "$BUILD/bin/volmap-view" ]; then echo "view test: $BUILD/bin/volmap-view is not built" >&2; exit 1; fi
if [ ! -f "$VIEWER/dist/viewer.js" ]; then (cd "$VIEWER" && npm run --silent build); fi
mkdir -p "$OUT"

passed=0; failed=0; skipped=0
run_case() {  # name, "charts corners" expected (or ""), volmap-view args...
  local name=$1 expect=$2; shift 2
  if [ -n "${VOLMAP_VIEW_CASES:-}" ] && [[ " $VOLMAP_VIEW_CASES " != *" $name "* ]]; then return; fi
  for f in "$@"; do
    case "$f" in */*) if [ ! -f "$f" ]; then echo "view test $name skipped: $f is absent"; skipped=$((skipped + 1)); return; fi ;; esac
  done
  local extra=""
  if [ -n "$expect" ]; then extra="--expect-charts ${expect% *} --expect-corners ${expect#* }"; fi
  "$BUILD/bin/volmap-view" "$@" -o "$OUT/$name.html"
  local log=$OUT/$name.log
  if node "$VIEWER/test/view.test.mjs" "$OUT/$name.html" --label "$name" --screenshot "$OUT/$name.png" $extra >"$log" 2>&1; then :; fi
  grep -v '^[0-9]* passed, [0-9]* failed' "$log" || true
  local line; line=$(grep -E '^[0-9]+ passed, [0-9]+ failed' "$log" | tail -n 1)
  if [ -z "$line" ]; then failed=$((failed + 1)); return; fi
  passed=$((passed + $(echo "$line" | cut -d' ' -f1)))
  failed=$((failed + $(echo "$line" | cut -d' ' -f3)))
}

# Unit tests of the typed-array geometry (node's test runner, no browser).
if node --test "$VIEWER/test/unit.test.mjs" >"$OUT/unit-$$.log" 2>&1; then :; fi
unit_pass=$(grep -E '^# pass ' "$OUT/unit-$$.log" | awk '{print $3}'); unit_fail=$(grep -E '^# fail ' "$OUT/unit-$$.log" | awk '{print $3}')
echo "viewer unit tests: ${unit_pass:-0} passed, ${unit_fail:-1} failed"
[ "${unit_fail:-1}" = 0 ] || grep -E '^not ok|Error' "$OUT/unit-$$.log" | head -20
passed=$((passed + ${unit_pass:-0})); failed=$((failed + ${unit_fail:-1}))
[ "${unit_fail:-1}" = 0 ] && rm -f "$OUT/unit-$$.log"

S=$DATA/volmap/viewer-samples
run_case bunny-map "" "$S/bunny_input.mesh" "$S/bunny_output.mesh" --energy mips3d
run_case hand-map "" "$S/hand_aigerman.mesh" "$S/hand_pc_aigerman.mesh" --energy conformal
run_case duck-star-boundary "24 14" "$DATA/volmap/G1/duck.mesh" --map "$DATA/volmap/G1_star/duck_star.txt"
run_case bunny-cube-boundary "6 8" "$DATA/volmap/G1/bunny.mesh" --map "$DATA/volmap/G1_cube/bunny_cube.txt"
run_case buste-mesh "" "$DATA/volmap/G1/buste.mesh"
run_case max-map "" "$S/max.mesh" "$S/max_pc.mesh"
# A 100,695-tet G1 map with inverted tets: buste onto the cube by volmap-tutte3d (when built).
if [ -z "${VOLMAP_VIEW_CASES:-}" ] || [[ " $VOLMAP_VIEW_CASES " == *" buste-tutte-map "* ]]; then
  if [ -x "$BUILD/bin/volmap-tutte3d" ] && [ -f "$DATA/volmap/G1/buste.mesh" ] && [ -f "$DATA/volmap/G1_cube/buste_cube.txt" ]; then
    "$BUILD/bin/volmap-tutte3d" "$DATA/volmap/G1/buste.mesh" "$DATA/volmap/G1_cube/buste_cube.txt" "$OUT/buste_cube_tutte.mesh" >/dev/null || true
  fi
  run_case buste-tutte-map "" "$DATA/volmap/G1/buste.mesh" "$OUT/buste_cube_tutte.mesh"
fi
[ -f "$OUT/bunny-map.png" ] && cp "$OUT/bunny-map.png" "$OUT/screenshot.png"
echo "view test: pages and screenshots in $OUT"
echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" = 0 ]
