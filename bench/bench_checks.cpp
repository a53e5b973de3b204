// bench_checks — the seven VOLMAP checks on G1 bunny (65,694 tets): the tool-equivalent pipeline
// (parse .mesh + all checks; VOLMAP's tetmesh_checks takes 2.2 s here, target >= 20x faster) and its
// parts: exact orientation of every tet, topology, boundary self-intersection (parallel and serial).
// Times are wall clock (UseRealTime) with the process CPU time of all threads alongside.
// Reads ../shared/data in place; skips (with a message) when it is absent.
#include <benchmark/benchmark.h>

#include <volmap/io/io.hpp>
#include <volmap/core/local_tables.hpp>
#include <volmap/check/self_intersection.hpp>
#include <volmap/check/tetmesh_checks.hpp>
#include <volmap/core/topology.hpp>

#include <filesystem>
#include <string>

namespace {

std::string data_path(const std::string& relative) {
  const char* env = std::getenv("VOLMAP_DATA");
  const std::filesystem::path root = env && *env ? env : VOLMAP_DATA_DIR;
  const auto p = root / relative;
  return std::filesystem::exists(p) ? p.string() : std::string();
}

const volmap::TetMeshData* bunny() {
  static const volmap::TetMeshData* mesh = [] {
    const std::string p = data_path("volmap/G1/bunny.mesh");
    return p.empty() ? nullptr : new volmap::TetMeshData(volmap::read_medit(p));
  }();
  return mesh;
}

struct Surface {
  std::vector<double> xyz;
  std::vector<std::uint32_t> tris;
};
const Surface* bunny_boundary() {
  static const Surface* s = []() -> Surface* {
    const auto* m = bunny();
    if (!m) return nullptr;
    auto* out = new Surface;
    out->xyz = m->xyz;
    const auto topo = volmap::analyze_topology(*m);
    for (std::uint32_t hf : topo.boundary_half_faces)
      for (int k = 0; k < 3; ++k) out->tris.push_back(m->tets[4 * (hf / 4) + volmap::kTetFace[hf % 4][k]]);
    return out;
  }();
  return s;
}

void BM_ToolEquivalent_Bunny(benchmark::State& state) {
  const std::string p = data_path("volmap/G1/bunny.mesh");
  if (p.empty()) return state.SkipWithError("../shared/data/volmap/G1/bunny.mesh absent");
  for (auto _ : state) {
    const auto mesh = volmap::read_medit(p);
    const auto report = volmap::check_tet_mesh(mesh);
    if (!report.all_passed()) state.SkipWithError("bunny should pass all checks");
    benchmark::DoNotOptimize(report.signs.positive);
  }
  state.counters["tets"] = 65694;
}

void BM_Parse_Bunny(benchmark::State& state) {
  const std::string p = data_path("volmap/G1/bunny.mesh");
  if (p.empty()) return state.SkipWithError("bunny absent");
  for (auto _ : state) benchmark::DoNotOptimize(volmap::read_medit(p).tets.data());
}

void BM_AllChecks_Bunny(benchmark::State& state) {
  const auto* m = bunny();
  if (!m) return state.SkipWithError("bunny absent");
  for (auto _ : state) benchmark::DoNotOptimize(volmap::check_tet_mesh(*m).signs.positive);
}

void BM_Orientation_Bunny(benchmark::State& state) {
  const auto* m = bunny();
  if (!m) return state.SkipWithError("bunny absent");
  for (auto _ : state)
    benchmark::DoNotOptimize(volmap::orient3d_tets(m->xyz.data(), m->num_vertices(), m->tets.data(), m->num_tets(), nullptr).positive);
}

void BM_Topology_Bunny(benchmark::State& state) {
  const auto* m = bunny();
  if (!m) return state.SkipWithError("bunny absent");
  for (auto _ : state) benchmark::DoNotOptimize(volmap::analyze_topology(*m).boundary_euler);
}

void BM_SelfIntersection_Bunny(benchmark::State& state) {
  const auto* s = bunny_boundary();
  if (!s) return state.SkipWithError("bunny absent");
  volmap::SelfIntersectionOptions options;
  options.parallel = state.range(0) != 0;
  std::size_t candidates = 0;
  for (auto _ : state) {
    const auto r = volmap::find_self_intersections(s->xyz, s->tris, options);
    candidates = r.candidate_pairs;
    benchmark::DoNotOptimize(r.intersecting_pairs);
  }
  state.counters["triangles"] = double(s->tris.size() / 3);
  state.counters["candidate_pairs"] = double(candidates);
}

}  // namespace

BENCHMARK(BM_ToolEquivalent_Bunny)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_Parse_Bunny)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_AllChecks_Bunny)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_Orientation_Bunny)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_Topology_Bunny)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_SelfIntersection_Bunny)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();

BENCHMARK_MAIN();
