// Tutte 3D baseline: unique edges, the uniform-Laplacian solve (each free vertex = mean of its
// neighbours, boundary untouched, singular systems reported), and the VOLMAP oracle: G1/log.csv's
// third column (inverted tets of the paper's Tutte 3D maps), reproduced exactly with the exact
// predicate. Default run: bone and duck × cube/tet/pyr/octa (8 rows) + the tool's contract.
// TEST_SUITE("long"): all 80 rows whose mesh is present, plus columns 8–10 (scaled Jacobian).
#include <doctest/doctest.h>
#include <volmap/core/error.hpp>
#include <volmap/io/io.hpp>
#include <volmap/check/map_check.hpp>
#include <volmap/check/metrics.hpp>
#include <volmap/volume/tutte3d.hpp>
#include <volmap/core/tet_mesh.hpp>
#include <volmap/testing/generate.hpp>

#include "test_support.hpp"
#include "vmap_test_util.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <unistd.h>

using namespace volmap;
namespace fs = std::filesystem;

namespace {

struct LogRow {
  std::string mesh, domain;
  std::size_t tets = 0, inverted = 0;
  double sj_min = 0, sj_max = 0, sj_mean = 0;
};

double parse_comma(std::string s) {
  std::replace(s.begin(), s.end(), ',', '.');
  return std::stod(s);
}

std::vector<LogRow> read_log(const fs::path& path) {
  std::vector<LogRow> rows;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::size_t pos = 0;
    while (true) {
      const std::size_t next = line.find("; ", pos);
      f.push_back(line.substr(pos, next == std::string::npos ? std::string::npos : next - pos));
      if (next == std::string::npos) break;
      pos = next + 2;
    }
    if (f.size() != 10) continue;
    std::string stem = f[0].substr(f[0].rfind('/') + 1);  // <mesh>_<dom>_tutte
    stem = stem.substr(0, stem.size() - std::string("_tutte").size());
    const std::size_t us = stem.rfind('_');
    LogRow r;
    r.mesh = stem.substr(0, us);
    r.domain = stem.substr(us + 1);
    r.tets = std::stoul(f[1]);
    r.inverted = std::stoul(f[2]);
    r.sj_min = parse_comma(f[7]);
    r.sj_max = parse_comma(f[8]);
    r.sj_mean = parse_comma(f[9]);
    rows.push_back(r);
  }
  return rows;
}

// Tutte map of one log row (mesh + G1_<dom> map) and its exact inverted count (orient3d <= 0).
struct RowResult {
  std::size_t tets = 0, inverted = 0;
  double sj_min = 1e300, sj_max = -1e300, sj_mean = 0;
  double seconds = 0;
};
RowResult run_row(const fs::path& root, const LogRow& row) {
  const TetMeshData mesh = read_medit((root / "volmap/G1" / (row.mesh + ".mesh")).string());
  const std::string map_path = (root / ("volmap/G1_" + row.domain) / (row.mesh + "_" + row.domain + ".txt")).string();
  const BoundaryMap map = read_boundary_map(map_path);
  validate_boundary_map(map, mesh, map_path);
  const Tutte3dResult tutte = tutte3d(mesh, map);
  RowResult r;
  r.seconds = tutte.timings.total();
  r.tets = mesh.num_tets();
  const TetSignCounts c = orient3d_tets(tutte.xyz.data(), mesh.num_vertices(), mesh.tets.data(), mesh.num_tets(), nullptr);
  REQUIRE(c.ok);
  r.inverted = c.zero + c.negative;
  double sum = 0;
  for (std::size_t t = 0; t < r.tets; ++t) {
    const std::uint32_t* v = &mesh.tets[4 * t];
    const double sj = tet_scaled_jacobian_volmap(&tutte.xyz[3 * v[0]], &tutte.xyz[3 * v[1]], &tutte.xyz[3 * v[2]],
                                                 &tutte.xyz[3 * v[3]]);
    r.sj_min = std::min(r.sj_min, sj);
    r.sj_max = std::max(r.sj_max, sj);
    sum += sj;
  }
  r.sj_mean = sum / double(r.tets);
  return r;
}

