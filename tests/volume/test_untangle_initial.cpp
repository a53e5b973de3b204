// Untangling from given initial maps and the FFM Newton machinery: the exact per-tet Hessian against
// finite differences of the analytic gradient, its SPD projection, the local
// (frozen-rest) untangler certified by the exact check, the warm-start ε, and `volmap-map --initial`
// (the 7-vertex Floater–Pham-Trong example of GalaxyMaps, a wrong boundary → exit 2, map `-`; the TLC cube).
#include <doctest/doctest.h>

#include <volmap/core/boundary_faces.hpp>
#include <volmap/volume/ffm.hpp>
#include <volmap/core/error.hpp>
#include <volmap/volume/volume_map.hpp>
#include <volmap/io/io.hpp>
#include <volmap/predicates.hpp>

#include "map_test_meshes.hpp"
#include "test_support.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sys/wait.h>

using map_test::scrambled_target;

namespace {

int run(const std::string& cmd) {
  const int rc = std::system((cmd + " > /dev/null 2>&1").c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

}  // namespace

TEST_CASE("FFM Hessian matches finite differences of the gradient and its projection is PSD") {
  const int n = 3;
  auto m = map_test::kuhn_grid(n);
  auto bnd = map_test::grid_boundary_flags(n);
  auto target = scrambled_target(m, bnd, 11, 0.3);
  REQUIRE(volmap::count_nonpositive(target, m.tets) > 0);  // tangled: the D < 0 branch of χ and its derivatives
  for (auto ref : {volmap::ReferenceShape::RegularTet, volmap::ReferenceShape::RestShape}) {
    volmap::FfmEnergy E(m.xyz, m.tets, bnd, target, ref, 0.5);
    const std::size_t nv = E.num_variables();
    auto x = E.initial_variables();
    std::vector<double> H(nv * nv), P(nv * nv), gp(nv), gm(nv);
    for (double eps : {1.0, 0.05}) {
      E.evaluate_dense_hessian(x.data(), eps, false, H.data());
      double max_err = 0, max_h = 0;
      for (std::size_t j = 0; j < nv; ++j) {
        const double h = 1e-6;
        auto xp = x, xm = x;
        xp[j] += h;
        xm[j] -= h;
        E.evaluate(xp.data(), eps, gp.data());
        E.evaluate(xm.data(), eps, gm.data());
        for (std::size_t i = 0; i < nv; ++i) {
          const double fd = (gp[i] - gm[i]) / (2 * h);
          max_err = std::max(max_err, std::abs(fd - H[i * nv + j]));
          max_h = std::max(max_h, std::abs(H[i * nv + j]));
        }
      }
      INFO("eps " << eps << " max |H| " << max_h << " max err " << max_err);
      CHECK(max_h > 0);
      CHECK(max_err <= 1e-4 * std::max(1.0, max_h));
      // The exact Hessian of a tangled map is indefinite; the projected one is PSD (and differs).
      E.evaluate_dense_hessian(x.data(), eps, true, P.data());
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Hm(H.data(), Eigen::Index(nv), Eigen::Index(nv));
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Pm(P.data(), Eigen::Index(nv), Eigen::Index(nv));
      const double lp = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Pm).eigenvalues().minCoeff();
      CHECK(lp >= -1e-9 * max_h);
      CHECK((Pm - Pm.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * max_h);
      if (eps < 1) CHECK(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Hm).eigenvalues().minCoeff() < 0);
    }
  }
}

TEST_CASE("local FFM fixes one displaced vertex and moves nothing outside its region") {
  const int n = 6;
  auto m = map_test::kuhn_grid(n);
  auto bnd = map_test::grid_boundary_flags(n);
  auto target = m.xyz;  // the identity map: valid
  // Push one interior vertex through a neighbour: its star tangles.
  const std::uint32_t v = std::uint32_t((3 * (n + 1) + 3) * (n + 1) + 3);  // (3,3,3)
  REQUIRE(!bnd[v]);
  target[3 * v] += 0.3;
  target[3 * v + 1] += 0.25;
  const std::size_t bad_before = volmap::count_nonpositive(target, m.tets);
  REQUIRE(bad_before > 0);
  const auto before = target;
  volmap::LocalUntangleOptions lo;
  lo.rings = 1;
  auto r = volmap::ffm_local_untangle(volmap::TetMesh(m), bnd, target, lo);
  CHECK(r.nonpositive_before == bad_before);
  CHECK(r.nonpositive_after == 0);
  CHECK(volmap::count_nonpositive(target, m.tets) == 0);
  CHECK(r.largest_region_tets < m.num_tets());
  // Vertices farther than the grown region (Chebyshev grid distance > 2 from (3,3,3)) are untouched.
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) {
        if (std::max({std::abs(i - 3), std::abs(j - 3), std::abs(k - 3)}) <= 2) continue;
        const std::size_t u = std::size_t((i * (n + 1) + j) * (n + 1) + k);
        for (int c = 0; c < 3; ++c) CHECK(target[3 * u + c] == before[3 * u + c]);
      }
}

