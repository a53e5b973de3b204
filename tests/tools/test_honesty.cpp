// Honesty, the rule of issue 16: no tool exits 0 or prints a certificate for an input mesh that
// volmap-tetmesh-check rejects. The oracle is volmap-tetmesh-check itself, run on every real tet mesh
// of ../shared/data that is not a valid VOLMAP input (opposite orientation, tangled maps, genus-1
// boundary) and on generated invalid meshes; every mapper and checker is then given that mesh with
// an identity boundary map and must refuse it: exit 2, one stderr line naming the file, no
// certificate on stdout, no output written, the input unchanged. Real data is skipped with a message
// when absent.
#include <doctest/doctest.h>

#include <volmap/io/io.hpp>
#include <volmap/testing/generate.hpp>

#include "tool_run.hpp"

#include <filesystem>

namespace fs = std::filesystem;
using volmap_test::RunResult;

namespace {

struct Verdicts {
  int rejected = 0, refused_by_all = 0;
};

// Every mapper and checker on `mesh` (a file volmap-tetmesh-check rejects) and its identity map.
void require_refused_everywhere(const fs::path& mesh, const fs::path& work) {
  const fs::path out = work / "out", scratch = work / "scratch";
  fs::remove_all(work);
  for (const auto& d : {out, scratch}) fs::create_directories(d);
  const std::string map = volmap_test::write_bytes(
      work / "identity_map.txt", volmap_test::boundary_identity_map_text(volmap::read_tet_mesh(mesh.string())));
  const std::string in = mesh.string(), name = mesh.filename().string();
  const std::string before = volmap_test::fingerprint(mesh.parent_path());
  const std::vector<std::vector<std::string>> runs = {
      {"volmap-tutte3d", in, map, (out / "t.mesh").string()},
      {"volmap-map", in, map, (out / "m.mesh").string(), "--time-limit", "5"},
      {"volmap-map-check", in, in, "--absolute", "--boundary", map},
      {"volmap-metrics", in, in},
      {"volmap-surface-map", "cube", in, (out / "s.txt").string()},
      {"volmap-surface-map-check", in, map},
  };
  for (std::vector<std::string> argv : runs) {
    const std::string tool = argv.front();
    if (!fs::exists(volmap_test::tool(tool))) {
      MESSAGE("skipped: " << tool << " is not built");
      continue;
    }
    argv.front() = volmap_test::tool(tool).string();
    CAPTURE(tool);
    const RunResult r = volmap_test::run_tool_process(argv, scratch, 120);
    std::string err = r.err;
    while (!err.empty() && err.back() == '\n') err.pop_back();
    CAPTURE(err);
    CHECK_FALSE(r.signaled);
    CHECK(r.exit_code == 2);
    CHECK(err.find('\n') == std::string::npos);
    CHECK(err.find(name) != std::string::npos);
    CHECK(err.find("not a valid input tet mesh") != std::string::npos);
    for (const char* phrase : {"certified injective", "The map is valid (certified", "Check result: SUCCESS"})
      CHECK(r.out.find(phrase) == std::string::npos);
    CHECK(volmap_test::listing(out).empty());
  }
  CHECK(volmap_test::fingerprint(mesh.parent_path()) == before);
  fs::remove_all(work);
}

// True when volmap-tetmesh-check rejects `mesh` (exit 1: a check failed).
bool tetmesh_check_rejects(const fs::path& mesh, const fs::path& scratch) {
  fs::create_directories(scratch);
  const RunResult r = volmap_test::run_tool_process({volmap_test::tool("volmap-tetmesh-check").string(), mesh.string()}, scratch, 300);
  REQUIRE_FALSE(r.signaled);
  REQUIRE_MESSAGE((r.exit_code == 0 || r.exit_code == 1), mesh << ": " << r.err);
  return r.exit_code == 1;
}

}  // namespace

