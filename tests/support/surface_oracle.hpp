// tests/support/surface_oracle.hpp — independent oracle for "closed, consistently oriented, genus-0
// surface with outward triangles": every directed edge once and its reverse once, Euler
// characteristic 2 on one component, positive enclosed volume. Written from scratch (directed-edge
// sort + union-find), sharing no code with the library's surface checks.
#pragma once

#include <volmap/io/io_surface.hpp>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

namespace volmap_test {

// Empty when `s` is a closed, oriented, connected genus-0 surface enclosing positive volume; else why not.
inline std::string closed_genus0_problem(const volmap::SurfaceData& s) {
  const std::size_t nv = s.num_vertices(), nf = s.num_triangles();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> directed;
  directed.reserve(3 * nf);
  for (std::size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) directed.emplace_back(s.tris[3 * f + k], s.tris[3 * f + (k + 1) % 3]);
  std::sort(directed.begin(), directed.end());
  if (std::adjacent_find(directed.begin(), directed.end()) != directed.end()) return "a directed edge appears twice";
  for (const auto& [a, b] : directed)
    if (!std::binary_search(directed.begin(), directed.end(), std::make_pair(b, a))) return "an edge has no twin";
  std::vector<std::uint32_t> parent(nv);
  std::iota(parent.begin(), parent.end(), 0u);
  const auto find = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  std::vector<bool> used(nv, false);
  for (const auto& [a, b] : directed) {
    parent[find(a)] = find(b);
    used[a] = used[b] = true;
  }
  std::size_t components = 0, used_vertices = 0;
  for (std::uint32_t v = 0; v < nv; ++v)
    if (used[v]) {
      ++used_vertices;
      components += find(v) == v;
    }
  if (components != 1) return std::to_string(components) + " components";
  const long euler = long(used_vertices) - long(directed.size() / 2) + long(nf);
  if (euler != 2) return "Euler characteristic " + std::to_string(euler);
  double volume = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    const double* a = &s.xyz[3 * s.tris[3 * f]];
    const double* b = &s.xyz[3 * s.tris[3 * f + 1]];
    const double* c = &s.xyz[3 * s.tris[3 * f + 2]];
    volume += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  if (!(volume > 0)) return "enclosed volume not positive (inward triangles)";
  return {};
}

}  // namespace volmap_test
