// Half-face TetMesh benchmarks on Kuhn grids of ~24k, 750k and ~2M tets (datastructure.md §6
// targets: <= 40 B/tet core, 750k tets built in <= 0.1 s, all edge stars of 750k in <= 0.1 s).
// First prints one JSON line per mesh with best-of-N wall times and byte counts (core and caches
// separately; *_cpu_s = process CPU time over all threads), then runs the same operations as Google
// Benchmark cases.
// Usage: bench_mesh [--quick] [google-benchmark flags]
#include <benchmark/benchmark.h>

#include <volmap/surface/boundary_surface.hpp>
#include <volmap/testing/generate.hpp>
#include <volmap/io/io.hpp>
#include <volmap/core/local_tables.hpp>
#include <volmap/core/tet_mesh.hpp>
#include <volmap/core/topology.hpp>

#include "side_by_side.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <map>
#include <string>
#include <memory>

using namespace volmap;

namespace {

const TetMeshData& grid(std::size_t n) {
  static std::map<std::size_t, std::unique_ptr<TetMeshData>> cache;
  auto& p = cache[n];
  if (!p) p = std::make_unique<TetMeshData>(generate_kuhn_grid(n, n, n));
  return *p;
}

double cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// Best-of-reps wall time; the process CPU time (all threads) of that rep is kept in last_cpu (on a
// shared machine the wall time includes waiting for a core, the CPU time does not).
double last_cpu = 0;
template <class F>
double best_seconds(int reps, F&& f) {
  double best = 1e300;
  for (int r = 0; r < reps; ++r) {
    const double c0 = cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    f();
    const auto t1 = std::chrono::steady_clock::now();
    const double c1 = cpu_seconds();
    const double wall = std::chrono::duration<double>(t1 - t0).count();
    if (wall < best) {
      best = wall;
      last_cpu = c1 - c0;
    }
  }
  return best;
}

// Walks the star of every edge once (edge ids from the cache); returns the sum of degrees.
std::size_t walk_all_edge_stars(const TetMesh& m) {
  std::size_t total = 0;
  const std::size_t ne = m.num_edges();
  for (std::uint32_t e = 0; e < ne; ++e) m.edge_star(EdgeId(e), [&total](TetId) { ++total; });
  return total;
}

void report(std::size_t n, int reps) {
  const TetMeshData& d = grid(n);
  std::unique_ptr<TetMesh> m;
  const double build = best_seconds(reps, [&] { m = std::make_unique<TetMesh>(d); });
  const double build_cpu = last_cpu;
  const double nt = double(m->num_tets());
  const std::size_t core = m->core_bytes();
  const double edge_cache = best_seconds(reps, [&] { m->clear_caches(); (void)m->num_edges(); });
  std::size_t degree_sum = 0;
  const double stars = best_seconds(reps, [&] { degree_sum = walk_all_edge_stars(*m); });
  const double stars_cpu = last_cpu;
  const std::size_t edge_bytes = m->cache_bytes();
  m->clear_caches();
  const double vt = best_seconds(reps, [&] { m->clear_caches(); (void)m->vertex_tets(VertexId(0)); });
  const std::size_t vt_bytes = m->cache_bytes();
  const double bnd = best_seconds(reps, [&] { m->clear_caches(); (void)m->boundary_half_faces(); });
  const std::size_t bnd_bytes = m->cache_bytes();
  std::size_t surface_faces = 0;
  const double surface = best_seconds(reps, [&] { surface_faces = extract_boundary_surface(*m).mesh.n_faces(); });
  TopologyReport topo;
  const double topology = best_seconds(reps, [&] { topo = analyze_topology(d); });
  std::printf("{\"bench\":\"mesh\",\"grid\":%zu,\"vertices\":%zu,\"tets\":%zu,\"edges\":%zu,", n, m->num_vertices(),
              m->num_tets(), m->num_edges());
  std::printf("\"build_s\":%.4f,\"build_cpu_s\":%.4f,\"build_cpu_ns_per_tet\":%.1f,\"core_bytes_per_tet\":%.2f,", build,
              build_cpu, 1e9 * build_cpu / nt, double(core) / nt);
  std::printf("\"edge_cache_build_s\":%.4f,\"edge_cache_bytes_per_tet\":%.2f,", edge_cache, double(edge_bytes) / nt);
  std::printf("\"all_edge_stars_s\":%.4f,\"all_edge_stars_cpu_s\":%.4f,\"edge_star_degree_sum\":%zu,", stars, stars_cpu,
              degree_sum);
  std::printf("\"vertex_tets_cache_s\":%.4f,\"vertex_tets_bytes_per_tet\":%.2f,", vt, double(vt_bytes) / nt);
  std::printf("\"boundary_list_s\":%.5f,\"boundary_list_bytes_per_tet\":%.3f,", bnd, double(bnd_bytes) / nt);
  std::printf("\"boundary_surface_s\":%.4f,\"boundary_faces\":%zu,\"analyze_topology_s\":%.4f,\"genus\":%lld}\n",
              surface, surface_faces, topology, topo.boundary_genus);
  std::fflush(stdout);
}

void BM_Build(benchmark::State& st) {
  const TetMeshData& d = grid(std::size_t(st.range(0)));
  for (auto _ : st) {
    TetMesh m(d);
    benchmark::DoNotOptimize(m.opposite_array().data());
  }
  st.counters["tets"] = double(d.num_tets());
  st.counters["ns_per_tet"] = benchmark::Counter(double(d.num_tets()), benchmark::Counter::kIsIterationInvariantRate |
                                                                          benchmark::Counter::kInvert);
}

// Anchor of the half-face build: a plain vector-of-vectors mesh, the way a textbook (or cinolib-style)
// code finds face neighbours: per-vertex lists of incident tets, then for every face of every tet the
// tet sharing it, found in the list of the face's first vertex. Result: the opposite half-face 4u + j
// (or -1 on the boundary) of every half-face, as TetMesh's opposite array.
struct PlainMesh {
  std::vector<std::vector<std::uint32_t>> vertex_tets;
  std::vector<std::int64_t> opposite;
};
PlainMesh plain_mesh_build(const TetMeshData& d) {
  PlainMesh m;
  const std::size_t nt = d.num_tets();
  const std::uint32_t* tets = d.tets.data();
  m.vertex_tets.resize(d.num_vertices());
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 4; ++k) m.vertex_tets[tets[4 * t + k]].push_back(std::uint32_t(t));
  m.opposite.assign(4 * nt, -1);
  for (std::size_t t = 0; t < nt; ++t)
    for (int f = 0; f < 4; ++f) {
      const std::uint32_t a = tets[4 * t + kTetFace[f][0]], b = tets[4 * t + kTetFace[f][1]], c = tets[4 * t + kTetFace[f][2]];
      for (std::uint32_t u : m.vertex_tets[a]) {
        if (u == t) continue;
        const std::uint32_t* q = tets + 4 * std::size_t(u);
        int shared = 0, other = 0;
        for (int j = 0; j < 4; ++j) {
          const bool in_face = q[j] == a || q[j] == b || q[j] == c;
          shared += in_face;
          if (!in_face) other = j;
        }
        if (shared == 3) {
          m.opposite[4 * t + f] = std::int64_t(4 * std::size_t(u) + other);
          break;
        }
      }
    }
  return m;
}

