// Synthetic tet meshes for the mapping tests (generated, no data files): a Kuhn-subdivided grid of
// the unit cube, oriented VOLMAP-positive (orient3d(v0,v1,v2,v3) > 0), boundary flags per vertex.
#pragma once

#include <volmap/mesh_data.hpp>
#include <volmap/predicates.hpp>

#include <cstdint>
#include <random>
#include <utility>
#include <vector>

namespace map_test {

// n×n×n cubes of side 1/n, 6 tets each (Kuhn split along the main diagonal).
inline volmap::TetMeshData kuhn_grid(int n) {
  volmap::TetMeshData m;
  auto id = [n](int i, int j, int k) { return std::uint32_t((i * (n + 1) + j) * (n + 1) + k); };
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) {
        m.xyz.push_back(double(i) / n);
        m.xyz.push_back(double(j) / n);
        m.xyz.push_back(double(k) / n);
      }
  static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        for (const auto& p : perms) {
          int c[3] = {i, j, k};
          std::uint32_t t[4];
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            c[p[s]] += 1;
            t[s + 1] = id(c[0], c[1], c[2]);
          }
          if (volmap::orient3d(&m.xyz[3 * t[0]], &m.xyz[3 * t[1]], &m.xyz[3 * t[2]], &m.xyz[3 * t[3]]) < 0)
            std::swap(t[2], t[3]);
          for (auto v : t) m.tets.push_back(v);
        }
  m.vertex_labels.assign(m.num_vertices(), 0);
  m.tet_labels.assign(m.num_tets(), 0);
  return m;
}

inline std::vector<std::uint8_t> grid_boundary_flags(int n) {
  std::vector<std::uint8_t> b;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k)
        b.push_back(i == 0 || j == 0 || k == 0 || i == n || j == n || k == n);
  return b;
}

// Exact number of tets with orient3d <= 0.
inline std::size_t exact_bad(const std::vector<double>& xyz, const std::vector<std::uint32_t>& tets) {
  auto c = volmap::orient3d_tets(xyz.data(), xyz.size() / 3, tets.data(), tets.size() / 4, nullptr);
  return c.zero + c.negative;
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

}  // namespace map_test