TEST_CASE("local FFM stops once more rings add nothing to the region it failed on") {
  // A 2x2x2 Kuhn grid with one free vertex: a tet of locked vertices is inverted by mirroring one
  // of its vertices across the other three's plane. Nothing free can fix it, and the region stops
  // growing after a ring or two: the two references fail there once each, and no ring is tried
  // again on the same region (before, the rounds ran to max_rounds re-solving it).
  const int n = 2;
  auto m = map_test::kuhn_grid(n);
  auto bnd = map_test::grid_boundary_flags(n);
  auto target = m.xyz;
  std::size_t locked_tet = m.num_tets();
  for (std::size_t t = 0; t < m.num_tets() && locked_tet == m.num_tets(); ++t)
    if (bnd[m.tets[4 * t]] && bnd[m.tets[4 * t + 1]] && bnd[m.tets[4 * t + 2]] && bnd[m.tets[4 * t + 3]]) locked_tet = t;
  REQUIRE(locked_tet < m.num_tets());
  const std::uint32_t* q = &m.tets[4 * locked_tet];
  const Eigen::Vector3d a(&m.xyz[3 * q[1]]), b(&m.xyz[3 * q[2]]), c(&m.xyz[3 * q[3]]), p(&m.xyz[3 * q[0]]);
  const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
  const Eigen::Vector3d mirrored = p - 2 * normal.dot(p - a) * normal;
  for (int k = 0; k < 3; ++k) target[3 * q[0] + k] = mirrored[k];
  const std::size_t bad = volmap::count_nonpositive(target, m.tets);
  REQUIRE(bad > 0);
  volmap::LocalUntangleOptions lo;
  lo.rings = 1;
  const auto r = volmap::ffm_local_untangle(volmap::TetMesh(m), bnd, target, lo);
  CHECK(r.nonpositive_after == bad);
  MESSAGE("rounds " << r.rounds << ", region " << r.largest_region_tets << " of " << m.num_tets() << " tets");
  CHECK(r.rounds <= 4);
  CHECK(r.rounds < lo.max_rounds);
}

TEST_CASE("FFM warm-start epsilon certifies a nearly valid map") {
  // A valid map with one displaced vertex: the warm start (ε from D_min, never 0) certifies like ε = 1.
  const int n = 5;
  auto m = map_test::kuhn_grid(n);
  auto bnd = map_test::grid_boundary_flags(n);
  auto target = scrambled_target(m, bnd, 5, 0.0);
  const std::uint32_t v = std::uint32_t((2 * (n + 1) + 2) * (n + 1) + 2);
  target[3 * v] += 0.25;
  target[3 * v + 2] += 0.12;
  REQUIRE(volmap::count_nonpositive(target, m.tets) > 0);
  auto cold = target, warm = target;
  volmap::FfmOptions o;
  const auto rc = volmap::ffm_untangle(m.xyz, m.tets, bnd, cold, o);
  o.initial_epsilon = 0;
  const auto rw = volmap::ffm_untangle(m.xyz, m.tets, bnd, warm, o);
  CHECK(rc.certified);
  CHECK(rw.certified);
  CHECK(volmap::count_nonpositive(warm, m.tets) == 0);
  MESSAGE("cold outer " << rc.outer_iterations << " warm outer " << rw.outer_iterations << " final eps " << rw.final_epsilon);
}