// A tet (0,1,2,3) split at an interior vertex 4: 4 tets, VOLMAP-positive.
TetMeshData split_tet() {
  TetMeshData m;
  m.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.1, 0.2, 0.3};
  // orient3d(0,1,2,3) for this corner tet: det[a-d;b-d;c-d] with d=(0,0,1): negative → use (1,0,2,3).
  const std::uint32_t base[4] = {1, 0, 2, 3};
  REQUIRE(orient3d(&m.xyz[3 * base[0]], &m.xyz[3 * base[1]], &m.xyz[3 * base[2]], &m.xyz[3 * base[3]]) > 0);
  for (int i = 0; i < 4; ++i) {
    std::uint32_t t[4] = {base[0], base[1], base[2], base[3]};
    t[i] = 4;
    m.tets.insert(m.tets.end(), t, t + 4);
  }
  return m;
}

}  // namespace

TEST_CASE("unique_tet_edges: sorted unique pairs; errors on bad ids") {
  TetMeshData m = split_tet();
  const auto edges = unique_tet_edges(m);
  CHECK(edges.size() == 2 * 10);  // K5 on 5 vertices
  for (std::size_t e = 0; e + 1 < edges.size() / 2; ++e) {
    CHECK(edges[2 * e] < edges[2 * e + 1]);
    const auto a = std::make_pair(edges[2 * e], edges[2 * e + 1]);
    const auto b = std::make_pair(edges[2 * e + 2], edges[2 * e + 3]);
    CHECK(a < b);
  }
  TetMeshData bad = m;
  bad.tets[5] = 99;
  CHECK_THROWS_AS(unique_tet_edges(bad), Error);
  bad = m;
  bad.tets[1] = bad.tets[0];
  CHECK_THROWS_AS(unique_tet_edges(bad), Error);
}

TEST_CASE("unique_tet_edges of a TetMesh (its edge cache) equals the list from the flat arrays, also after edits") {
  TetMesh mesh(generate_kuhn_grid(3, 2, 2));
  CHECK(unique_tet_edges(mesh) == unique_tet_edges(mesh.to_data()));
  const double p[3] = {0.5, 0.0, 0.0};  // grid vertices 0 and 1 are (0,0,0) and (1,0,0)
  mesh.split_edge(VertexId(0), VertexId(1), p);
  CHECK(mesh.num_vertices() == 4 * 3 * 3 + 1);
  CHECK(unique_tet_edges(mesh) == unique_tet_edges(mesh.to_data()));
}

TEST_CASE("tutte3d: single interior vertex goes to the mean of its 4 neighbours; boundary kept bit-exact") {
  const TetMeshData m = split_tet();
  BoundaryMap map;
  map.vids = {3, 0, 2, 1};  // file order is irrelevant
  map.xyz = {0.25, 0.5, 7.0, 0.1, 0.2, 0.3, -1.0, 4.0, 2.0, 3.0, 1.0 / 3.0, 0.0};
  const Tutte3dResult r = tutte3d(m, map);
  CHECK(r.num_free == 1);
  CHECK(r.num_fixed == 4);
  CHECK(r.num_edges == 10);
  for (std::size_t k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i) CHECK(r.xyz[3 * map.vids[k] + i] == map.xyz[3 * k + i]);
  for (int i = 0; i < 3; ++i) {
    double mean = 0;
    for (std::size_t k = 0; k < 4; ++k) mean += map.xyz[3 * k + i] / 4;
    CHECK(r.xyz[3 * 4 + i] == doctest::Approx(mean).epsilon(1e-14));
  }
}

