#!/usr/bin/env bash
# volmap set-up: installs the Debian packages the project needs (skipping what is installed),
# configures and builds, then runs what was asked:
#   scripts/setup.sh --demo     build, then run the demo on built-in data
#   scripts/setup.sh --test     build, then run the whole test suite (what .ci/run calls)
#   scripts/setup.sh            build only
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
MODE=${1:-build}
BUILD=${VOLMAP_BUILD_DIR:-$ROOT/build}
JOBS=${VOLMAP_JOBS:-$(nproc)}

PACKAGES=(build-essential cmake pkg-config libeigen3-dev libboost-dev libgmp-dev libopenmesh-dev
          libtet1.5-dev doctest-dev libbenchmark-dev libcli11-dev nlohmann-json3-dev liblbfgspp-dev
          libtbb-dev libcgal-dev python3-meshio chromium fonts-liberation snakemake clang libclang-rt-14-dev)
# Node.js + npm for the viewer bundle: the machine's own when present, else Debian's.
command -v npm >/dev/null || PACKAGES+=(nodejs npm)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  SUDO=""; [ "$(id -u)" = 0 ] || SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# volmap-view's browser bundle (viewer/dist/viewer.js: three.js + viewer, pinned by package-lock.json),
# with the machine's Node.js/npm; npm ci only when the lock file changed since the last install.
if command -v npm >/dev/null; then
  if [ ! -f viewer/node_modules/.package-lock.json ] || [ viewer/package-lock.json -nt viewer/node_modules/.package-lock.json ]; then
    (cd viewer && npm ci --no-audit --no-fund --loglevel=error) || echo "setup: npm ci failed in viewer/ (volmap-view tests will skip)"
  fi
  if [ -d viewer/node_modules/three ]; then (cd viewer && npm run --silent build); fi
else
  echo "setup: npm not found: volmap-view's bundle (viewer/dist/viewer.js) is not built"
fi

cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD" -j"$JOBS"

case "$MODE" in
  --demo) exec "$ROOT/scripts/demo.sh" "$BUILD" "${@:2}" ;;
  --test) exec "$ROOT/scripts/test.sh" "$BUILD" ;;
  build|--build) ;;
  *) echo "usage: scripts/setup.sh [--demo|--test]" >&2; exit 2 ;;
esac
