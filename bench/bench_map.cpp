// Mapping micro-benchmarks: FFM energy+gradient per tet, link-kernel LP, on generated Kuhn grids.
// The G1 success table is produced by bench/run_map_g1.sh + bench/summarise_map_g1.py (see there).
//
// Same-run anchors (bench/side_by_side.hpp: ours_ms, anchor_ms, ratio = ours/anchor, CPU time, min):
//   BM_FfmEnergyGradient_SideBySide  ours = FfmEnergy::evaluate (energy + gradient, as BM_FfmEnergyGradient);
//                                    anchor = a FLOOR, not the same quantity: a plain per-tet loop that
//                                    only forms J = (target edge matrix) * (source edge matrix).inverse()
//                                    with Eigen::Matrix3d and takes det(J) and |J|_F, the minimal work
//                                    any distortion energy needs (no barrier, no gradient).
//   BM_TlcEnergy_SideBySide          ours = volmap::tlc_lifted_content (value AND gradient dT) summed over
//                                    the tets, Tutte form a·(1 diagonal, 1/2 off), a = 1e-4; anchor =
//                                    the published formulation, VALUE ONLY: the lifted tet's volume from
//                                    its squared edge lengths |x_i - x_j|^2 + a (d_ij = 1) through the 5x5
//                                    Cayley-Menger determinant (Eigen, .determinant()), V = sqrt(det/288).
//                                    The two sums must agree to 1e-9 relative.
//   BM_LocalInfeasibility_SideBySide ours = find_local_infeasibility (every certificate kind, the
//                                    free-edge line LPs included) on an n³ Kuhn grid mapped onto
//                                    itself, boundary locked: a feasible map, so every search runs to
//                                    the end and finds nothing; anchor = one exact orient3d_tets pass
//                                    over the same tets (what any validity check costs). On this grid
//                                    few edges between free vertices have two fixed opposite edges, so
//                                    the free-edge LPs are a small part (24³: 11 ms, 36x the anchor,
//                                    the same within noise without them); on G1 scans the whole search
//                                    takes a median 0.08 s per case (mapping.md §10).
#include <benchmark/benchmark.h>

#include <volmap/core/local_tables.hpp>
#include <volmap/core/tet_mesh.hpp>
#include <volmap/volume/cone_repair.hpp>
#include <volmap/volume/infeasibility.hpp>
#include <volmap/volume/kernel_lp.hpp>
#include <volmap/volume/ffm.hpp>
#include <volmap/volume/tlc.hpp>

#include <Eigen/Dense>

#include "side_by_side.hpp"

#include "../tests/support/map_test_meshes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
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

// The FFM benchmarks' problem: an n³ Kuhn grid whose interior vertices are moved along x by
// 0.3·sin(id) (some tets inverted), its energy with the regular reference, variables and gradient.
struct FfmProblem {
  Grid g;
  std::vector<double> target;
  std::unique_ptr<volmap::FfmEnergy> energy;
  std::vector<double> x, grad;

  explicit FfmProblem(int n) : g(kuhn(n)), target(g.xyz) {
    for (std::size_t v = 0; v < g.bnd.size(); ++v)
      if (!g.bnd[v]) target[3 * v] += 0.3 * std::sin(double(v));
    energy = std::make_unique<volmap::FfmEnergy>(g.xyz, g.tets, g.bnd, target, volmap::ReferenceShape::RegularTet);
    x = energy->initial_variables();
    grad.resize(x.size());
  }
  double evaluate() { return energy->evaluate(x.data(), 0.1, grad.data()); }
};

