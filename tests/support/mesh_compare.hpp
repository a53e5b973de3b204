// Comparing meshes in tests: coordinates bit for bit (memcmp, so -0.0 != 0.0 and NaN payloads count)
// and the id and label arrays exactly.
#pragma once

#include <doctest/doctest.h>
#include <volmap/core/mesh_data.hpp>

#include <cstring>
#include <vector>

namespace volmap_test {

inline bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

inline void check_same_mesh(const volmap::TetMeshData& a, const volmap::TetMeshData& b) {
  CHECK(same_bits(a.xyz, b.xyz));
  CHECK(a.tets == b.tets);
  CHECK(a.vertex_labels == b.vertex_labels);
  CHECK(a.tet_labels == b.tet_labels);
}

}  // namespace volmap_test
