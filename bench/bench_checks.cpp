// bench_checks — the seven VOLMAP checks on G1 bunny (65,694 tets): the tool-equivalent pipeline
// (parse .mesh + all checks; VOLMAP's tetmesh_checks takes 2.2 s here, target >= 20x faster) and its
// parts: exact orientation of every tet, topology, boundary self-intersection (parallel and serial).
// Times are wall clock (UseRealTime) with the process CPU time of all threads alongside.
// Reads ../shared/data in place; skips (with a message) when it is absent.
//
// Same-run anchors (bench/side_by_side.hpp: ours_ms, anchor_ms, ratio = ours/anchor, CPU time, min):
//   BM_Orientation_Bunny_SideBySide            ours = volmap::orient3d_tets (exact); anchor = naive double
//                                              3x3 determinant det[a-d; b-d; c-d] per tet (plain loop,
//                                              not robust: the cost floor), counting positives.
//   BM_Orientation_Bunny_CgalEpick_SideBySide  anchor = CGAL Epick CGAL::orientation (filtered exact) on
//                                              Point_3 built beforehand (not timed); only with CGAL.
//   BM_Topology_Bunny_SideBySide               ours = volmap::analyze_topology; anchor = what a
//                                              straightforward implementation does: every tet face's
//                                              sorted vertex triple as the key of a std::map<std::array<
//                                              uint32_t,3>, int> counting occurrences; boundary faces =
//                                              keys seen once.
// Each checks that both sides agree (positive count; boundary face count) and fails otherwise.
#include <benchmark/benchmark.h>

#include <volmap/io/io.hpp>
#include <volmap/core/local_tables.hpp>
#include <volmap/check/self_intersection.hpp>
#include <volmap/check/tetmesh_checks.hpp>
#include <volmap/core/topology.hpp>

#include "side_by_side.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#ifdef VOLMAP_HAVE_CGAL
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#endif

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

// ---- Same-run anchors ----------------------------------------------------------------------------

// Naive double orient3d of every tet, Shewchuk's sign convention (det[a-d; b-d; c-d] > 0 for a
// VOLMAP-positive tet): the number of positive determinants.
std::size_t naive_positive_count(const volmap::TetMeshData& m) {
  const double* x = m.xyz.data();
  const std::uint32_t* tv = m.tets.data();
  const std::size_t nt = m.num_tets();
  std::size_t positive = 0;
  for (std::size_t t = 0; t < nt; ++t) {
    const double* a = x + 3 * std::size_t(tv[4 * t]);
    const double* b = x + 3 * std::size_t(tv[4 * t + 1]);
    const double* c = x + 3 * std::size_t(tv[4 * t + 2]);
    const double* d = x + 3 * std::size_t(tv[4 * t + 3]);
    const double ax = a[0] - d[0], ay = a[1] - d[1], az = a[2] - d[2];
    const double bx = b[0] - d[0], by = b[1] - d[1], bz = b[2] - d[2];
    const double cx = c[0] - d[0], cy = c[1] - d[1], cz = c[2] - d[2];
    const double det = ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx);
    positive += det > 0 ? 1 : 0;
  }
  return positive;
}

// ours = volmap::orient3d_tets (exact), the same call as BM_Orientation_Bunny, against `anchor`, a
// callable returning its count of VOLMAP-positive tets.
template <class Anchor>
void orientation_side_by_side(benchmark::State& state, const volmap::TetMeshData& m, Anchor&& anchor) {
  std::size_t ours_positive = 0, anchor_positive = 0;
  bench::run_side_by_side(
      state,
      [&] {
        ours_positive = volmap::orient3d_tets(m.xyz.data(), m.num_vertices(), m.tets.data(), m.num_tets(), nullptr).positive;
        benchmark::DoNotOptimize(ours_positive);
      },
      [&] {
        anchor_positive = anchor();
        benchmark::DoNotOptimize(anchor_positive);
      });
  if (ours_positive != anchor_positive) return state.SkipWithError("the anchor counted another number of positive tets");
  state.counters["tets"] = double(m.num_tets());
  state.counters["positive"] = double(ours_positive);
}