TEST_CASE("tutte3d on a Kuhn grid: every free vertex is the mean of its neighbours; identity boundary = identity") {
  const TetMeshData grid = vmap_test::kuhn_grid(6);
  const int s = 7;
  BoundaryMap map;
  for (std::size_t v = 0; v < grid.num_vertices(); ++v) {
    const int i = v % s, j = (v / s) % s, k = v / (s * s);
    if (i == 0 || j == 0 || k == 0 || i == s - 1 || j == s - 1 || k == s - 1) {
      map.vids.push_back(std::uint32_t(v));
      // Boundary moved by a smooth non-affine deformation.
      const double* p = &grid.xyz[3 * v];
      map.xyz.insert(map.xyz.end(), {p[0] + 0.1 * p[1] * p[1], p[1] + 0.2 * p[2] * p[0], p[2] - 0.1 * p[0] * p[1]});
    }
  }
  const Tutte3dResult r = tutte3d(grid, map);
  CHECK(r.num_free == 5 * 5 * 5);
  const auto edges = unique_tet_edges(grid);
  std::vector<double> sum(3 * grid.num_vertices(), 0.0);
  std::vector<int> degree(grid.num_vertices(), 0);
  for (std::size_t e = 0; e < edges.size() / 2; ++e) {
    const auto a = edges[2 * e], b = edges[2 * e + 1];
    ++degree[a];
    ++degree[b];
    for (int i = 0; i < 3; ++i) {
      sum[3 * a + i] += r.xyz[3 * b + i];
      sum[3 * b + i] += r.xyz[3 * a + i];
    }
  }
  std::vector<std::uint8_t> fixed(grid.num_vertices(), 0);
  for (auto v : map.vids) fixed[v] = 1;
  double worst = 0;
  for (std::size_t v = 0; v < grid.num_vertices(); ++v) {
    if (fixed[v]) continue;
    for (int i = 0; i < 3; ++i) worst = std::max(worst, std::fabs(r.xyz[3 * v + i] - sum[3 * v + i] / degree[v]));
  }
  CHECK(worst < 1e-12);

  // Identity boundary: the uniform Laplacian of a Kuhn grid reproduces affine functions exactly
  // (the Kuhn stencil is symmetric), so the grid maps to itself.
  BoundaryMap identity = map;
  for (std::size_t k = 0; k < identity.vids.size(); ++k)
    for (int i = 0; i < 3; ++i) identity.xyz[3 * k + i] = grid.xyz[3 * identity.vids[k] + i];
  const Tutte3dResult id = tutte3d(grid, identity);
  double err = 0;
  for (std::size_t i = 0; i < grid.xyz.size(); ++i) err = std::max(err, std::fabs(id.xyz[i] - grid.xyz[i]));
  CHECK(err < 1e-12);
}

TEST_CASE("solve_uniform_laplacian: reusable with any fixed mask; singular systems throw Failed") {
  const TetMeshData m = split_tet();
  const auto edges = unique_tet_edges(m);
  std::vector<double> xyz = m.xyz;
  std::vector<std::uint8_t> fixed = {1, 1, 1, 1, 0};
  solve_uniform_laplacian(m.num_vertices(), edges, fixed, xyz);
  CHECK(xyz[12] == doctest::Approx(0.25));  // mean x of (0,0,0),(1,0,0),(0,1,0),(0,0,1)
  CHECK(xyz[13] == doctest::Approx(0.25));
  // Fix only vertex 4, free the rest: connected to a fixed vertex → solvable, all collapse onto it.
  std::vector<std::uint8_t> only4 = {0, 0, 0, 0, 1};
  xyz = m.xyz;
  solve_uniform_laplacian(m.num_vertices(), edges, only4, xyz);
  CHECK(xyz[0] == doctest::Approx(0.1));
  // No fixed vertex at all: singular.
  std::vector<std::uint8_t> none(5, 0);
  try {
    solve_uniform_laplacian(m.num_vertices(), edges, none, xyz);
    FAIL("expected an error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Failed);
  }
  CHECK_THROWS_AS(solve_uniform_laplacian(4, edges, fixed, xyz), Error);  // size mismatch
}

TEST_CASE("G1 log.csv oracle; default subset: bone and duck x cube/tet/pyr/octa inverted counts") {
  VOLMAP_REQUIRE_DATA(log_path, "volmap/G1/log.csv");
  const fs::path root = volmap_test::data_root();
  std::size_t checked = 0;
  for (const LogRow& row : read_log(log_path)) {
    if (row.mesh != "bone" && row.mesh != "duck") continue;
    const RowResult r = run_row(root, row);
    INFO(row.mesh << " " << row.domain);
    CHECK(r.tets == row.tets);
    CHECK(r.inverted == row.inverted);
    ++checked;
  }
  CHECK(checked == 8);
}

TEST_CASE("volmap-tutte3d tool: writes the map; certifies the file on disk; exit 1 when not injective") {
  VOLMAP_REQUIRE_DATA(mesh, "volmap/G1/bone.mesh");
  VOLMAP_REQUIRE_DATA(map, "volmap/G1_cube/bone_cube.txt");
  const fs::path out = fs::temp_directory_path() / ("vmap_tutte_bone_" + std::to_string(::getpid()) + ".mesh");
  const auto tool = volmap_test::tool("volmap-tutte3d").string();
  const auto r = vmap_test::run(tool + " " + mesh.string() + " " + map.string() + " " + out.string() + " --json");
  CHECK(r.code == 1);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["inverted"] == 53);
  CHECK(j["output_negative"].get<int>() + j["output_zero"].get<int>() == 53);
  CHECK(j["boundary_mismatches"] == 0);
  CHECK(j["injective"] == false);
  // Independent re-check of the written file: same count, boundary bit-exact.
  const TetMeshData in = read_medit(mesh.string());
  const TetMeshData written = read_medit(out.string());
  const BoundaryMap bmap = read_boundary_map(map.string());
  const MapCheckReport check = check_map(in, written, &bmap);
  CHECK(check.output.zero + check.output.negative == 53);
  CHECK(check.boundary_mismatches == 0);
  CHECK(written.tets == in.tets);
  fs::remove(out);

  // Bad inputs: exit 2, nothing written.
  const fs::path out2 = fs::temp_directory_path() / ("vmap_tutte_bad_" + std::to_string(::getpid()) + ".mesh");
  VOLMAP_REQUIRE_DATA(duck_map, "volmap/G1_cube/duck_cube.txt");
  CHECK(vmap_test::run(tool + " " + mesh.string() + " " + duck_map.string() + " " + out2.string()).code == 2);
  CHECK(!fs::exists(out2));
  CHECK(vmap_test::run(tool + " " + mesh.string() + " /nonexistent.txt " + out2.string()).code == 2);
  CHECK(vmap_test::run(tool + " " + mesh.string()).code == 2);
  CHECK(vmap_test::run(tool + " " + mesh.string() + " " + map.string() + " " + out2.string() + " --weights cotan").code == 2);
}

