// refinement_checks.hpp — what every refinement of a mapped pair must keep (cone repair, the
// whole-mesh cone): original vertices bit-exact, exact positive source and target, the same oriented
// boundary triangles, boundary targets untouched, a valid manifold tet mesh; and what a refused one
// must keep: everything.
#pragma once

#include <volmap/check/tetmesh_checks.hpp>
#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/mesh_data.hpp>
#include <volmap/predicates.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace refinement_checks {

// The oriented boundary triangles of m, each rotated to start at its smallest id, sorted.
inline std::vector<std::array<std::uint32_t, 3>> boundary_triangles(const volmap::TetMeshData& m) {
  std::vector<std::array<std::uint32_t, 3>> out;
  for (auto hf : volmap::boundary_half_faces(m)) {
    auto f = volmap::half_face_vertices(m, hf);
    std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());  // keeps the orientation
    out.push_back(f);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The repaired pair is a valid refinement: original vertices kept bit-exactly, exact positive source
// and target, same oriented boundary triangles, boundary targets untouched, manifold genus-0 mesh.
inline void check_refinement(const volmap::TetMeshData& before, const std::vector<double>& target_before, const std::vector<std::uint8_t>& bnd_before,
                      const volmap::TetMeshData& after, const std::vector<double>& target_after, const std::vector<std::uint8_t>& bnd_after) {
  REQUIRE(after.num_vertices() >= before.num_vertices());
  REQUIRE(target_after.size() == after.xyz.size());
  REQUIRE(bnd_after.size() == after.num_vertices());
  CHECK(std::equal(before.xyz.begin(), before.xyz.end(), after.xyz.begin()));
  for (std::size_t v = 0; v < before.num_vertices(); ++v) {
    CHECK(bnd_after[v] == bnd_before[v]);
    if (bnd_before[v])
      for (int i = 0; i < 3; ++i) CHECK(target_after[3 * v + i] == target_before[3 * v + i]);
  }
  for (std::size_t v = before.num_vertices(); v < after.num_vertices(); ++v) CHECK(bnd_after[v] == 0);
  CHECK(volmap::count_nonpositive(after.xyz, after.tets) == 0);
  CHECK(volmap::count_nonpositive(target_after, after.tets) == 0);
  CHECK(boundary_triangles(after) == boundary_triangles(before));
  CHECK(after.tet_labels.size() == after.num_tets());
  const auto report = volmap::check_tet_mesh(after);
  for (const auto& c : report.checks) CHECK_MESSAGE(c.passed, c.key << ": " << c.detail);
}

// A refusal left everything exactly as it was: tets, labels, positions, targets, locked flags.
inline void check_unchanged(const volmap::TetMeshData& before, const std::vector<double>& target_before, const std::vector<std::uint8_t>& bnd_before,
                            const volmap::TetMeshData& after, const std::vector<double>& target_after, const std::vector<std::uint8_t>& bnd_after) {
  CHECK(after.tets == before.tets);
  CHECK(after.tet_labels == before.tet_labels);
  CHECK(after.xyz == before.xyz);
  CHECK(target_after == target_before);
  CHECK(bnd_after == bnd_before);
}

}  // namespace refinement_checks
