// Synthetic tet meshes for the mapping tests (generated, no data files): the library's Kuhn grid of
// the unit cube (volmap/generate.hpp: VOLMAP-positive tets, vertex (i,j,k) = i + (n+1)(j + (n+1)k)
// at (i/n, j/n, k/n)) and its boundary flags per vertex.
#pragma once

#include <volmap/generate.hpp>
#include <volmap/mesh_data.hpp>

#include <cstdint>
#include <vector>

namespace map_test {

// n×n×n cubes of side 1/n, 6 tets each.
inline volmap::TetMeshData kuhn_grid(int n) { return volmap::generate_kuhn_unit_cube(std::size_t(n)); }

// 1 for the vertices of kuhn_grid(n) on the cube's boundary (the test is symmetric in i, j, k, so it
// does not depend on which index runs fastest).
inline std::vector<std::uint8_t> grid_boundary_flags(int n) {
  std::vector<std::uint8_t> b;
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        b.push_back(i == 0 || j == 0 || k == 0 || i == n || j == n || k == n);
  return b;
}

}  // namespace map_test