// TetMesh(data) next to the plain build, alternately in one loop (side_by_side.hpp); fails unless
// both find the same face pairs.
void BM_Build_SideBySide(benchmark::State& st) {
  const TetMeshData& d = grid(std::size_t(st.range(0)));
  std::unique_ptr<TetMesh> ours;
  PlainMesh plain;
  bench::run_side_by_side(
      st, [&] { ours = std::make_unique<TetMesh>(d); }, [&] { plain = plain_mesh_build(d); });
  const auto& opp = ours->opposite_array();
  std::size_t mismatches = 0;
  for (std::size_t h = 0; h < opp.size(); ++h)
    mismatches += plain.opposite[h] < 0 ? opp[h] != TetMesh::kBoundary : opp[h] != std::uint32_t(plain.opposite[h]);
  if (mismatches != 0) st.SkipWithError("the plain build found other face pairs");
  st.counters["tets"] = double(d.num_tets());
}

void BM_AllEdgeStars(benchmark::State& st) {
  const TetMesh m(grid(std::size_t(st.range(0))));
  (void)m.num_edges();
  for (auto _ : st) benchmark::DoNotOptimize(walk_all_edge_stars(m));
  st.counters["edges"] = double(m.num_edges());
}

void BM_EdgeCache(benchmark::State& st) {
  const TetMesh m(grid(std::size_t(st.range(0))));
  for (auto _ : st) {
    m.clear_caches();
    benchmark::DoNotOptimize(m.num_edges());
  }
}

