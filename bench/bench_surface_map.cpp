// Surface mapping and the exact surface-map check on G1 meshes (read in place from ../shared/data).
// Reference figures on this machine class (VOLMAP's tools, end to end incl. IO): surface_mapping
// bunny -> CUBE 2.2 s, -> STAR 2.7 s; surface_mapping_check bunny 2.7 s. Target: >= 20x faster.
// Benchmarks measure the library calls (mesh already in memory) and, separately, reading the mesh.
#include <benchmark/benchmark.h>
#include <volmap/surface/domain.hpp>
#include <volmap/io/io.hpp>
#include <volmap/surface/surface_map.hpp>
#include <volmap/surface/surface_map_check.hpp>

#include <filesystem>
#include <string>

namespace {
std::string data(const std::string& rel) {
  const auto p = std::filesystem::path(VOLMAP_DATA_DIR) / rel;
  return std::filesystem::exists(p) ? p.string() : std::string();
}

void BM_ReadMesh(benchmark::State& st, std::string name) {
  const std::string path = data("volmap/G1/" + name + ".mesh");
  if (path.empty()) return st.SkipWithError("data absent");
  for (auto _ : st) benchmark::DoNotOptimize(volmap::read_medit(path));
}

void BM_SurfaceMap(benchmark::State& st, std::string name, std::string domain) {
  const std::string path = data("volmap/G1/" + name + ".mesh");
  if (path.empty()) return st.SkipWithError("data absent");
  const auto mesh = volmap::read_medit(path);
  const auto d = volmap::builtin_domain(domain);
  std::size_t added = 0;
  for (auto _ : st) {
    auto r = volmap::map_surface_to_domain(mesh, d);
    added = r.added_vertices;
    benchmark::DoNotOptimize(r);
  }
  st.counters["added_vertices"] = static_cast<double>(added);
}

void BM_SurfaceMapCheck(benchmark::State& st, std::string name, std::string domain) {
  const std::string path = data("volmap/G1/" + name + ".mesh");
  const std::string map_path = data("volmap/G1_" + domain + "/" + name + "_" + domain + ".txt");
  if (path.empty() || map_path.empty()) return st.SkipWithError("data absent");
  const auto mesh = volmap::read_medit(path);
  const auto map = volmap::read_boundary_map(map_path);
  const auto d = volmap::builtin_domain(domain);
  for (auto _ : st) {
    auto r = volmap::check_surface_map(mesh, map, &d);
    if (!r.ok) st.SkipWithError("check failed");
    benchmark::DoNotOptimize(r);
  }
}
}  // namespace

BENCHMARK_CAPTURE(BM_ReadMesh, bunny, std::string("bunny"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SurfaceMap, bunny_cube, std::string("bunny"), std::string("cube"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SurfaceMap, bunny_star, std::string("bunny"), std::string("star"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SurfaceMap, bone_star, std::string("bone"), std::string("star"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SurfaceMapCheck, bunny_cube, std::string("bunny"), std::string("cube"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SurfaceMapCheck, bunny_star, std::string("bunny"), std::string("star"))->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