void BM_FfmEnergyGradient(benchmark::State& state) {
  FfmProblem p(int(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(p.evaluate());
  state.counters["ns/tet"] = benchmark::Counter(double(p.g.tets.size() / 4), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
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

// Times cone_repair on copies of (mesh, boundary flags, target) (the copies are not timed) and
// reports what the last run did.
void time_cone_repair(benchmark::State& state, const volmap::TetMeshData& m0, const std::vector<std::uint8_t>& bnd0,
                      const std::vector<double>& target0) {
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
  state.counters["growth_steps"] = double(r.growth_steps);
  state.counters["max_region"] = double(r.max_region);
}

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
  time_cone_repair(state, m0, bnd0, target0);
}
BENCHMARK(BM_ConeRepairScattered)->Unit(benchmark::kMillisecond);

// B1 cone repair where the regions must grow far: in a 24^3 Kuhn grid, the interior vertices of
// a block of range(0)^3 cells have their x mirrored about the block's middle in the target, which
// inverts the block and tangles the ring around it. The repair grows one region over the block and
// beyond; most of the time goes to its growth steps (∂R, ball checks, LPs) and to re-inserting its
// interior vertices into the patch.
void BM_ConeRepairMirroredBlock(benchmark::State& state) {
  const int n = 24, b = int(state.range(0)), lo = (n - b) / 2, hi = lo + b;
  const volmap::TetMeshData m0 = map_test::kuhn_grid(n);
  const auto bnd0 = map_test::grid_boundary_flags(n);
  auto target0 = m0.xyz;
  const double mid = 0.5 * double(lo + hi) / n;
  for (std::size_t v = 0; v < m0.num_vertices(); ++v) {
    const double* p = &m0.xyz[3 * v];
    bool inside = true;
    for (int c = 0; c < 3; ++c) inside = inside && p[c] * n > lo + 0.5 && p[c] * n < hi - 0.5;
    if (inside) target0[3 * v] = 2 * mid - p[0];
  }
  time_cone_repair(state, m0, bnd0, target0);
}
BENCHMARK(BM_ConeRepairMirroredBlock)->Arg(4)->Arg(6)->Unit(benchmark::kMillisecond);

// ---- Same-run anchors ----------------------------------------------------------------------------

// Edge matrix of tet t as Eigen columns x_{k+1} - x_0.
Eigen::Matrix3d edge_matrix(const std::vector<double>& xyz, const std::uint32_t* tet) {
  Eigen::Matrix3d E;
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) E(i, k) = xyz[3 * std::size_t(tet[k + 1]) + std::size_t(i)] - xyz[3 * std::size_t(tet[0]) + std::size_t(i)];
  return E;
}

void BM_FfmEnergyGradient_SideBySide(benchmark::State& state) {
  FfmProblem p(int(state.range(0)));
  const Grid& g = p.g;
  const std::vector<double>& target = p.target;
  const std::size_t nt = g.tets.size() / 4;
  double floor_sum = 0;
  bench::run_side_by_side(
      state, [&] { benchmark::DoNotOptimize(p.evaluate()); },
      [&] {
        // Floor anchor: per tet J = T S^-1, det J and |J|_F (source S from the grid, target T).
        double s = 0;
        for (std::size_t t = 0; t < nt; ++t) {
          const std::uint32_t* tet = &g.tets[4 * t];
          const Eigen::Matrix3d J = edge_matrix(target, tet) * edge_matrix(g.xyz, tet).inverse();
          s += J.determinant() + J.norm();
        }
        floor_sum = s;
        benchmark::DoNotOptimize(floor_sum);
      });
  if (!std::isfinite(floor_sum)) return state.SkipWithError("floor anchor: non-finite Jacobians");
  state.counters["tets"] = double(nt);
}
BENCHMARK(BM_FfmEnergyGradient_SideBySide)->Arg(30)->Unit(benchmark::kMillisecond)->UseRealTime()->ComputeStatistics("min", bench::min_of);

void BM_LocalInfeasibility_SideBySide(benchmark::State& state) {
  const int n = int(state.range(0));
  const volmap::TetMeshData m = map_test::kuhn_grid(n);
  const volmap::TetMesh mesh(m);
  const std::vector<std::uint8_t> locked = map_test::grid_boundary_flags(n);
  std::vector<std::int8_t> signs(m.num_tets());
  std::size_t found = 0, nonpositive = 0;
  bench::run_side_by_side(
      state, [&] { found = volmap::find_local_infeasibility(mesh, locked, m.xyz).size(); },
      [&] {
        const auto counts = volmap::orient3d_tets(m.xyz.data(), m.num_vertices(), m.tets.data(), m.num_tets(), signs.data());
        nonpositive = counts.negative + counts.zero;
      });
  if (found != 0 || nonpositive != 0) return state.SkipWithError("the identity map must be valid and certificate-free");
  state.counters["tets"] = double(m.num_tets());
}
BENCHMARK(BM_LocalInfeasibility_SideBySide)->Arg(24)->Unit(benchmark::kMillisecond)->UseRealTime()->ComputeStatistics("min", bench::min_of);

// Lifted content of one tet from its lifted squared edge lengths (Cayley-Menger, value only).
double cayley_menger_lifted_volume(const std::vector<double>& xyz, const std::uint32_t* tet, double a) {
  Eigen::Matrix<double, 5, 5> CM;
  CM(0, 0) = 0;
  for (int i = 1; i < 5; ++i) CM(0, i) = CM(i, 0) = 1;
  for (int i = 0; i < 4; ++i) {
    CM(i + 1, i + 1) = 0;
    for (int j = i + 1; j < 4; ++j) {
      double d2 = 0;
      for (int c = 0; c < 3; ++c) {
        const double d = xyz[3 * std::size_t(tet[i]) + std::size_t(c)] - xyz[3 * std::size_t(tet[j]) + std::size_t(c)];
        d2 += d * d;
      }
      CM(i + 1, j + 1) = CM(j + 1, i + 1) = d2 + a;  // Tutte form: d_ij = 1
    }
  }
  return std::sqrt(std::max(CM.determinant() / 288.0, 0.0));
}

void BM_TlcEnergy_SideBySide(benchmark::State& state) {
  const int n = int(state.range(0));
  const Grid g = kuhn(n);
  // Interior vertices moved by up to 0.3 grid spacings (the lift keeps every content > 0 even if a tet flips).
  auto target = g.xyz;
  for (std::size_t v = 0; v < g.bnd.size(); ++v)
    if (!g.bnd[v])
      for (int c = 0; c < 3; ++c) target[3 * v + std::size_t(c)] += 0.3 / n * std::sin(double(3 * v + std::size_t(c)));
  const double a = 1e-4;
  double rest[9];
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) rest[3 * k + l] = a * (k == l ? 1.0 : 0.5);
  const std::size_t nt = g.tets.size() / 4;
  std::vector<double> dT(9 * nt);
  // Row-major target edge matrix: T[3 * i + k] = coordinate i of x_{k+1} - x_0.
  const auto target_edges = [&target](const std::uint32_t* tet, double* T) {
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k)
        T[3 * i + k] = target[3 * std::size_t(tet[k + 1]) + std::size_t(i)] - target[3 * std::size_t(tet[0]) + std::size_t(i)];
  };
  double ours_sum = 0, anchor_sum = 0;
  bench::run_side_by_side(
      state,
      [&] {
        double s = 0;
        for (std::size_t t = 0; t < nt; ++t) {
          const std::uint32_t* tet = &g.tets[4 * t];
          double T[9];
          target_edges(tet, T);
          s += volmap::tlc_lifted_content(T, rest, &dT[9 * t]);
        }
        ours_sum = s;
        benchmark::DoNotOptimize(ours_sum);
        benchmark::DoNotOptimize(dT.data());
      },
      [&] {
        double s = 0;
        for (std::size_t t = 0; t < nt; ++t) s += cayley_menger_lifted_volume(target, &g.tets[4 * t], a);
        anchor_sum = s;
        benchmark::DoNotOptimize(anchor_sum);
      });
  const double rel = std::abs(ours_sum - anchor_sum) / std::max(std::abs(anchor_sum), 1e-300);
  double worst_tet = 0;  // untimed: the largest per-tet relative difference
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint32_t* tet = &g.tets[4 * t];
    double T[9];
    target_edges(tet, T);
    const double o = volmap::tlc_lifted_content(T, rest, nullptr), c = cayley_menger_lifted_volume(target, tet, a);
    worst_tet = std::max(worst_tet, std::abs(o - c) / c);
  }
  state.counters["max_tet_rel_diff"] = worst_tet;
  state.counters["tets"] = double(nt);
  state.counters["content_sum"] = ours_sum;
  state.counters["rel_diff"] = rel;
  if (!(rel <= 1e-9)) return state.SkipWithError("Cayley-Menger anchor disagrees with tlc_lifted_content by > 1e-9 relative");
}
BENCHMARK(BM_TlcEnergy_SideBySide)->Arg(30)->Unit(benchmark::kMillisecond)->UseRealTime()->ComputeStatistics("min", bench::min_of);

}  // namespace
BENCHMARK_MAIN();
