// Volume-map benchmarks: Tutte 3D (edges / assembly / factorisation / solve separately; SimplicialLLT
// vs SimplicialLDLT vs ConjugateGradient — CHOLMOD is not installed here, so it is not compared) on
// G1 meshes and on a generated Kuhn grid of >= 1M tets; the exact map check in ns/tet (and per
// degenerate tet); the metrics per tet. Real data is read in place from ../shared/data (skipped when
// absent). Counters: *_ms are per-iteration averages; ns_per_tet = wall time / tets.
#include <benchmark/benchmark.h>
#include <volmap/io.hpp>
#include <volmap/map_check.hpp>
#include <volmap/metrics.hpp>
#include <volmap/predicates.hpp>
#include <volmap/tutte3d.hpp>

#include "../tests/vmap_test_util.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>

using namespace volmap;
namespace fs = std::filesystem;

namespace {

const fs::path kData = VOLMAP_DATA_DIR;

const char* factorization_name(SparseFactorization f) {
  switch (f) {
    case SparseFactorization::LLT: return "SimplicialLLT";
    case SparseFactorization::LDLT: return "SimplicialLDLT";
    case SparseFactorization::ConjugateGradient: return "ConjugateGradient";
  }
  return "?";
}

struct MeshAndMap {
  TetMeshData mesh;
  BoundaryMap map;
};

// Kuhn grid n³ (6n³ tets, VOLMAP-positive) with the boundary fixed at a smooth deformation.
MeshAndMap kuhn_problem(int n) {
  MeshAndMap p;
  p.mesh = vmap_test::kuhn_grid(n);
  const int s = n + 1;
  for (std::size_t v = 0; v < p.mesh.num_vertices(); ++v) {
    const int i = int(v % s), j = int((v / s) % s), k = int(v / (std::size_t(s) * s));
    if (i == 0 || j == 0 || k == 0 || i == n || j == n || k == n) {
      const double* x = &p.mesh.xyz[3 * v];
      p.map.vids.push_back(std::uint32_t(v));
      p.map.xyz.insert(p.map.xyz.end(), {100 * x[0] + 10 * std::sin(3 * x[1]), 100 * x[1] + 10 * x[2] * x[0],
                                         100 * x[2] - 5 * std::cos(2 * x[0])});
    }
  }
  return p;
}

const MeshAndMap& g1_problem(const std::string& name, const std::string& domain) {
  static std::map<std::string, MeshAndMap> cache;
  const std::string key = name + "_" + domain;
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  MeshAndMap p;
  p.mesh = read_medit((kData / "volmap/G1" / (name + ".mesh")).string());
  p.map = read_boundary_map((kData / ("volmap/G1_" + domain) / (key + ".txt")).string());
  return cache.emplace(key, std::move(p)).first->second;
}

const MeshAndMap& kuhn_cached(int n) {
  static std::map<int, MeshAndMap> cache;
  auto it = cache.find(n);
  if (it != cache.end()) return it->second;
  return cache.emplace(n, kuhn_problem(n)).first->second;
}

void run_tutte(benchmark::State& state, const MeshAndMap& p, SparseFactorization f) {
  Tutte3dOptions options;
  options.factorization = f;
  Tutte3dTimings sum;
  std::size_t inverted = 0;
  for (auto _ : state) {
    const Tutte3dResult r = tutte3d(p.mesh, p.map, options);
    sum.edges += r.timings.edges;
    sum.assembly += r.timings.assembly;
    sum.factorization += r.timings.factorization;
    sum.solve += r.timings.solve;
    state.PauseTiming();
    const TetSignCounts c = orient3d_tets(r.xyz.data(), p.mesh.num_vertices(), p.mesh.tets.data(), p.mesh.num_tets(), nullptr);
    inverted = c.zero + c.negative;
    state.ResumeTiming();
  }
  const double n = double(state.iterations());
  state.counters["tets"] = double(p.mesh.num_tets());
  state.counters["free_vertices"] = double(p.mesh.num_vertices() - p.map.vids.size());
  state.counters["edges_ms"] = 1e3 * sum.edges / n;
  state.counters["assembly_ms"] = 1e3 * sum.assembly / n;
  state.counters["factor_ms"] = 1e3 * sum.factorization / n;
  state.counters["solve_ms"] = 1e3 * sum.solve / n;
  state.counters["inverted"] = double(inverted);
  state.SetLabel(factorization_name(f));
}

void BM_Tutte3d_G1(benchmark::State& state, std::string name, SparseFactorization f) {
  if (!fs::exists(kData / "volmap/G1" / (name + ".mesh"))) {
    state.SkipWithError("../shared/data absent");
    return;
  }
  run_tutte(state, g1_problem(name, "cube"), f);
}

void BM_Tutte3d_Kuhn(benchmark::State& state, SparseFactorization f) {
  run_tutte(state, kuhn_cached(int(state.range(0))), f);
}

struct Pair {
  TetMeshData in, out;
};
const Pair* viewer_pair(const std::string& name) {
  static std::map<std::string, Pair> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return &it->second;
  const fs::path dir = kData / "volmap/viewer-samples";
  if (!fs::exists(dir / (name + "_input.mesh"))) return nullptr;
  Pair p{read_medit((dir / (name + "_input.mesh")).string()), read_medit((dir / (name + "_output.mesh")).string())};
  return &cache.emplace(name, std::move(p)).first->second;
}

// Full exact check (input and output signs, pairing, relative comparison), TBB-parallel.
void BM_MapCheck(benchmark::State& state, std::string name, bool parallel) {
  const Pair* p = viewer_pair(name);
  if (!p) {
    state.SkipWithError("../shared/data absent");
    return;
  }
  MapCheckOptions o;
  o.parallel = parallel;
  for (auto _ : state) benchmark::DoNotOptimize(check_map(p->in, p->out, nullptr, o).num_bad);
  state.counters["tets"] = double(p->in.num_tets());
  state.counters["ns_per_tet"] = benchmark::Counter(double(p->in.num_tets()) * 1e-9,
                                                    benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// One serial batch orientation pass (the predicate engine alone).
void BM_Orient3dTets(benchmark::State& state, std::string name) {
  const Pair* p = viewer_pair(name);
  if (!p) {
    state.SkipWithError("../shared/data absent");
    return;
  }
  for (auto _ : state)
    benchmark::DoNotOptimize(
        orient3d_tets(p->out.xyz.data(), p->out.num_vertices(), p->in.tets.data(), p->in.num_tets(), nullptr).positive);
  state.counters["ns_per_tet"] = benchmark::Counter(double(p->in.num_tets()) * 1e-9,
                                                    benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// Every tet exactly degenerate (Kuhn grid flattened onto the plane x = y, so no coordinate is constant):
// the cost of the exact fallback per degenerate tet.
void BM_MapCheck_AllDegenerate(benchmark::State& state) {
  const int n = int(state.range(0));
  const TetMeshData in = vmap_test::kuhn_grid(n);
  TetMeshData out = in;
  for (std::size_t v = 0; v < out.num_vertices(); ++v) out.xyz[3 * v] = out.xyz[3 * v + 1];
  std::size_t zero = 0;
  for (auto _ : state) zero = check_map(in, out).output.zero;
  state.counters["degenerate"] = double(zero);
  state.counters["us_per_degenerate_tet"] = benchmark::Counter(double(zero) * 1e-6,
                                                               benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_Metrics(benchmark::State& state, std::string name) {
  const Pair* p = viewer_pair(name);
  if (!p) {
    state.SkipWithError("../shared/data absent");
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(compute_metrics(p->in, p->out).energy[0].mean);
  state.counters["ns_per_tet"] = benchmark::Counter(double(p->in.num_tets()) * 1e-9,
                                                    benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// End to end like the tool: parse both files + metrics (VOLMAP's metrics: 0.78 s on this pair).
void BM_Metrics_EndToEnd(benchmark::State& state, std::string name) {
  const fs::path dir = kData / "volmap/viewer-samples";
  if (!fs::exists(dir / (name + "_input.mesh"))) {
    state.SkipWithError("../shared/data absent");
    return;
  }
  for (auto _ : state) {
    const TetMeshData in = read_medit((dir / (name + "_input.mesh")).string());
    const TetMeshData out = read_medit((dir / (name + "_output.mesh")).string());
    benchmark::DoNotOptimize(compute_metrics(in, out).energy[0].mean);
  }
}

}  // namespace

#define TUTTE_G1(name)                                                                                  \
  BENCHMARK_CAPTURE(BM_Tutte3d_G1, name##_LLT, #name, SparseFactorization::LLT)->Unit(benchmark::kMillisecond); \
  BENCHMARK_CAPTURE(BM_Tutte3d_G1, name##_LDLT, #name, SparseFactorization::LDLT)->Unit(benchmark::kMillisecond); \
  BENCHMARK_CAPTURE(BM_Tutte3d_G1, name##_CG, #name, SparseFactorization::ConjugateGradient)->Unit(benchmark::kMillisecond);
TUTTE_G1(bone)
TUTTE_G1(duck)
TUTTE_G1(bunny)
TUTTE_G1(buste)

// n = 56: 6·56³ = 1,053,696 tets.
BENCHMARK_CAPTURE(BM_Tutte3d_Kuhn, LLT, SparseFactorization::LLT)->Arg(20)->Arg(56)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Tutte3d_Kuhn, LDLT, SparseFactorization::LDLT)->Arg(20)->Arg(56)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Tutte3d_Kuhn, CG, SparseFactorization::ConjugateGradient)->Arg(20)->Arg(56)->Iterations(1)->Unit(benchmark::kMillisecond);

BENCHMARK_CAPTURE(BM_MapCheck, bunny_parallel, "bunny", true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MapCheck, bunny_serial, "bunny", false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MapCheck, duck_parallel, "duck", true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Orient3dTets, bunny_output, "bunny")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MapCheck_AllDegenerate)->Arg(10)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Metrics, bunny, "bunny")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Metrics, duck, "duck")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Metrics_EndToEnd, bunny, "bunny")->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
