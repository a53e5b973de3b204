// The mapper's state and judge (map_state.hpp): the state takes the boundary map as locked targets;
// the judge keeps a stage that does not make the exact non-positive count worse and undoes one that
// does — positions only, or a stage that also changed the mesh (mesh, target and locked restored
// bit-identically); an expired time budget runs no untangling stage. Oracles: exact counts from
// orient3d_tets on arrays copied before the stages, and the arrays themselves.
#include <doctest/doctest.h>

#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>
#include <volmap/volume/map_stages.hpp>
#include <volmap/volume/map_state.hpp>
#include <volmap/volume/volume_map.hpp>

#include "map_test_meshes.hpp"

#include <random>

namespace {

// Kuhn grid of the unit cube mapped by an orientation-preserving affine map (scrambled_target's map
// without the scrambling): Tutte reproduces it, so every tet is positive after place_by_tutte.
struct AffineCase {
  explicit AffineCase(int n)
      : mesh(map_test::kuhn_grid(n)), bnd(map_test::grid_boundary_flags(n)), affine(map_test::scrambled_target(mesh, bnd, 1, 0.0)),
        map(map_test::boundary_map_of(bnd, affine)) {}
  volmap::TetMeshData mesh;
  std::vector<std::uint8_t> bnd;
  std::vector<double> affine;
  volmap::BoundaryMap map;
};

}  // namespace

TEST_CASE("MapState: locked = the boundary, targets = the map's doubles; bad pairs are refused") {
  AffineCase c(3);
  volmap::MapState s(c.mesh, c.map);
  CHECK(s.input_vertices == c.mesh.num_vertices());
  CHECK(s.input_tets == c.mesh.num_tets());
  const std::vector<double> x = s.target_xyz();
  for (std::size_t v = 0; v < c.bnd.size(); ++v) {
    CHECK(s.locked.data()[v] == c.bnd[v]);
    for (int i = 0; i < 3; ++i) CHECK(x[3 * v + i] == (c.bnd[v] ? c.affine[3 * v + i] : 0.0));
  }
  auto missing = c.map;
  missing.vids.pop_back();
  missing.xyz.resize(missing.xyz.size() - 3);
  CHECK_THROWS_AS(volmap::MapState(c.mesh, missing), volmap::Error);
  auto inverted = c.mesh;
  std::swap(inverted.tets[0], inverted.tets[1]);
  CHECK_THROWS_AS(volmap::MapState(inverted, c.map), volmap::Error);
}

TEST_CASE("StageJudge: a worsening stage is undone, an improving or equal one is kept") {
  AffineCase c(4);
  volmap::MapState s(c.mesh, c.map);
  volmap::StageJudge judge(s);
  volmap::place_by_tutte(s);
  const std::vector<double> good = s.target_xyz();
  REQUIRE(volmap::count_nonpositive(good, c.mesh.tets) == 0);
  const volmap::StageVerdict first = judge.judge();
  CHECK(first.measured == 0);
  CHECK(first.kept == 0);
  CHECK_FALSE(first.undone);
  // A "stage" that scrambles the interior: worse, so undone bit-identically.
  std::vector<double> scrambled = map_test::scrambled_target(c.mesh, c.bnd, 7, 0.3);
  const std::size_t scrambled_bad = volmap::count_nonpositive(scrambled, c.mesh.tets);
  REQUIRE(scrambled_bad > 0);
  s.set_target_xyz(scrambled);
  const volmap::StageVerdict worse = judge.judge();
  CHECK(worse.undone);
  CHECK(worse.measured == scrambled_bad);
  CHECK(worse.kept == 0);
  CHECK(s.target_xyz() == good);
  CHECK(judge.best() == 0);
  // From a fresh judge on the scrambled state, a stage that repairs part of it is kept.
  volmap::StageJudge judge2(s);
  s.set_target_xyz(scrambled);
  CHECK(judge2.judge().kept == scrambled_bad);
  std::vector<double> half = scrambled;
  for (std::size_t v = 0; v < c.bnd.size() / 2; ++v)
    for (int i = 0; i < 3; ++i) half[3 * v + i] = good[3 * v + i];
  const std::size_t half_bad = volmap::count_nonpositive(half, c.mesh.tets);
  REQUIRE(half_bad < scrambled_bad);
  s.set_target_xyz(half);
  const volmap::StageVerdict better = judge2.judge();
  CHECK_FALSE(better.undone);
  CHECK(better.kept == half_bad);
  CHECK(s.target_xyz() == half);
  // An equal count is kept too (the new positions stay): a tiny move of an interior vertex.
  std::vector<double> moved = half;
  std::size_t v = 0;
  while (c.bnd[v]) ++v;
  moved[3 * v] += 1e-9;
  REQUIRE(volmap::count_nonpositive(moved, c.mesh.tets) == half_bad);
  s.set_target_xyz(moved);
  CHECK_FALSE(judge2.judge().undone);
  CHECK(s.target_xyz() == moved);
}