TEST_CASE("volmap-map --initial: GalaxyMaps 7-vertex example certifies and a wrong boundary exits 2") {
  const auto tool = volmap_test::tool("volmap-map");
  if (!std::filesystem::exists(tool)) {
    MESSAGE("skipped: volmap-map not built");
    return;
  }
  VOLMAP_REQUIRE_DATA(object, "maps/galaxymaps/example_object.vtk");
  VOLMAP_REQUIRE_DATA(parameter, "maps/galaxymaps/example_parameter.vtk");
  const auto dir = volmap_test::scratch_dir("untangle_initial");
  const auto input = volmap::read_tet_mesh(object.string());
  const auto initial = volmap::read_tet_mesh(parameter.string());
  REQUIRE(volmap::count_nonpositive(initial.xyz, initial.tets) == 2);  // the upstream initial map: 2 flipped tets
  const auto bverts = volmap::boundary_vertex_ids(input);
  REQUIRE(bverts.size() == 5);
  const std::string out = (dir / "out.mesh").string();
  const std::string base = tool.string() + " " + object.string() + " ";

  // Map `-`: the boundary map is taken from the initial file.
  CHECK(run(base + "- " + out + " --initial " + parameter.string()) == 0);
  auto written = volmap::read_medit(out);
  CHECK(written.tets == input.tets);
  CHECK(volmap::count_nonpositive(written.xyz, written.tets) == 0);
  for (auto v : bverts)
    for (int c = 0; c < 3; ++c) CHECK(written.xyz[3 * v + c] == initial.xyz[3 * v + c]);

  // The same boundary as an explicit map file certifies too.
  volmap::BoundaryMap map;
  for (auto v : bverts) {
    map.vids.push_back(v);
    for (int c = 0; c < 3; ++c) map.xyz.push_back(initial.xyz[3 * v + c]);
  }
  const std::string map_path = (dir / "map.txt").string();
  volmap::write_boundary_map(map_path, map);
  std::filesystem::remove(out);
  CHECK(run(base + map_path + " " + out + " --initial " + parameter.string()) == 0);
  CHECK(std::filesystem::exists(out));

  // A wrong boundary in the initial file: exit 2 and no output written.
  auto moved = initial;
  moved.xyz[3 * bverts[0]] += 1e-3;
  const std::string moved_path = (dir / "moved.mesh").string();
  volmap::write_medit(moved_path, moved);
  std::filesystem::remove(out);
  CHECK(run(base + map_path + " " + out + " --initial " + moved_path) == 2);
  CHECK(!std::filesystem::exists(out));
  // An initial file with other tets, or `-` without --initial: exit 2.
  auto other = initial;
  std::swap(other.tets[0], other.tets[1]);
  const std::string other_path = (dir / "other.mesh").string();
  volmap::write_medit(other_path, other);
  CHECK(run(base + map_path + " " + out + " --initial " + other_path) == 2);
  CHECK(run(base + "- " + out) == 2);
  // Without --initial (Tutte start) the example also certifies: the cascade untangles Tutte's 2 flips.
  CHECK(run(base + map_path + " " + out) == 0);
  std::filesystem::remove_all(dir);
}