TEST_CASE("honesty: every real tet mesh volmap-tetmesh-check rejects is refused by every mapper and checker") {
  const fs::path root = volmap_test::data_root();
  if (root.empty()) {
    MESSAGE("skipped: ../shared/data is absent");
    return;
  }
  if (!fs::exists(volmap_test::tool("volmap-tetmesh-check"))) {
    MESSAGE("skipped: volmap-tetmesh-check is not built");
    return;
  }
  // Tet meshes that are not valid VOLMAP inputs (README: opposite orientation, tangled initial maps,
  // a genus-1 boundary), up to 3 MB each to keep the default suite short.
  const std::vector<std::string> candidates = {
      "negative/robustpolycube_NY_2.mesh",        "volmap/viewer-samples/hand_aigerman.mesh",
      "volmap/viewer-samples/max.mesh",           "volmap/viewer-samples/hand_pc_aigerman.mesh",
      "volmap/viewer-samples/max_pc.mesh",        "tetmeshes/cinolib/sphere.mesh",
      "tetmeshes/libigl_tutorial/bunny.mesh",     "tetmeshes/libigl_tutorial/hand.mesh",
      "tetmeshes/libigl_tutorial/octopus-low.mesh", "tetmeshes/robustpolycube/B0.mesh",
      "tetmeshes/robustpolycube/pente.mesh",      "tetmeshes/stardecompositionmaps/open.vtk",
      "tetmeshes/stardecompositionmaps/thumb.vtk", "maps/galaxymaps/example_parameter.vtk",
      "maps/galaxymaps/tgs_100349_parameter.vtk", "maps/lim_benchmark/armadillo-598-init.vtk",
  };
  const fs::path work = fs::temp_directory_path() / ("volmap_honesty_" + std::to_string(getpid()));
  Verdicts v;
  for (const std::string& rel : candidates) {
    const fs::path mesh = volmap_test::data_file(rel);
    if (mesh.empty()) {
      MESSAGE("skipped: " << rel << " is absent");
      continue;
    }
    if (fs::file_size(mesh) > 3u << 20) continue;
    CAPTURE(rel);
    if (!tetmesh_check_rejects(mesh, work / "check")) {
      MESSAGE(rel << ": accepted by volmap-tetmesh-check (not a case for this test)");
      continue;
    }
    ++v.rejected;
    require_refused_everywhere(mesh, work / "run");
  }
  fs::remove_all(work);
  MESSAGE(v.rejected << " real meshes rejected by volmap-tetmesh-check, each refused by every mapper and checker");
  CHECK(v.rejected >= 10);
}

TEST_CASE("honesty: generated meshes volmap-tetmesh-check rejects are refused by every mapper and checker") {
  if (!fs::exists(volmap_test::tool("volmap-tetmesh-check"))) {
    MESSAGE("skipped: volmap-tetmesh-check is not built");
    return;
  }
  const fs::path work = fs::temp_directory_path() / ("volmap_honesty_gen_" + std::to_string(getpid()));
  const fs::path in = work / "in";
  fs::create_directories(in);
  const volmap::TetMeshData g = volmap::generate_kuhn_grid(2, 2, 2);
  std::vector<std::pair<std::string, volmap::TetMeshData>> bad;
  {
    volmap::TetMeshData m = g;  // one tet listed twice
    m.tets.insert(m.tets.end(), g.tets.begin(), g.tets.begin() + 4);
    bad.emplace_back("duplicate_tet.mesh", m);
  }
  {
    volmap::TetMeshData m = g;  // one tet listed twice, its vertices in another (even) order
    m.tets.insert(m.tets.end(), {g.tets[1], g.tets[0], g.tets[3], g.tets[2]});
    bad.emplace_back("duplicate_tet_permuted.mesh", m);
  }
  {
    volmap::TetMeshData m = g;  // the last cube's 6 tets over 8 new vertices at the same points
    std::vector<std::uint32_t> copy(g.num_vertices(), ~0u);
    for (std::size_t k = g.tets.size() - 24; k < g.tets.size(); ++k) {
      const std::uint32_t u = g.tets[k];
      if (copy[u] == ~0u) {
        copy[u] = static_cast<std::uint32_t>(m.num_vertices());
        m.xyz.insert(m.xyz.end(), &g.xyz[3 * u], &g.xyz[3 * u] + 3);
      }
      m.tets.push_back(copy[u]);
    }
    bad.emplace_back("coincident_last_cube.mesh", m);
  }
  {
    volmap::TetMeshData m = g;  // one interior vertex moved onto another: coincident, flat tets
    m.xyz[3 * 13] = 0, m.xyz[3 * 13 + 1] = 0, m.xyz[3 * 13 + 2] = 0;
    bad.emplace_back("collapsed_vertex.mesh", m);
  }
  {
    volmap::TetMeshData m = g;  // every tet inverted (the opposite orientation convention)
    for (std::size_t t = 0; t < m.num_tets(); ++t) std::swap(m.tets[4 * t], m.tets[4 * t + 1]);
    bad.emplace_back("all_inverted.mesh", m);
  }
  int rejected = 0;
  for (const auto& [name, m] : bad) {
    CAPTURE(name);
    const fs::path mesh = in / name;
    volmap_test::write_bytes(mesh, volmap_test::medit_text(m));
    REQUIRE(tetmesh_check_rejects(mesh, work / "check"));
    ++rejected;
    require_refused_everywhere(mesh, work / "run");
  }
  fs::remove_all(work);
  CHECK(rejected == int(bad.size()));
}
