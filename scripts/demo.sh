#!/usr/bin/env bash
# The demo on built-in data (no downloads, no ../shared needed). Today: the exact-predicate
# validator on its generated hard cases, then the predicate benchmark.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
"$BUILD/bin/volmap-predicates-selftest"
if [ -x "$BUILD/bin/bench_predicates" ]; then
  "$BUILD/bin/bench_predicates" --benchmark_min_time=0.05
fi
