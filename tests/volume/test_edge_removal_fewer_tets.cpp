// Step 14c (docs/mapping.md §8): 3-2 flips that take tets out of a certified map
// (edge_removal_fewer_tets.hpp). The case is the smallest one there is: a triangle x, y, z with an
// apex a on each side of it, filled by the three tets around the axis (a, b). Oracles: in the
// identity map the two tets on the triangle tile the same bipyramid, so the flip must leave a map
// that check_map (exact orient3d in both spaces) certifies, with the same boundary faces and one tet
// fewer; when the map lifts b above the triangle's plane the three axis tets stay positive (b only
// slides along the axis) but the tet (z, y, x, b) would be inverted, so nothing may be flipped.
#include <doctest/doctest.h>

#include <volmap/check/map_check.hpp>
#include <volmap/core/boundary_faces.hpp>
#include <volmap/predicates.hpp>
#include <volmap/volume/edge_removal_fewer_tets.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace {

using Face = std::array<std::uint32_t, 3>;

// Vertices x, y, z, a, b = 0..4; the triangle in the plane z = 0 around its centroid c, a = c + e_z,
// b = c - e_z; tets (x, y, a, b), (y, z, a, b), (z, x, a, b), each turned positive.
volmap::TetMeshData axis_bipyramid() {
  const double c = 1.0 / 3.0;
  volmap::TetMeshData m;
  m.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, c, c, 1, c, c, -1};
  m.tets = {0, 1, 3, 4, 1, 2, 3, 4, 2, 0, 3, 4};
  for (std::size_t t = 0; t < m.num_tets(); ++t) {
    std::uint32_t* v = &m.tets[4 * t];
    if (volmap::orient3d(&m.xyz[3 * v[0]], &m.xyz[3 * v[1]], &m.xyz[3 * v[2]], &m.xyz[3 * v[3]]) < 0) std::swap(v[0], v[1]);
  }
  return m;
}

std::vector<Face> sorted_boundary(const volmap::TetMeshData& m) {
  std::vector<Face> faces;
  for (std::uint64_t hf : volmap::boundary_half_faces(m)) {
    Face f = volmap::half_face_vertices(m, hf);
    std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());  // same cycle, smallest first
    faces.push_back(f);
  }
  std::sort(faces.begin(), faces.end());
  return faces;
}

}  // namespace

TEST_CASE("step 14c: a degree-3 edge valid to flip in both spaces goes, one tet fewer, the map still certified") {
  const volmap::TetMeshData m = axis_bipyramid();
  volmap::TetMeshData flipped = m;
  std::vector<double> target = m.xyz;  // the identity map
  std::vector<std::uint8_t> locked(m.num_vertices(), 1);
  const volmap::EdgeRemovalResult r = volmap::remove_degree3_edges(flipped, locked, target);
  CHECK(r.flips == 1);
  CHECK(r.tets_before == 3);
  CHECK(r.tets_after == 2);
  REQUIRE(flipped.num_tets() == 2);
  CHECK(flipped.xyz == m.xyz);  // no vertex moved, none added or removed
  volmap::TetMeshData mapped = flipped;
  mapped.xyz = target;
  CHECK(volmap::check_map(flipped, mapped).certified());
  CHECK(sorted_boundary(flipped) == sorted_boundary(m));
  for (std::size_t t = 0; t < 2; ++t) {  // the axis edge (a, b) is gone: no tet holds both
    const std::uint32_t* v = &flipped.tets[4 * t];
    CHECK_FALSE((std::count(v, v + 4, 3u) == 1 && std::count(v, v + 4, 4u) == 1));
  }
}

TEST_CASE("step 14c: no flip when the map would invert one of the two new tets") {
  const volmap::TetMeshData m = axis_bipyramid();
  std::vector<double> target = m.xyz;
  target[3 * 4 + 2] = 0.5;  // b slides up the axis, above the triangle, below a
  volmap::TetMeshData mapped = m;
  mapped.xyz = target;
  REQUIRE(volmap::check_map(m, mapped).certified());  // the three axis tets stay positive
  volmap::TetMeshData kept = m;
  std::vector<std::uint8_t> locked(m.num_vertices(), 1);
  const volmap::EdgeRemovalResult r = volmap::remove_degree3_edges(kept, locked, target);
  CHECK(r.flips == 0);
  CHECK(kept.tets == m.tets);
  CHECK(target == mapped.xyz);
}