void BM_BoundarySurface(benchmark::State& st) {
  const TetMesh m(grid(std::size_t(st.range(0))));
  for (auto _ : st) {
    m.clear_caches();
    auto s = extract_boundary_surface(m);
    benchmark::DoNotOptimize(s.mesh.n_faces());
  }
}

void BM_AnalyzeTopology(benchmark::State& st) {
  const TetMeshData& d = grid(std::size_t(st.range(0)));
  for (auto _ : st) benchmark::DoNotOptimize(analyze_topology(d).num_faces);
}

// check_invariants without (arg 0) and with (arg 1) the exact positivity pass over every tet: the
// difference is the pass alone (scalar orient3d per tet inside one FpEnvironmentScope).
void BM_CheckInvariants(benchmark::State& st) {
  const TetMesh m(grid(std::size_t(st.range(0))));
  for (auto _ : st) benchmark::DoNotOptimize(m.check_invariants(st.range(1) != 0).ok);
}

}  // namespace

// Grid sizes: 16^3*6 = 24 576, 50^3*6 = 750 000, 70^3*6 = 2 058 000 tets.
BENCHMARK(BM_Build)->Arg(16)->Arg(50)->Arg(70)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Build_SideBySide)->Arg(50)->Unit(benchmark::kMillisecond)->UseRealTime()->ComputeStatistics("min", bench::min_of);
BENCHMARK(BM_AllEdgeStars)->Arg(16)->Arg(50)->Arg(70)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EdgeCache)->Arg(16)->Arg(50)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BoundarySurface)->Arg(16)->Arg(50)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AnalyzeTopology)->Arg(16)->Arg(50)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CheckInvariants)->Args({50, 0})->Args({50, 1})->Unit(benchmark::kMillisecond);

// Real meshes from ../shared/data (skipped when absent): read, build, topology, boundary surface.
void report_real(const char* relative, int reps) {
  const std::string path = std::string(VOLMAP_DATA_DIR) + "/" + relative;
  if (std::FILE* f = std::fopen(path.c_str(), "rb")) std::fclose(f);
  else return;
  TetMeshData d;
  const double read = best_seconds(reps, [&] { d = read_medit(path); });
  std::unique_ptr<TetMesh> m;
  const double build = best_seconds(reps, [&] { m = std::make_unique<TetMesh>(d); });
  const double build_cpu = last_cpu;
  TopologyReport topo;
  const double topology = best_seconds(reps, [&] { topo = analyze_topology(d); });
  const double topology_cpu = last_cpu;
  const double surface = best_seconds(reps, [&] { m->clear_caches(); (void)extract_boundary_surface(*m); });
  std::printf("{\"bench\":\"mesh_real\",\"file\":\"%s\",\"vertices\":%zu,\"tets\":%zu,\"read_s\":%.4f,", relative,
              d.num_vertices(), d.num_tets(), read);
  std::printf("\"build_s\":%.4f,\"build_cpu_s\":%.4f,\"core_bytes_per_tet\":%.2f,\"analyze_topology_s\":%.4f,",
              build, build_cpu, double(m->core_bytes()) / double(m->num_tets()), topology);
  std::printf("\"analyze_topology_cpu_s\":%.4f,\"boundary_surface_s\":%.4f,\"genus\":%lld}\n", topology_cpu, surface,
              topo.boundary_genus);
  std::fflush(stdout);
}

int main(int argc, char** argv) {
  bool quick = false;
  int out = 1;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0) quick = true;
    else argv[out++] = argv[i];
  }
  argc = out;
  for (std::size_t n : {std::size_t(16), std::size_t(50), std::size_t(70)}) report(n, quick ? 1 : 3);
  report_real("volmap/G1/bunny.mesh", quick ? 1 : 3);
  report_real("volmap/G1/bone.mesh", quick ? 1 : 3);
  if (quick) return 0;
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
