// Splitting the edges of non-positive tets (bad_tet_split.hpp, docs/mapping.md §8 step 8), on a
// scrambled Kuhn grid. Oracles computed here from the flat arrays before the split: the interior
// edges of the inverted tets (edges of ∂M excluded, found from the boundary faces), the oriented
// boundary, exact source positivity of every tet afterwards, and the exact count (a child of an
// inverted parent at the edge's target midpoint has half its volume: the count cannot drop).
#include <doctest/doctest.h>

#include <volmap/core/boundary_faces.hpp>
#include <volmap/volume/bad_tet_split.hpp>
#include <volmap/volume/map_stages.hpp>
#include <volmap/predicates.hpp>

#include "map_test_meshes.hpp"
#include "mesh_test_util.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

TEST_CASE("split edges of non-positive tets: every interior edge of an inverted tet, the source stays positive, dM untouched") {
  const int n = 4;
  const volmap::TetMeshData grid = map_test::kuhn_grid(n);
  const auto bnd = map_test::grid_boundary_flags(n);
  const std::vector<double> target = map_test::scrambled_target(grid, bnd, 11, 0.35);
  volmap::MapState state(grid, map_test::boundary_map_of(bnd, target), target);
  const std::size_t bad_before = state.count_nonpositive();
  REQUIRE(bad_before > 0);

  // The oracle: interior edges of the inverted tets, from the flat arrays.
  std::set<std::array<std::uint32_t, 2>> boundary_edges, expected;
  for (std::uint64_t h : volmap::boundary_half_faces(grid)) {
    const auto f = volmap::half_face_vertices(grid, h);
    for (int i = 0; i < 3; ++i) boundary_edges.insert({std::min(f[i], f[(i + 1) % 3]), std::max(f[i], f[(i + 1) % 3])});
  }
  for (std::size_t t = 0; t < grid.num_tets(); ++t) {
    const std::uint32_t* v = &grid.tets[4 * t];
    if (volmap::orient3d(&target[3 * v[0]], &target[3 * v[1]], &target[3 * v[2]], &target[3 * v[3]]) > 0) continue;
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        const std::array<std::uint32_t, 2> e = {std::min(v[a], v[b]), std::max(v[a], v[b])};
        if (!boundary_edges.count(e)) expected.insert(e);
      }
  }
  const auto boundary = mesh_test::oriented_boundary(state.source);
  const std::size_t nv = state.source.num_vertices();

  const volmap::BadTetSplitResult r = volmap::split_edges_of_nonpositive_tets(state);
  MESSAGE("scrambled Kuhn grid " << n << ": " << r.bad_tets << " inverted tets, " << r.edges_split << " edges split, tets "
                                 << r.tets_before << " -> " << r.tets_after);
  CHECK(r.bad_tets == bad_before);
  CHECK(r.edges_split + r.edges_skipped == expected.size());
  CHECK(r.edges_skipped == 0);
  CHECK(state.source.num_vertices() == nv + r.edges_split);
  CHECK(r.tets_after > r.tets_before);
  CHECK(state.source.check_invariants(true).ok);
  CHECK(mesh_test::oriented_boundary(state.source) == boundary);
  // Every source tet exactly positive; the new vertices are free and sit at the midpoint of the
  // targets of the edge they split (the two old neighbours whose source midpoint they are).
  const volmap::TetMeshData after = state.source.to_data();
  CHECK(volmap::count_nonpositive(after.xyz, after.tets) == 0);
  const std::vector<double> x = state.target_xyz();
  for (std::size_t w = nv; w < state.source.num_vertices(); ++w) {
    CHECK(state.locked.data()[w] == 0);
    bool at_a_midpoint = false;
    for (const auto& e : expected) {
      bool source_mid = true, target_mid = true;
      for (int i = 0; i < 3; ++i) {
        source_mid = source_mid && after.xyz[3 * w + i] == 0.5 * (after.xyz[3 * e[0] + i] + after.xyz[3 * e[1] + i]);
        target_mid = target_mid && x[3 * w + i] == 0.5 * (x[3 * e[0] + i] + x[3 * e[1] + i]);
      }
      at_a_midpoint = at_a_midpoint || (source_mid && target_mid);
    }
    CHECK(at_a_midpoint);
  }
  CHECK(state.count_nonpositive() >= bad_before);
}
