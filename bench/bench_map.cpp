// Mapping micro-benchmarks: FFM energy+gradient per tet, link-kernel LP, on generated Kuhn grids.
// The G1 success table is produced by bench/run_map_g1.sh + bench/summarise_map_g1.py (see there).
#include <benchmark/benchmark.h>

#include <volmap/core/local_tables.hpp>
#include <volmap/volume/cone_repair.hpp>
#include <volmap/volume/kernel_lp.hpp>
#include <volmap/volume/ffm.hpp>

#include "../tests/support/map_test_meshes.hpp"

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace {

struct Grid {
  std::vector<double> xyz;
  std::vector<std::uint32_t> tets;
  std::vector<std::uint8_t> bnd;
};

// The library's unit-cube Kuhn grid (volmap/generate.hpp) with its boundary flags.
Grid kuhn(int n) {
  volmap::TetMeshData d = map_test::kuhn_grid(n);
  return {std::move(d.xyz), std::move(d.tets), map_test::grid_boundary_flags(n)};
}

void BM_FfmEnergyGradient(benchmark::State& state) {
  const Grid g = kuhn(int(state.range(0)));
  auto target = g.xyz;
  for (std::size_t v = 0; v < g.bnd.size(); ++v)
    if (!g.bnd[v]) target[3 * v] += 0.3 * std::sin(double(v));
  volmap::FfmEnergy E(g.xyz, g.tets, g.bnd, target, volmap::ReferenceShape::RegularTet);
  auto x = E.initial_variables();
  std::vector<double> grad(x.size());
  for (auto _ : state) benchmark::DoNotOptimize(E.evaluate(x.data(), 0.1, grad.data()));
  state.counters["ns/tet"] = benchmark::Counter(double(g.tets.size() / 4), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_FfmEnergyGradient)->Arg(10)->Arg(30)->Unit(benchmark::kMillisecond);

void BM_LinkKernelLP(benchmark::State& state) {
  // The link of the centre vertex of a 2×2×2 Kuhn grid (24 triangles).
  const Grid g = kuhn(2);
  std::vector<double> tri;
  const auto& F = volmap::kTetFace;
  for (std::size_t t = 0; t < g.tets.size() / 4; ++t)
    for (int i = 0; i < 4; ++i)
      if (g.tets[4 * t + i] == 13)
        for (int j = 0; j < 3; ++j)
          for (int c = 0; c < 3; ++c) tri.push_back(g.xyz[3 * g.tets[4 * t + F[i][j]] + c]);
  double q[3];
  for (auto _ : state) benchmark::DoNotOptimize(volmap::strict_kernel_point(tri, q));
}
BENCHMARK(BM_LinkKernelLP);

// B1 cone repair of a 24^3 Kuhn grid (82 944 tets) with 64 well-separated interior vertices
// scrambled in the target (each inverts part of its star): cluster search over every tet per round,
// region growth, kernel checks, vertex re-insertion. The copy of the inputs is not timed.
void BM_ConeRepairScattered(benchmark::State& state) {
  const int n = 24;
  const volmap::TetMeshData m0 = map_test::kuhn_grid(n);
  const auto bnd0 = map_test::grid_boundary_flags(n);
  auto target0 = m0.xyz;
  unsigned seed = 7;
  for (int i = 3; i < n; i += 6)
    for (int j = 3; j < n; j += 6)
      for (int k = 3; k < n; k += 6) {
        const std::size_t v = std::size_t((i * (n + 1) + j) * (n + 1) + k);
        for (int c = 0; c < 3; ++c) {
          seed = seed * 1103515245u + 12345u;
          target0[3 * v + c] += (double((seed >> 8) % 1000) / 1000.0 - 0.5) * 0.5 / (n / 6.0);
        }
      }
  volmap::ConeRepairResult r;
  for (auto _ : state) {
    state.PauseTiming();
    volmap::TetMeshData m = m0;
    auto bnd = bnd0;
    auto target = target0;
    state.ResumeTiming();
    r = volmap::cone_repair(m, bnd, target);
    benchmark::DoNotOptimize(target.data());
  }
  state.counters["clusters"] = double(r.clusters);
  state.counters["patches"] = double(r.patches);
  state.counters["failed"] = double(r.failed_clusters);
}
BENCHMARK(BM_ConeRepairScattered)->Unit(benchmark::kMillisecond);

}  // namespace
BENCHMARK_MAIN();
