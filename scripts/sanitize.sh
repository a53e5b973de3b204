#!/usr/bin/env bash
# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer (g++, -O1 -g1: half the build
# time of -O2 -g, line numbers kept in every report), in build-asan/.
#   scripts/sanitize.sh                 build everything, run ctest -LE long (the whole default suite;
#                                       what CI runs, see .ci/run)
#   scripts/sanitize.sh --subset        build the tools and the predicates / core / io / tools suites
#                                       only and run those binaries (quicker local check)
#   scripts/sanitize.sh [ctest args]    build everything, run ctest with these arguments
# Any sanitizer report aborts the test that triggered it (UBSan is built with -fno-sanitize-recover,
# ASan with abort_on_error), so a green run means no report. Prints the wall time of build and tests.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
BUILD=${VOLMAP_ASAN_BUILD_DIR:-$ROOT/build-asan}
JOBS=${VOLMAP_JOBS:-$(nproc)}
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

# The subset: the predicates (also under FTZ|DAZ), the mesh structure, every file parser and the
# tool suite (bad-input corpus: every tool under ASan). Suites are tests/<wing>/ -> test_<wing>.
SUBSET_TESTS=(test_predicates test_core test_io test_tools)

start=$(date +%s)
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -DNDEBUG" -DVOLMAP_SANITIZE=ON -DVOLMAP_BUILD_BENCH=OFF >/dev/null
status=0
if [ "${1:-}" = --subset ]; then
  TOOLS=()
  for f in "$ROOT"/tools/volmap-*.cpp; do TOOLS+=("$(basename "$f" .cpp)"); done
  TESTS=()
  for t in "${SUBSET_TESTS[@]}"; do [ -d "$ROOT/tests/${t#test_}" ] && TESTS+=("$t"); done
  cmake --build "$BUILD" -j"$JOBS" --target "${TOOLS[@]}" "${TESTS[@]}" >/dev/null
  built=$(date +%s)
  echo "== sanitizer build (subset: tools + ${#TESTS[@]} test executables): $((built - start)) s"
  for t in "${TESTS[@]}"; do
    if (cd "$BUILD/tests" && "./$t" --test-suite-exclude=long >"$BUILD/$t.asan.log" 2>&1); then
      echo "   $t: passed"
    else
      echo "   $t: FAILED (log: $BUILD/$t.asan.log)"; tail -n 30 "$BUILD/$t.asan.log"; status=1
    fi
  done
  echo "== sanitizer tests (ASan+UBSan, subset of ${#TESTS[@]} executables): $(( $(date +%s) - built )) s, exit $status"
else
  cmake --build "$BUILD" -j"$JOBS" >/dev/null
  built=$(date +%s)
  echo "== sanitizer build: $((built - start)) s"
  ARGS=("$@")
  ((${#ARGS[@]} == 0)) && ARGS=(-LE long)
  ctest --test-dir "$BUILD" -j"$JOBS" --output-on-failure "${ARGS[@]}" || status=$?
  echo "== sanitizer tests (ASan+UBSan, ctest ${ARGS[*]}): $(( $(date +%s) - built )) s, exit $status"
fi
exit $status
