// side_by_side.hpp — runs volmap's code and its anchor (the reference implementation or the plain
// baseline it is judged against) in the SAME benchmark loop, alternately, and reports both as counters,
// so one run on a loaded machine gives comparable figures:
//   ours_ms, anchor_ms   process CPU time per call (all threads), the minimum over the iterations;
//   ratio                ours_ms / anchor_ms (< 1: volmap is faster; 0.1 = ten times faster);
//   ours_wall_ms, anchor_wall_ms, wall_ratio   the same in wall-clock time.
// The benchmark's own Time column covers both calls of an iteration: read the counters.
// With --benchmark_repetitions=N, take the "_min" aggregate rows (ComputeStatistics("min")).
#pragma once

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <limits>
#include <vector>

namespace bench {

inline double process_cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

struct CallTime {
  double cpu = std::numeric_limits<double>::infinity();
  double wall = std::numeric_limits<double>::infinity();
};

template <class F>
void time_call(CallTime& best, F&& f) {
  const double c0 = process_cpu_seconds();
  const auto w0 = std::chrono::steady_clock::now();
  f();
  const auto w1 = std::chrono::steady_clock::now();
  const double c1 = process_cpu_seconds();
  best.cpu = std::min(best.cpu, c1 - c0);
  best.wall = std::min(best.wall, std::chrono::duration<double>(w1 - w0).count());
}

inline void report_side_by_side(benchmark::State& state, const CallTime& ours, const CallTime& anchor) {
  state.counters["ours_ms"] = 1e3 * ours.cpu;
  state.counters["anchor_ms"] = 1e3 * anchor.cpu;
  state.counters["ratio"] = anchor.cpu > 0 ? ours.cpu / anchor.cpu : 0.0;
  state.counters["ours_wall_ms"] = 1e3 * ours.wall;
  state.counters["anchor_wall_ms"] = 1e3 * anchor.wall;
  state.counters["wall_ratio"] = anchor.wall > 0 ? ours.wall / anchor.wall : 0.0;
}

// Per iteration: the anchor once, then ours once.
template <class Ours, class Anchor>
void run_side_by_side(benchmark::State& state, Ours&& ours, Anchor&& anchor) {
  CallTime o, a;
  for (auto _ : state) {
    time_call(a, anchor);
    time_call(o, ours);
  }
  report_side_by_side(state, o, a);
}

inline double min_of(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

}  // namespace bench
