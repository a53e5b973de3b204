// Volume-map benchmarks: Tutte 3D (edges / assembly / factorisation / solve separately; SimplicialLLT
// vs SimplicialLDLT vs ConjugateGradient — CHOLMOD is not installed here, so it is not compared) on
// G1 meshes and on a generated Kuhn grid of >= 1M tets; the exact map check in ns/tet (and per
// degenerate tet); the metrics per tet. Real data is read in place from ../shared/data (skipped when
// absent). Counters: *_ms are per-iteration averages; ns_per_tet = wall time / tets.
#include <benchmark/benchmark.h>
#include <volmap/io/io.hpp>
#include <volmap/check/map_check.hpp>
#include <volmap/check/metrics.hpp>
#include <volmap/predicates.hpp>
#include <volmap/volume/tutte3d.hpp>

#include "../tests/support/vmap_test_util.hpp"
#include "anchor_volmap_metrics.hpp"
#include "side_by_side.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
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

// ---- The map check in ns/tet, excluding parsing: on the viewer bunny pair (98,840 tets) and on a
// generated Kuhn grid of 6·56³ = 1,053,696 tets with a smooth valid deformation. In one run, so the
// ratios are comparable on a loaded machine (all times are wall clock):
//   PlainDet      the anchor: the naive double determinant of input and output tets, counting signs
//                 (NOT exact; what an uncertified check would cost), one thread;
//   TwoPasses     two serial orient3d_tets passes (input, output), each with its O(V) census;
//   BlockedPasses the same per block of 8192 tets, each mesh's census once (check_map's inner work);
//   MapCheck      the whole volmap::check_map (connectivity, census, fused signs, report),
//                 /0 = one thread, /1 = all TBB workers.
struct CheckCase {
  TetMeshData in, out;
};
const CheckCase* check_case(const std::string& name) {
  static std::map<std::string, CheckCase> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return &it->second;
  CheckCase c;
  if (name == "grid56") {
    c.in = vmap_test::kuhn_grid(56);
    c.out = c.in;
    // x + 0.03·(sin 2y, sin 2z, sin 2x): Jacobian I + (entries ≤ 0.06), every tet stays positive.
    for (std::size_t v = 0; v < c.in.num_vertices(); ++v) {
      const double* p = &c.in.xyz[3 * v];
      double* q = &c.out.xyz[3 * v];
      q[0] = 100 * (p[0] + 0.03 * std::sin(2 * p[1]));
      q[1] = 100 * (p[1] + 0.03 * std::sin(2 * p[2]));
      q[2] = 100 * (p[2] + 0.03 * std::sin(2 * p[0]));
    }
  } else {
    const Pair* p = viewer_pair(name);
    if (!p) return nullptr;
    c.in = p->in;
    c.out = p->out;
  }
  return &cache.emplace(name, std::move(c)).first->second;
}

