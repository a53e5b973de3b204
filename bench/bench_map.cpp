// Mapping micro-benchmarks: FFM energy+gradient per tet, link-kernel LP, on generated Kuhn grids.
// The G1 success table is produced by bench/run_map_g1.sh + bench/summarise_map_g1.py (see there).
#include <benchmark/benchmark.h>

#include <volmap/cone_repair.hpp>
#include <volmap/ffm.hpp>
#include <volmap/predicates.hpp>

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

Grid kuhn(int n) {
  Grid g;
  auto id = [n](int i, int j, int k) { return std::uint32_t((i * (n + 1) + j) * (n + 1) + k); };
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) {
        g.xyz.insert(g.xyz.end(), {double(i) / n, double(j) / n, double(k) / n});
        g.bnd.push_back(i == 0 || j == 0 || k == 0 || i == n || j == n || k == n);
      }
  static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        for (const auto& p : perms) {
          int c[3] = {i, j, k};
          std::uint32_t t[4];
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            c[p[s]] += 1;
            t[s + 1] = id(c[0], c[1], c[2]);
          }
          if (volmap::orient3d(&g.xyz[3 * t[0]], &g.xyz[3 * t[1]], &g.xyz[3 * t[2]], &g.xyz[3 * t[3]]) < 0) std::swap(t[2], t[3]);
          g.tets.insert(g.tets.end(), t, t + 4);
        }
  return g;
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
