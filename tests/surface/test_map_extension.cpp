// Carrying a boundary map across midpoint edge splits: the identity map of a Kuhn grid, split
// twice along one boundary edge (the second split cuts an edge made by the first, so the first new
// vertex loses a parent as neighbour), extends to the identity on the new vertices.
#include <doctest/doctest.h>
#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/error.hpp>
#include <volmap/testing/generate.hpp>
#include <volmap/surface/map_extension.hpp>
#include <volmap/core/tet_mesh.hpp>

namespace {
volmap::BoundaryMap identity_map(const volmap::TetMeshData& mesh) {
  volmap::BoundaryMap map;
  for (const auto v : volmap::boundary_vertex_ids(mesh)) {
    map.vids.push_back(v);
    map.xyz.insert(map.xyz.end(), &mesh.xyz[3 * v], &mesh.xyz[3 * v] + 3);
  }
  return map;
}
}  // namespace

TEST_CASE("identity map extends to the identity across repeated midpoint splits") {
  const auto grid = volmap::generate_kuhn_grid(2, 2, 2);
  const auto map = identity_map(grid);
  volmap::TetMesh mesh(grid);
  // Boundary edge (0,1) on the grid's corner (vertex 0 = origin, vertex 1 = (1,0,0)).
  const volmap::VertexId a(0), b(1);
  const double* xa = &grid.xyz[0];
  const double* xb = &grid.xyz[3];
  const double mid[3] = {0.5 * (xa[0] + xb[0]), 0.5 * (xa[1] + xb[1]), 0.5 * (xa[2] + xb[2])};
  const volmap::VertexId v = mesh.split_edge(a, b, mid);
  const double quarter[3] = {0.5 * (xa[0] + mid[0]), 0.5 * (xa[1] + mid[1]), 0.5 * (xa[2] + mid[2])};
  mesh.split_edge(a, v, quarter);  // the new vertex sits between a and v: a is no longer v's neighbour
  const auto refined = mesh.to_data();
  REQUIRE(refined.num_vertices() == grid.num_vertices() + 2);
  const auto extended = volmap::extend_boundary_map_over_splits(map, grid, refined);
  CHECK(extended.size() == map.size() + 2);
  for (std::size_t i = 0; i < extended.size(); ++i)
    for (int k = 0; k < 3; ++k) CHECK(extended.xyz[3 * i + k] == refined.xyz[3 * extended.vids[i] + k]);

  // A new boundary vertex that is not a midpoint is refused.
  auto moved = refined;
  moved.xyz[3 * (refined.num_vertices() - 1)] += 1e-3;
  CHECK_THROWS_AS(volmap::extend_boundary_map_over_splits(map, grid, moved), volmap::Error);
}