TEST_CASE("compute_volume_map starts from the given initial map and checks its boundary") {
  const int n = 3;
  auto m = map_test::kuhn_grid(n);
  auto bnd = map_test::grid_boundary_flags(n);
  volmap::BoundaryMap map;
  for (std::uint32_t v = 0; v < m.num_vertices(); ++v)
    if (bnd[v]) {
      map.vids.push_back(v);
      for (int c = 0; c < 3; ++c) map.xyz.push_back(m.xyz[3 * v + c]);
    }
  // A valid initial map (the identity) is returned untouched: Tutte 3D would move the interior.
  volmap::VolumeMapOptions o;
  o.quality_pass = false;
  o.initial_xyz = m.xyz;
  auto r = volmap::compute_volume_map(m, map, o);
  CHECK(r.certified);
  CHECK(r.certified_by == "initial");
  CHECK(r.target_xyz == m.xyz);
  volmap::VolumeMapOptions tutte;
  tutte.quality_pass = false;
  CHECK(volmap::compute_volume_map(m, map, tutte).target_xyz != m.xyz);
  // A tangled initial map is untangled; its boundary must match the map bit for bit.
  o.initial_xyz = scrambled_target(m, bnd, 3, 0.0);
  for (std::size_t k = 0; k < map.size(); ++k)
    for (int c = 0; c < 3; ++c) map.xyz[3 * k + c] = o.initial_xyz[3 * std::size_t(map.vids[k]) + c];
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    if (!bnd[v]) o.initial_xyz[3 * v] += 0.9;  // push every interior vertex across its neighbours
  REQUIRE(volmap::count_nonpositive(o.initial_xyz, m.tets) > 0);
  r = volmap::compute_volume_map(m, map, o);
  CHECK(r.certified);
  CHECK(r.stages.at(1).name == "initial");
  auto wrong = o;
  wrong.initial_xyz[3 * std::size_t(map.vids[0]) + 1] = std::nextafter(wrong.initial_xyz[3 * std::size_t(map.vids[0]) + 1], 1e9);
  CHECK_THROWS_AS(volmap::compute_volume_map(m, map, wrong), volmap::Error);
  wrong.initial_xyz.pop_back();
  CHECK_THROWS_AS(volmap::compute_volume_map(m, map, wrong), volmap::Error);
}

TEST_CASE("TLC example cube from its tangled initial map certifies with a bit-exact boundary") {
  VOLMAP_REQUIRE_DATA(p, "maps/tlc/input");
  // Blocks: nV 3 + rest positions, nV 3 + initial positions, nT 4 + tets, nH + handle (boundary) ids.
  std::ifstream in(p);
  std::size_t count = 0, width = 0;
  volmap::TetMeshData rest;
  in >> count >> width;
  rest.xyz.resize(3 * count);
  for (auto& x : rest.xyz) in >> x;
  std::vector<double> init(3 * count);
  in >> count >> width;
  for (auto& x : init) in >> x;
  in >> count >> width;
  rest.tets.resize(4 * count);
  for (auto& t : rest.tets) in >> t;
  in >> count;
  volmap::BoundaryMap map;
  for (std::size_t i = 0; i < count; ++i) {
    std::uint32_t h = 0;
    in >> h;
    map.vids.push_back(h);
    for (int c = 0; c < 3; ++c) map.xyz.push_back(init[3 * std::size_t(h) + c]);
  }
  REQUIRE(rest.num_tets() == 162);
  REQUIRE(volmap::count_nonpositive(init, rest.tets) == 36);
  volmap::VolumeMapOptions o;
  o.initial_xyz = init;
  o.quality_pass = false;
  const auto r = volmap::compute_volume_map(rest, map, o);
  MESSAGE("refined " << r.refined << " tets " << r.source.num_tets() << " certified " << r.certified << " by " << r.certified_by);
  CHECK(volmap::count_nonpositive(r.source.xyz, r.source.tets) == 0);  // the refined source stays valid
  CHECK(r.certified == (volmap::count_nonpositive(r.target_xyz, r.source.tets) == 0));
  CHECK(r.stages.at(r.refined ? 2 : 1).name == "initial");
  for (std::size_t k = 0; k < map.size(); ++k)
    for (int c = 0; c < 3; ++c) CHECK(r.target_xyz[3 * std::size_t(map.vids[k]) + c] == map.xyz[3 * k + c]);
}
