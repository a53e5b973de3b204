#!/usr/bin/env bash
# The whole test suite on an already built tree ($1, default build/):
#  1. predicates again in a build where the rest of the code uses -ffp-contract=fast -march=native
#     (proves the predicates' own flags protect them), then the same tests with MXCSR FTZ|DAZ set;
#  2. install into a scratch prefix and build/run the outside consumer project against it: the
#     predicates alone, then volmap::volmap reading, checking, mapping and certifying a G1 pair
#     (bone cube from ../shared/data, or a generated pair when the data is absent);
#  3. the main ctest run (default labels; set VOLMAP_LONG_TESTS=1 to include tests labelled long).
# The main ctest summary is printed last so CI reads it.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
BUILD=$(realpath -m "${1:-$ROOT/build}")  # absolute: reused as CMAKE_PREFIX_PATH below
JOBS=${VOLMAP_JOBS:-$(nproc)}

echo "== predicates under -ffp-contract=fast -march=native for the rest of the code"
FAST=$BUILD-fastmath
cmake -S "$ROOT" -B "$FAST" -DCMAKE_BUILD_TYPE=Release -DVOLMAP_BUILD_LIB=OFF -DVOLMAP_BUILD_BENCH=OFF \
      -DCMAKE_CXX_FLAGS="-ffp-contract=fast -march=native" >/dev/null
cmake --build "$FAST" -j"$JOBS" >/dev/null
ctest --test-dir "$FAST" -j"$JOBS" --output-on-failure -LE long | tail -n 3
echo "== predicates with MXCSR flush-to-zero + denormals-are-zero set (VOLMAP_TEST_FTZ_DAZ=1)"
VOLMAP_TEST_FTZ_DAZ=1 ctest --test-dir "$FAST" -j"$JOBS" --output-on-failure -LE long | tail -n 3

echo "== install + outside consumer project"
PREFIX=$BUILD-install
rm -rf "$PREFIX"
cmake --install "$BUILD" --prefix "$PREFIX" >/dev/null
cmake -S "$ROOT/tests/consumer" -B "$BUILD-consumer" -DCMAKE_PREFIX_PATH="$PREFIX" >/dev/null
cmake --build "$BUILD-consumer" -j"$JOBS" >/dev/null
"$BUILD-consumer/volmap_consumer"
DATA=${VOLMAP_DATA:-$ROOT/../shared/data}
CONSUMER_OUT=$BUILD-consumer/out
mkdir -p "$CONSUMER_OUT"
if [ -f "$DATA/volmap/G1/bone.mesh" ]; then
  "$BUILD-consumer/volmap_consumer_map" "$DATA/volmap/G1/bone.mesh" "$DATA/volmap/G1_cube/bone_cube.txt" "$CONSUMER_OUT"
else
  echo "consumer: $DATA/volmap/G1 absent; mapping a generated shape instead"
  "$BUILD/bin/volmap-shapes" "$CONSUMER_OUT/shapes" >/dev/null
  "$BUILD/bin/volmap-tetrahedralize" "$CONSUMER_OUT/shapes/peanut.off" "$CONSUMER_OUT/blob.mesh" >/dev/null
  "$BUILD/bin/volmap-surface-map" cube "$CONSUMER_OUT/blob.mesh" "$CONSUMER_OUT/blob_cube.txt" >/dev/null
  "$BUILD-consumer/volmap_consumer_map" "$CONSUMER_OUT/blob.mesh" "$CONSUMER_OUT/blob_cube.txt" "$CONSUMER_OUT"
fi

echo "== main test suite"
LABELS=(-LE long)
[ "${VOLMAP_LONG_TESTS:-0}" = 1 ] && LABELS=()
ctest --test-dir "$BUILD" -j"$JOBS" --output-on-failure "${LABELS[@]}"
