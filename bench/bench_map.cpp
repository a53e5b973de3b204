// Mapping micro-benchmarks: FFM energy+gradient per tet, link-kernel LP, on generated Kuhn grids.
// The G1 success table is produced by bench/run_map_g1.sh + bench/summarise_map_g1.py (see there).
#include <benchmark/benchmark.h>

#include <volmap/cone_repair.hpp>
#include <volmap/ffm.hpp>

#include "../tests/map_test_meshes.hpp"

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
  static const int F[4][3] = {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}};
  for (std::size_t t = 0; t < g.tets.size() / 4; ++t)
    for (int i = 0; i < 4; ++i)
      if (g.tets[4 * t + i] == 13)
        for (int j = 0; j < 3; ++j)
          for (int c = 0; c < 3; ++c) tri.push_back(g.xyz[3 * g.tets[4 * t + F[i][j]] + c]);
  double q[3];
  for (auto _ : state) benchmark::DoNotOptimize(volmap::strict_kernel_point(tri, q));
}
BENCHMARK(BM_LinkKernelLP);

}  // namespace
BENCHMARK_MAIN();
