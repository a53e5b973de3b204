// Synthetic tet meshes for the mapping tests (generated, no data files): the library's Kuhn grid of
// the unit cube (volmap/generate.hpp: VOLMAP-positive tets, vertex (i,j,k) = i + (n+1)(j + (n+1)k)
// at (i/n, j/n, k/n)) and its boundary flags per vertex.
#pragma once

#include <volmap/testing/generate.hpp>
#include <volmap/core/mesh_data.hpp>
#include <volmap/predicates.hpp>

#include <cstdint>
#include <random>
#include <utility>
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

// Boundary mapped by an orientation-preserving affine map; interior moved randomly by ±amount.
inline std::vector<double> scrambled_target(const volmap::TetMeshData& m, const std::vector<std::uint8_t>& bnd, unsigned seed, double amount) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  std::vector<double> t(m.xyz.size());
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    const double x = m.xyz[3 * v], y = m.xyz[3 * v + 1], z = m.xyz[3 * v + 2];
    t[3 * v] = 2 * x + 0.3 * y;
    t[3 * v + 1] = y + 0.2 * z;
    t[3 * v + 2] = 0.5 * z + 0.1 * x;
    if (!bnd[v])
      for (int i = 0; i < 3; ++i) t[3 * v + i] += u(rng);
  }
  return t;
}

// The boundary map of `target` on the vertices flagged in `bnd` (file order: increasing id).
inline volmap::BoundaryMap boundary_map_of(const std::vector<std::uint8_t>& bnd, const std::vector<double>& target) {
  volmap::BoundaryMap m;
  for (std::size_t v = 0; v < bnd.size(); ++v)
    if (bnd[v]) {
      m.vids.push_back(std::uint32_t(v));
      for (int i = 0; i < 3; ++i) m.xyz.push_back(target[3 * v + i]);
    }
  return m;
}

}  // namespace map_test