// Anchor: the naive double determinant.
void BM_Orientation_Bunny_SideBySide(benchmark::State& state) {
  const auto* m = bunny();
  if (!m) return state.SkipWithError("bunny absent");
  orientation_side_by_side(state, *m, [m] { return naive_positive_count(*m); });
}

#ifdef VOLMAP_HAVE_CGAL
// Anchor: CGAL Epick orientation on Point_3 built here, outside the timed region.
void BM_Orientation_Bunny_CgalEpick_SideBySide(benchmark::State& state) {
  const auto* m = bunny();
  if (!m) return state.SkipWithError("bunny absent");
  using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;
  std::vector<Point> pts;
  pts.reserve(m->num_vertices());
  for (std::size_t v = 0; v < m->num_vertices(); ++v) pts.emplace_back(m->xyz[3 * v], m->xyz[3 * v + 1], m->xyz[3 * v + 2]);
  const std::uint32_t* tv = m->tets.data();
  const std::size_t nt = m->num_tets();
  orientation_side_by_side(state, *m, [&] {
    // CGAL::orientation(p, q, r, s) = -orient3d(p, q, r, s): VOLMAP-positive tets are CGAL::NEGATIVE.
    std::size_t positive = 0;
    for (std::size_t t = 0; t < nt; ++t)
      positive += CGAL::orientation(pts[tv[4 * t]], pts[tv[4 * t + 1]], pts[tv[4 * t + 2]], pts[tv[4 * t + 3]]) == CGAL::NEGATIVE ? 1 : 0;
    return positive;
  });
}
#endif

// Face matching with a std::map keyed by each face's sorted vertex triple; returns the number of
// faces seen exactly once (the boundary faces).
std::size_t map_boundary_face_count(const volmap::TetMeshData& m) {
  std::map<std::array<std::uint32_t, 3>, int> faces;
  const std::size_t nt = m.num_tets();
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint32_t* v = &m.tets[4 * t];
    for (int skip = 0; skip < 4; ++skip) {
      std::array<std::uint32_t, 3> key{};
      int k = 0;
      for (int i = 0; i < 4; ++i)
        if (i != skip) key[std::size_t(k++)] = v[i];
      std::sort(key.begin(), key.end());
      ++faces[key];
    }
  }
  std::size_t boundary = 0;
  for (const auto& f : faces) boundary += f.second == 1 ? 1 : 0;
  return boundary;
}

void BM_Topology_Bunny_SideBySide(benchmark::State& state) {
  const auto* m = bunny();
  if (!m) return state.SkipWithError("bunny absent");
  std::size_t ours_boundary = 0, anchor_boundary = 0;
  bench::run_side_by_side(
      state,
      [&] {
        const auto topo = volmap::analyze_topology(*m);
        ours_boundary = topo.boundary_half_faces.size();
        benchmark::DoNotOptimize(ours_boundary);
      },
      [&] {
        anchor_boundary = map_boundary_face_count(*m);
        benchmark::DoNotOptimize(anchor_boundary);
      });
  if (ours_boundary != anchor_boundary) return state.SkipWithError("the std::map anchor found another number of boundary faces");
  state.counters["tets"] = double(m->num_tets());
  state.counters["boundary_faces"] = double(ours_boundary);
}

}  // namespace

BENCHMARK(BM_ToolEquivalent_Bunny)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_Parse_Bunny)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_AllChecks_Bunny)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_Orientation_Bunny)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_Topology_Bunny)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_SelfIntersection_Bunny)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_Orientation_Bunny_SideBySide)->Unit(benchmark::kMillisecond)->UseRealTime()->ComputeStatistics("min", bench::min_of);
#ifdef VOLMAP_HAVE_CGAL
BENCHMARK(BM_Orientation_Bunny_CgalEpick_SideBySide)->Unit(benchmark::kMillisecond)->UseRealTime()->ComputeStatistics("min", bench::min_of);
#endif
BENCHMARK(BM_Topology_Bunny_SideBySide)->Unit(benchmark::kMillisecond)->UseRealTime()->ComputeStatistics("min", bench::min_of);

BENCHMARK_MAIN();