TEST_CASE("injective Tutte map certifies with exit 0") {
  // Kuhn grid, boundary at its own positions: the identity map, injective.
  const TetMeshData grid = vmap_test::kuhn_grid(3);
  const fs::path dir = fs::temp_directory_path() / ("vmap_tutte_grid_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  write_medit((dir / "grid.mesh").string(), grid);
  std::ofstream mapfile(dir / "grid.txt");
  mapfile.precision(17);
  for (std::size_t v = 0; v < grid.num_vertices(); ++v) {
    const int i = v % 4, j = (v / 4) % 4, k = v / 16;
    if (i == 0 || j == 0 || k == 0 || i == 3 || j == 3 || k == 3)
      mapfile << v << " " << grid.xyz[3 * v] << " " << grid.xyz[3 * v + 1] << " " << grid.xyz[3 * v + 2] << "\n";
  }
  mapfile.close();
  const auto tool = volmap_test::tool("volmap-tutte3d").string();
  const auto r = vmap_test::run(tool + " " + (dir / "grid.mesh").string() + " " + (dir / "grid.txt").string() + " " +
                                (dir / "out.mesh").string() + " --json");
  CHECK(r.code == 0);
  CHECK(nlohmann::json::parse(r.out)["injective"] == true);
  fs::remove_all(dir);
}

TEST_SUITE("long") {
  TEST_CASE("G1 log.csv oracle on all 80 rows whose mesh is present: inverted count and scaled Jacobian cols 8-10") {
    VOLMAP_REQUIRE_DATA(log_path, "volmap/G1/log.csv");
    const fs::path root = volmap_test::data_root();
    std::size_t checked = 0, matched = 0, sj_matched = 0;
    for (const LogRow& row : read_log(log_path)) {
      if (!fs::exists(root / "volmap/G1" / (row.mesh + ".mesh"))) continue;
      const RowResult r = run_row(root, row);
      INFO(row.mesh << " " << row.domain << ": ours " << r.inverted << " log " << row.inverted);
      CHECK(r.tets == row.tets);
      CHECK(r.inverted == row.inverted);
      // The log prints 6 decimals.
      CHECK(std::fabs(r.sj_min - row.sj_min) <= 6e-7);
      CHECK(std::fabs(r.sj_max - row.sj_max) <= 6e-7);
      CHECK(std::fabs(r.sj_mean - row.sj_mean) <= 6e-7);
      matched += r.inverted == row.inverted;
      sj_matched += std::fabs(r.sj_min - row.sj_min) <= 6e-7 && std::fabs(r.sj_max - row.sj_max) <= 6e-7 &&
                    std::fabs(r.sj_mean - row.sj_mean) <= 6e-7;
      ++checked;
      MESSAGE(row.mesh << "_" << row.domain << " tets " << r.tets << " inverted " << r.inverted << " (log "
                       << row.inverted << ") tutte " << r.seconds << " s");
    }
    MESSAGE("rows checked " << checked << ", inverted matched " << matched << ", scaled Jacobian matched " << sj_matched);
    CHECK(checked == 80);
  }
}
