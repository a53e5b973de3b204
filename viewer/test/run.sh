#!/usr/bin/env bash
# Headless browser test of volmap-view pages (what the lead / CI calls):
#   viewer/test/run.sh [build-dir]
# Needs Debian's chromium (/usr/bin/chromium, or $CHROMIUM) and viewer/node_modules (npm ci);
# skips with a message (exit 0) when either is absent. Builds viewer/dist/viewer.js when missing,
# writes pages with build/bin/volmap-view from ../shared/data (each skipped when its data is absent)
# and runs view.test.mjs on each; screenshots and pages land in <build>/view-test/.
# $VOLMAP_VIEW_CASES (space-separated names) runs a subset: bunny-map hand-map bunny-cube-boundary buste-mesh.
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
run_case() {  # name, expect-map flag, volmap-view args...
  local name=$1 flag=$2; shift 2
  if [ -n "${VOLMAP_VIEW_CASES:-}" ] && [[ " $VOLMAP_VIEW_CASES " != *" $name "* ]]; then return; fi
  for f in "$@"; do
    case "$f" in */*) if [ ! -f "$f" ]; then echo "view test $name skipped: $f is absent"; skipped=$((skipped + 1)); return; fi ;; esac
  done
  "$BUILD/bin/volmap-view" "$@" -o "$OUT/$name.html"
  local log=$OUT/$name.log
  if node "$VIEWER/test/view.test.mjs" "$OUT/$name.html" --label "$name" --screenshot "$OUT/$name.png" $flag >"$log" 2>&1; then :; fi
  grep -v '^[0-9]* passed, [0-9]* failed' "$log" || true
  local line; line=$(grep -E '^[0-9]+ passed, [0-9]+ failed' "$log" | tail -n 1)
  if [ -z "$line" ]; then failed=$((failed + 1)); return; fi
  passed=$((passed + $(echo "$line" | cut -d' ' -f1)))
  failed=$((failed + $(echo "$line" | cut -d' ' -f3)))
}

S=$DATA/volmap/viewer-samples
run_case bunny-map "" "$S/bunny_input.mesh" "$S/bunny_output.mesh" --energy mips3d
run_case hand-map "" "$S/hand_aigerman.mesh" "$S/hand_pc_aigerman.mesh" --energy conformal
run_case bunny-cube-boundary --expect-map "$DATA/volmap/G1/bunny.mesh" --map "$DATA/volmap/G1_cube/bunny_cube.txt"
run_case buste-mesh "" "$DATA/volmap/G1/buste.mesh"
[ -f "$OUT/bunny-map.png" ] && cp "$OUT/bunny-map.png" "$OUT/screenshot.png"
echo "view test: pages and screenshots in $OUT"
echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" = 0 ]
