// Shared helpers of the tet-mesh tests: brute-force oracles (std::map based, deliberately naive and
// independent of the library's counting-sort code) and a tiny Medit reader for the shared data.
#pragma once

#include <volmap/core/local_tables.hpp>
#include <volmap/core/mesh_data.hpp>
#include <volmap/core/tet_mesh.hpp>
#include <volmap/predicates.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace mesh_test {

using Triple = std::array<std::uint32_t, 3>;

inline Triple sorted_face(const std::vector<std::uint32_t>& tv, std::size_t h) {
  const std::uint32_t* p = &tv[4 * (h / 4)];
  Triple f;
  for (int k = 0; k < 3; ++k) f[k] = p[volmap::kTetFace[h % 4][k]];
  std::sort(f.begin(), f.end());
  return f;
}

// Every distinct face -> its half-faces.
inline std::map<Triple, std::vector<std::uint32_t>> brute_faces(const std::vector<std::uint32_t>& tv) {
  std::map<Triple, std::vector<std::uint32_t>> m;
  for (std::size_t h = 0; h < tv.size(); ++h)
    if (tv[4 * (h / 4)] != 0xFFFFFFFFu) m[sorted_face(tv, h)].push_back(std::uint32_t(h));
  return m;
}

// Every edge (sorted pair) -> sorted tets containing it.
inline std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> brute_edges(
    const std::vector<std::uint32_t>& tv) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> m;
  for (std::size_t t = 0; t < tv.size() / 4; ++t) {
    if (tv[4 * t] == 0xFFFFFFFFu) continue;
    for (int k = 0; k < 6; ++k) {
      std::uint32_t a = tv[4 * t + volmap::kTetEdge[k][0]], b = tv[4 * t + volmap::kTetEdge[k][1]];
      if (a > b) std::swap(a, b);
      m[{a, b}].push_back(std::uint32_t(t));
    }
  }
  return m;
}

// The oriented boundary triangles of a mesh's live tets (each rotated to start at its smallest id),
// from the brute-force face map (independent of the mesh's own boundary cache).
inline std::set<Triple> oriented_boundary(const volmap::TetMesh& m) {
  std::set<Triple> out;
  const auto& tv = m.tet_vertex_array();
  for (const auto& [face, hfs] : brute_faces(tv)) {
    if (hfs.size() != 1) continue;
    Triple f;
    for (int k = 0; k < 3; ++k) f[k] = tv[4 * (hfs[0] / 4) + volmap::kTetFace[hfs[0] % 4][k]];
    std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
    out.insert(f);
  }
  return out;
}

inline int orient_tet(const std::vector<double>& xyz, const std::uint32_t* p) {
  return volmap::orient3d(&xyz[3 * std::size_t(p[0])], &xyz[3 * std::size_t(p[1])], &xyz[3 * std::size_t(p[2])],
                          &xyz[3 * std::size_t(p[3])]);
}

}  // namespace mesh_test
