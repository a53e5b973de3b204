#!/usr/bin/env bash
# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer (g++), in build-asan/.
#   scripts/sanitize.sh [ctest args...]   (default: every test except those labelled long)
# Examples: scripts/sanitize.sh -R 'io|mesh|predicates'   (a subset, as CI does when short of time)
# Any sanitizer report aborts the test that triggered it (UBSan is built with -fno-sanitize-recover),
# so a green ctest run means no report. Prints the wall time of the build and of the test run.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
BUILD=${VOLMAP_ASAN_BUILD_DIR:-$ROOT/build-asan}
JOBS=${VOLMAP_JOBS:-$(nproc)}
# detect_leaks: the tools exit through run_tool and the tests free what they allocate; keep leaks on.
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

start=$(date +%s)
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVOLMAP_SANITIZE=ON -DVOLMAP_BUILD_BENCH=OFF >/dev/null
cmake --build "$BUILD" -j"$JOBS" >/dev/null
built=$(date +%s)
echo "== sanitizer build: $((built - start)) s"
ARGS=("$@")
((${#ARGS[@]} == 0)) && ARGS=(-LE long)
status=0
ctest --test-dir "$BUILD" -j"$JOBS" --output-on-failure "${ARGS[@]}" || status=$?
echo "== sanitizer tests (ASan+UBSan, ctest ${ARGS[*]}): $(( $(date +%s) - built )) s, exit $status"
exit $status