void set_ns_per_tet(benchmark::State& state, std::size_t tets) {
  state.counters["tets"] = double(tets);
  state.counters["ns_per_tet"] =
      benchmark::Counter(double(tets) * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

std::size_t plain_det_positive(const double* xyz, const std::uint32_t* tets, std::size_t nt) {
  std::size_t positive = 0;
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint32_t* v = tets + 4 * t;
    const double *a = xyz + 3 * v[0], *b = xyz + 3 * v[1], *c = xyz + 3 * v[2], *d = xyz + 3 * v[3];
    const double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
    const double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
    const double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
    positive += adz * (bdx * cdy - cdx * bdy) + bdz * (cdx * ady - adx * cdy) + cdz * (adx * bdy - bdx * ady) > 0;
  }
  return positive;
}

// Times `body(case)` per iteration on the named case; reports ns per tet.
template <class Body>
void run_check_case(benchmark::State& state, const std::string& name, Body body) {
  const CheckCase* c = check_case(name);
  if (!c) return state.SkipWithError("../shared/data absent");
  for (auto _ : state) body(*c);
  set_ns_per_tet(state, c->in.num_tets());
}

void BM_Check_PlainDet(benchmark::State& state, std::string name) {
  run_check_case(state, name, [](const CheckCase& c) {
    benchmark::DoNotOptimize(plain_det_positive(c.in.xyz.data(), c.in.tets.data(), c.in.num_tets()));
    benchmark::DoNotOptimize(plain_det_positive(c.out.xyz.data(), c.in.tets.data(), c.in.num_tets()));
  });
}

void BM_Check_TwoPasses(benchmark::State& state, std::string name) {
  run_check_case(state, name, [](const CheckCase& c) {
    const std::size_t nt = c.in.num_tets(), nv = c.in.num_vertices();
    benchmark::DoNotOptimize(orient3d_tets(c.in.xyz.data(), nv, c.in.tets.data(), nt, nullptr).positive);
    benchmark::DoNotOptimize(orient3d_tets(c.out.xyz.data(), nv, c.in.tets.data(), nt, nullptr).positive);
  });
}

// Two passes over blocks of 8192 tets with the census hoisted (what check_map does per block).
void BM_Check_BlockedPasses(benchmark::State& state, std::string name) {
  run_check_case(state, name, [](const CheckCase& c) {
    const std::size_t nt = c.in.num_tets(), nv = c.in.num_vertices();
    const Orient3dBatchFilter fi = orient3d_batch_filter(c.in.xyz.data(), nv);
    const Orient3dBatchFilter fo = orient3d_batch_filter(c.out.xyz.data(), nv);
    std::size_t positive = 0;
    for (std::size_t first = 0; first < nt; first += 8192) {
      const std::size_t count = std::min<std::size_t>(8192, nt - first);
      positive += orient3d_tets(fi, c.in.xyz.data(), nv, c.in.tets.data() + 4 * first, count, nullptr).positive;
      positive += orient3d_tets(fo, c.out.xyz.data(), nv, c.in.tets.data() + 4 * first, count, nullptr).positive;
    }
    benchmark::DoNotOptimize(positive);
  });
}

void BM_Check_MapCheck(benchmark::State& state, std::string name) {
  MapCheckOptions o;
  o.parallel = state.range(0) != 0;
  std::size_t bad = 0;
  run_check_case(state, name, [&](const CheckCase& c) { bad += check_map(c.in, c.out, nullptr, o).num_bad; });
  if (bad != 0) state.SkipWithError("the map should be valid");
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

// ---- Metrics side by side with VOLMAP's `metrics` (anchor_volmap_metrics.hpp: its algorithm, cinolib
// reader and per-tet allocations, re-implemented for benchmarking only). Both sides run in the same
// loop (side_by_side.hpp); ratio = ours / VOLMAP in process CPU time.
//   Metrics          the computation alone (meshes already in memory, each side in its own layout);
//   Metrics_EndToEnd what the tools do: parse both .mesh files, compute, format the text block; the
//                    case fails unless both print the same block (VOLMAP's digits, volmap-reference.md §9).
// The whole executables: `bench_volume_maps --volmap-metrics-anchor in.mesh out.mesh` runs the
// anchor alone as a process (for /usr/bin/time -v next to `volmap-metrics in.mesh out.mesh`).
struct AnchorPair {
  anchor::VolmapMesh in, out;
};
const AnchorPair* anchor_pair(const std::string& name) {
  static std::map<std::string, AnchorPair> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return &it->second;
  const fs::path dir = kData / "volmap/viewer-samples";
  AnchorPair p;
  if (!anchor::read_mesh_like_cinolib((dir / (name + "_input.mesh")).c_str(), p.in) ||
      !anchor::read_mesh_like_cinolib((dir / (name + "_output.mesh")).c_str(), p.out))
    return nullptr;
  return &cache.emplace(name, std::move(p)).first->second;
}

void BM_Metrics(benchmark::State& state, std::string name) {
  const Pair* p = viewer_pair(name);
  const AnchorPair* a = p ? anchor_pair(name) : nullptr;
  if (!a) return state.SkipWithError("../shared/data absent");
  bench::run_side_by_side(
      state, [&] { benchmark::DoNotOptimize(compute_metrics(p->in, p->out).energy[0].mean); },
      [&] { benchmark::DoNotOptimize(anchor::volmap_metrics(a->in, a->out, 100.0).energy[0][2]); });
  state.counters["tets"] = double(p->in.num_tets());
}

void BM_Metrics_EndToEnd(benchmark::State& state, std::string name) {
  const fs::path dir = kData / "volmap/viewer-samples";
  const std::string in_path = (dir / (name + "_input.mesh")).string(), out_path = (dir / (name + "_output.mesh")).string();
  if (!fs::exists(in_path)) return state.SkipWithError("../shared/data absent");
  std::string ours_text, anchor_text;
  bench::run_side_by_side(
      state,
      [&] {
        const TetMeshData in = read_medit(in_path);
        const TetMeshData out = read_medit(out_path);
        ours_text = format_metrics_volmap(compute_metrics(in, out));
      },
      [&] {
        anchor::VolmapMesh in, out;
        anchor::read_mesh_like_cinolib(in_path.c_str(), in);
        anchor::read_mesh_like_cinolib(out_path.c_str(), out);
        anchor_text = anchor::format_volmap(anchor::volmap_metrics(in, out, 100.0));
      });
  if (ours_text != anchor_text) state.SkipWithError(("printed blocks differ:\n" + ours_text + "VOLMAP:\n" + anchor_text).c_str());
}

// The anchor as a process: prints VOLMAP's block for in.mesh -> out.mesh (exit 2 if unreadable).
int run_anchor_process(const char* in_path, const char* out_path) {
  anchor::VolmapMesh in, out;
  if (!anchor::read_mesh_like_cinolib(in_path, in) || !anchor::read_mesh_like_cinolib(out_path, out)) return 2;
  std::fputs(anchor::format_volmap(anchor::volmap_metrics(in, out, 100.0)).c_str(), stdout);
  return 0;
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

// n = 56: 6·56³ = 1,053,696 tets (166,375 free vertices). The simplicial Cholesky factorisations of a
// 3D grid Laplacian fill in heavily (nested-dissection-like fronts of ~n² unknowns): at n = 56 LLT ran
// > 13 min (1.2 GB) on this shared 2-core machine without finishing, so the direct solvers stop at
// n = 32 (196,608 tets); conjugate gradient runs the 1M-tet grid.
BENCHMARK_CAPTURE(BM_Tutte3d_Kuhn, LLT, SparseFactorization::LLT)->Arg(20)->Arg(32)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Tutte3d_Kuhn, LDLT, SparseFactorization::LDLT)->Arg(20)->Arg(32)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Tutte3d_Kuhn, CG, SparseFactorization::ConjugateGradient)->Arg(20)->Arg(32)->Arg(56)->Iterations(1)->Unit(benchmark::kMillisecond);

// On a loaded machine the minimum over repetitions is the least disturbed figure: run with
// --benchmark_repetitions=N to get a "_min" row next to mean/median.
double min_of(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }
#define CHECK_BENCH(fn, name) \
  BENCHMARK_CAPTURE(fn, name, #name)->Unit(benchmark::kMillisecond)->UseRealTime()->ComputeStatistics("min", min_of)
#define CHECK_CASE(name)                           \
  CHECK_BENCH(BM_Check_PlainDet, name);            \
  CHECK_BENCH(BM_Check_TwoPasses, name);           \
  CHECK_BENCH(BM_Check_BlockedPasses, name);       \
  CHECK_BENCH(BM_Check_MapCheck, name)->Arg(0)->Arg(1);
CHECK_CASE(bunny)
CHECK_CASE(grid56)
BENCHMARK(BM_MapCheck_AllDegenerate)->Arg(10)->Unit(benchmark::kMillisecond);
#define SIDE_BY_SIDE(fn, name) \
  BENCHMARK_CAPTURE(fn, name, #name)->Unit(benchmark::kMillisecond)->UseRealTime()->ComputeStatistics("min", bench::min_of)
SIDE_BY_SIDE(BM_Metrics, bunny);
SIDE_BY_SIDE(BM_Metrics, duck);
SIDE_BY_SIDE(BM_Metrics_EndToEnd, bunny);

int main(int argc, char** argv) {
  if (argc == 4 && std::string(argv[1]) == "--volmap-metrics-anchor") return run_anchor_process(argv[2], argv[3]);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
