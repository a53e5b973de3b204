// Flips that remove non-positive tets (bad_tet_flip.hpp). Oracles: the two triangulations of five
// points (the 3-2 and 2-3 flips' answers are known from the construction), exact orient3d of every
// tet in both geometries, and on a scrambled Kuhn grid the invariants a flip keeps (vertices,
// targets, oriented boundary, source positivity) and the count, which every move lowers.
#include <doctest/doctest.h>

#include <volmap/volume/bad_tet_flip.hpp>
#include <volmap/predicates.hpp>

#include "map_test_meshes.hpp"
#include "mesh_test_util.hpp"

#include <array>
#include <vector>

namespace {

// Five points: triangle a b c in z = 0 (ids 0 1 2), d above (3), e below (4) in the source.
const std::vector<double> kFivePoints = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0.2, 0.2, 1, 0.2, 0.2, -1};

// The five points with these tets, each reordered to be positive.
volmap::TetMeshData five_point_mesh(const std::vector<std::array<std::uint32_t, 4>>& tets) {
  volmap::TetMeshData m;
  m.xyz = kFivePoints;
  for (std::array<std::uint32_t, 4> t : tets) {
    if (volmap::orient3d(&m.xyz[3 * t[0]], &m.xyz[3 * t[1]], &m.xyz[3 * t[2]], &m.xyz[3 * t[3]]) < 0) std::swap(t[0], t[1]);
    m.tets.insert(m.tets.end(), t.begin(), t.end());
  }
  return m;
}

// Every vertex of the five-point meshes is on ∂M: the whole target is the prescribed map.
volmap::BoundaryMap map_all(const std::vector<double>& target) {
  volmap::BoundaryMap map;
  for (std::uint32_t v = 0; v < target.size() / 3; ++v) map.vids.push_back(v);
  map.xyz = target;
  return map;
}

std::size_t nonpositive_source_tets(const volmap::MapState& s) {
  const volmap::TetMeshData d = s.source.to_data();
  return volmap::count_nonpositive(d.xyz, d.tets);
}

}  // namespace

TEST_CASE("flip bad tets: a 3-2 flip removes the edge whose three tets are tangled in the target") {
  const volmap::TetMeshData m = five_point_mesh({{3, 4, 0, 1}, {3, 4, 1, 2}, {3, 4, 2, 0}});
  std::vector<double> target = kFivePoints;
  target[12] = 2, target[13] = 2, target[14] = -0.1;  // e moves: the line de misses triangle abc
  volmap::MapState state(m, map_all(target));
  REQUIRE(state.count_nonpositive() > 0);
  const volmap::BadTetFlipResult r = volmap::flip_nonpositive_tets(state);
  CHECK(r.edges_removed == 1);
  CHECK(r.faces_flipped == 0);
  CHECK(r.bad_after == 0);
  CHECK(state.count_nonpositive() == 0);
  CHECK(state.source.num_tets() == 2);  // the two tets on triangle abc
  CHECK(nonpositive_source_tets(state) == 0);
  CHECK(state.source.check_invariants(true).ok);
}

TEST_CASE("flip bad tets: a 2-3 flip when d and e end on one side of abc with the line de through it") {
  const volmap::TetMeshData m = five_point_mesh({{0, 1, 2, 3}, {0, 1, 2, 4}});
  std::vector<double> target = kFivePoints;
  target[14] = 0.5;  // e above abc, below d: the tet (a, b, c, e) inverts, the three around de do not
  volmap::MapState state(m, map_all(target));
  REQUIRE(state.count_nonpositive() == 1);
  const volmap::BadTetFlipResult r = volmap::flip_nonpositive_tets(state);
  CHECK(r.faces_flipped == 1);
  CHECK(r.bad_after == 0);
  CHECK(state.source.num_tets() == 3);
  CHECK(nonpositive_source_tets(state) == 0);
  CHECK(state.source.check_invariants(true).ok);
}

TEST_CASE("flip bad tets: no admissible move leaves the state as it was") {
  const volmap::TetMeshData m = five_point_mesh({{0, 1, 2, 3}, {0, 1, 2, 4}});
  std::vector<double> target = kFivePoints;
  target[14] = 2;  // e above d: the line de still crosses abc, but tets around de would invert
  volmap::MapState state(m, map_all(target));
  const std::size_t bad = state.count_nonpositive();
  REQUIRE(bad == 1);
  const volmap::BadTetFlipResult r = volmap::flip_nonpositive_tets(state);
  CHECK(r.edges_removed + r.faces_flipped == 0);
  CHECK(state.count_nonpositive() == bad);
  CHECK(state.source.num_tets() == 2);
}

TEST_CASE("flip bad tets on a scrambled Kuhn grid: each move lowers the count; vertices, targets and dM stay") {
  const int n = 4;
  const volmap::TetMeshData grid = map_test::kuhn_grid(n);
  const auto bnd = map_test::grid_boundary_flags(n);
  for (unsigned seed : {3u, 11u, 17u}) {
    const std::vector<double> target = map_test::scrambled_target(grid, bnd, seed, 0.35);
    volmap::MapState state(grid, map_test::boundary_map_of(bnd, target), target);
    const std::size_t bad_before = state.count_nonpositive();
    REQUIRE(bad_before > 0);
    const auto boundary = mesh_test::oriented_boundary(state.source);
    const std::vector<double> x_before = state.target_xyz();
    const volmap::BadTetFlipResult r = volmap::flip_nonpositive_tets(state);
    MESSAGE("seed " << seed << ": " << bad_before << " -> " << r.bad_after << " non-positive, " << r.edges_removed
                    << " edge removals, " << r.faces_flipped << " 2-3 flips, tets " << r.tets_before << " -> " << r.tets_after);
    CHECK(r.bad_before == bad_before);
    CHECK(r.bad_after == state.count_nonpositive());
    CHECK(r.bad_after + r.edges_removed + r.faces_flipped <= bad_before);
    CHECK(state.target_xyz() == x_before);
    CHECK(state.source.num_vertices() == grid.num_vertices());
    CHECK(mesh_test::oriented_boundary(state.source) == boundary);
    CHECK(nonpositive_source_tets(state) == 0);
    CHECK(state.source.check_invariants(true).ok);
  }
}