TEST_CASE("StageJudge: a worsening stage that refined the mesh is undone with the mesh") {
  AffineCase c(3);
  volmap::MapState s(c.mesh, c.map);
  volmap::StageJudge judge(s);
  volmap::place_by_tutte(s);
  REQUIRE(judge.judge().kept == 0);
  const std::vector<std::uint32_t> tets = s.source.tet_vertex_array();
  const std::vector<double> xyz = s.source.positions(), target = s.target_xyz();
  const std::vector<std::uint8_t> locked = s.locked.data();
  // Split an interior tet at its centroid and give the new vertex a target far outside: worse.
  std::uint32_t t = 0;
  while (c.bnd[c.mesh.tets[4 * t]] && c.bnd[c.mesh.tets[4 * t + 1]] && c.bnd[c.mesh.tets[4 * t + 2]] && c.bnd[c.mesh.tets[4 * t + 3]]) ++t;
  double p[3] = {0, 0, 0};
  for (int i = 0; i < 4; ++i)
    for (int d = 0; d < 3; ++d) p[d] += 0.25 * c.mesh.xyz[3 * c.mesh.tets[4 * t + i] + d];
  const volmap::VertexId w = s.source.split_tet(volmap::TetId(t), p);
  s.target[w] = {10.0, 10.0, 10.0};
  CHECK(s.locked[w] == 0);  // a new vertex starts unlocked
  REQUIRE(s.source.num_tets() == c.mesh.num_tets() + 3);
  const volmap::StageVerdict v = judge.judge();
  CHECK(v.undone);
  CHECK(v.measured > 0);
  CHECK(v.kept == 0);
  CHECK(s.source.tet_vertex_array() == tets);
  CHECK(s.source.positions() == xyz);
  CHECK(s.target_xyz() == target);
  CHECK(s.locked.data() == locked);
  CHECK(s.source.check_invariants(true).ok);
}

TEST_CASE("compute_volume_map: an expired time budget runs no untangling stage and certifies nothing it did not check") {
  AffineCase c(4);
  std::vector<double> initial = map_test::scrambled_target(c.mesh, c.bnd, 3, 0.3);
  REQUIRE(volmap::count_nonpositive(initial, c.mesh.tets) > 0);
  volmap::VolumeMapOptions o;
  o.initial_xyz = initial;
  o.time_limit_seconds = 1e-9;  // over before the first untangling stage
  o.whole_mesh_cone = false;     // the last resort would certify this convex case (test_whole_mesh_cone.cpp)
  const volmap::VolumeMapResult r = volmap::compute_volume_map(c.mesh, c.map, o);
  REQUIRE(r.stages.size() == 2);
  CHECK(r.stages[0].name == "feasibility");
  CHECK(r.stages[1].name == "initial");
  CHECK(r.target_xyz == initial);
  CHECK_FALSE(r.certified);
  CHECK(r.nonpositive == volmap::count_nonpositive(initial, c.mesh.tets));
  // The same without a limit is certified, and the result's arrays pass the exact check.
  o.time_limit_seconds = 0;
  const volmap::VolumeMapResult full = volmap::compute_volume_map(c.mesh, c.map, o);
  CHECK(full.certified);
  CHECK(volmap::count_nonpositive(full.target_xyz, full.source.tets) == 0);
  CHECK(full.stages.size() > 2);
}
