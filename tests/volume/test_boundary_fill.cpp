// Fewer tets after refinement (docs/mapping.md §4.1, §8 step 14): the fill search of
// steiner_free_fill.hpp, the vertex removal of vertex_removal.hpp and the mapper's step 14.
// Oracles: Schönhardt's twisted prism has no tetrahedralisation without a new vertex (Schönhardt
// 1928) while the prism twisted the other way has one of 4 tets (its diagonals all turn one way:
// one interior edge is needed); a triangulated cube without
// interior vertices has 5 or 6 tets; every fill is re-checked by check_map (exact orient3d in both
// spaces) and its boundary faces compared with the surface it was asked to fill; the coarse T-shaped
// polycube part mapped onto the tetrahedron grows by more than a quarter without step 14 (its
// tets all touch ∂M and some are inverted by the map) and not at all with it.
#include <doctest/doctest.h>

#include <volmap/check/map_check.hpp>
#include <volmap/core/boundary_faces.hpp>
#include <volmap/predicates.hpp>
#include <volmap/surface/domain.hpp>
#include <volmap/surface/surface_map.hpp>
#include <volmap/testing/generate.hpp>
#include <volmap/volume/boundary_fill.hpp>
#include <volmap/volume/steiner_free_fill.hpp>
#include <volmap/volume/vertex_removal.hpp>
#include <volmap/volume/volume_map.hpp>

#include "map_test_meshes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

namespace {

using Face = std::array<std::uint32_t, 3>;

// A triangular prism: bottom a_i = 0..2 at z = 0, top b_i = 3..5 at z = 1 turned by `twist`
// radians; each side quad split by the diagonal (a_i, b_{i+1}). Faces outward (the axis point
// (0, 0, 0.5) on their positive side).
struct Prism {
  std::vector<double> xyz;
  std::vector<Face> faces;
};

Prism prism(double twist) {
  Prism p;
  const double pi = std::acos(-1.0);
  for (int level = 0; level < 2; ++level)
    for (int i = 0; i < 3; ++i) {
      const double a = 2 * pi * i / 3 + (level ? twist : 0.0);
      p.xyz.insert(p.xyz.end(), {std::cos(a), std::sin(a), double(level)});
    }
  std::vector<Face> faces = {{0, 1, 2}, {3, 4, 5}};
  for (std::uint32_t i = 0; i < 3; ++i) {
    const std::uint32_t a0 = i, a1 = (i + 1) % 3, b0 = 3 + i, b1 = 3 + (i + 1) % 3;
    faces.push_back({a0, a1, b1});
    faces.push_back({a0, b1, b0});
  }
  const double axis[3] = {0, 0, 0.5};
  for (Face f : faces) {
    if (volmap::orient3d(&p.xyz[3 * f[0]], &p.xyz[3 * f[1]], &p.xyz[3 * f[2]], axis) < 0) std::swap(f[1], f[2]);
    p.faces.push_back(f);
  }
  return p;
}

// Whether the prism's side diagonals are reflex edges of the surface (Schönhardt's polyhedron):
// the two faces of a side quad meet at its diagonal, reflex when the far vertex of one lies outside
// the inner half-space of the other.
bool diagonals_reflex(const Prism& p) {
  const Face& f = p.faces[2];
  const Face& g = p.faces[3];
  std::uint32_t far = 0;
  for (std::uint32_t v : g)
    if (std::find(f.begin(), f.end(), v) == f.end()) far = v;
  return volmap::orient3d(&p.xyz[3 * f[0]], &p.xyz[3 * f[1]], &p.xyz[3 * f[2]], &p.xyz[3 * far]) < 0;
}

std::set<std::array<std::uint32_t, 3>> sorted_faces(const std::vector<Face>& faces) {
  std::set<std::array<std::uint32_t, 3>> out;
  for (Face f : faces) {
    std::sort(f.begin(), f.end());
    out.insert(f);
  }
  return out;
}

// The fill as a mesh of the given vertices, checked independently: exact positivity in both
// spaces (check_map with the target as the map of every vertex) and its boundary = the surface.
void check_fill(const std::vector<Face>& surface, const std::vector<double>& source, const std::vector<double>& target,
                const std::vector<std::uint32_t>& tets) {
  // Vertices no tet uses (left-out optional points) would make the pair invalid: only the used ones,
  // renumbered in order of first use.
  volmap::TetMeshData in, out;
  std::vector<std::uint32_t> id(source.size() / 3, UINT32_MAX);
  in.tets = tets;
  for (std::uint32_t v : tets)
    if (id[v] == UINT32_MAX) {
      id[v] = std::uint32_t(in.xyz.size() / 3);
      in.xyz.insert(in.xyz.end(), &source[3 * v], &source[3 * v] + 3);
      out.xyz.insert(out.xyz.end(), &target[3 * v], &target[3 * v] + 3);
    }
  for (auto& v : in.tets) v = id[v];
  out.tets = in.tets;
  CHECK(volmap::check_map(in, out).certified());
  std::vector<Face> got;
  for (std::uint64_t hf : volmap::boundary_half_faces(in)) got.push_back(volmap::half_face_vertices(in, hf));
  std::vector<Face> expected;
  for (Face f : surface) expected.push_back({id[f[0]], id[f[1]], id[f[2]]});
  CHECK(sorted_faces(got) == sorted_faces(expected));
}

// The unit cube's surface: 8 corners, two triangles per side, outward.
Prism cube_surface() {
  const volmap::TetMeshData c = volmap::generate_kuhn_grid(1, 1, 1);
  Prism p;
  p.xyz = c.xyz;
  for (std::uint64_t hf : volmap::boundary_half_faces(c)) p.faces.push_back(volmap::half_face_vertices(c, hf));
  return p;
}

}  // namespace

TEST_CASE("Steiner-free fill: Schönhardt's twisted prism has none (search exhausted); twisted the other way, 4 tets") {
  // The same faces (diagonals (a_i, b_{i+1})) turned by +30 and -30 degrees: one turn makes the
  // diagonals reflex (Schönhardt's polyhedron), the other convex.
  const double twist = std::acos(-1.0) / 6;
  const Prism plus = prism(twist), minus = prism(-twist);
  REQUIRE(sorted_faces(plus.faces) == sorted_faces(minus.faces));
  REQUIRE(diagonals_reflex(plus) != diagonals_reflex(minus));
  const Prism& reflex = diagonals_reflex(plus) ? plus : minus;
  const Prism& convex = diagonals_reflex(plus) ? minus : plus;

  const auto none = volmap::fill_without_steiner_points(reflex.faces, reflex.xyz.data(), reflex.xyz.data(), 6);
  CHECK_FALSE(none.found);
  CHECK(none.exhausted);

  const auto fill = volmap::fill_without_steiner_points(convex.faces, convex.xyz.data(), convex.xyz.data(), 6);
  REQUIRE(fill.found);
  CHECK(fill.optimal);
  // V - 3 + interior edges: the three diagonals turn one way round the prism, so no tet can take
  // two side triangles and a cap without the third tet crossing a diagonal; one interior edge is
  // needed (a prism splits into 3 tets only when its diagonals do not all turn the same way).
  CHECK(fill.tets.size() == 4 * 4);
  check_fill(convex.faces, convex.xyz, convex.xyz, fill.tets);

  // Both spaces count: the convex prism mapped onto Schönhardt's (same faces) has no fill.
  const auto both = volmap::fill_without_steiner_points(convex.faces, convex.xyz.data(), reflex.xyz.data(), 6);
  CHECK_FALSE(both.found);
  CHECK(both.exhausted);
}

TEST_CASE("Steiner-free fill: a required inner point is used, an optional one left out when fewer tets do") {
  Prism cube = cube_surface();
  cube.xyz.insert(cube.xyz.end(), {0.5, 0.5, 0.5});  // vertex 8, the centre

  const auto with_centre = volmap::fill_without_steiner_points(cube.faces, cube.xyz.data(), cube.xyz.data(), 9, {}, {8});
  REQUIRE(with_centre.found);
  CHECK(std::count(with_centre.tets.begin(), with_centre.tets.end(), 8u) > 0);
  CHECK(with_centre.tets.size() == 4 * 12);  // the cones over the 12 triangles: the only fill with the centre
  check_fill(cube.faces, cube.xyz, cube.xyz, with_centre.tets);

  const auto optional = volmap::fill_without_steiner_points(cube.faces, cube.xyz.data(), cube.xyz.data(), 9, {}, {}, {8});
  REQUIRE(optional.found);
  CHECK(std::count(optional.tets.begin(), optional.tets.end(), 8u) == 0);
  const std::size_t tets = optional.tets.size() / 4;
  CHECK((tets == 5 || tets == 6));  // every triangulation of a cube on its corners
  check_fill(cube.faces, cube.xyz, cube.xyz, optional.tets);

  // max_tets bounds the search: no fill with fewer tets than that minimum exists.
  volmap::SteinerFreeFillLimits below;
  below.max_tets = tets;
  const auto none = volmap::fill_without_steiner_points(cube.faces, cube.xyz.data(), cube.xyz.data(), 9, below, {}, {8});
  CHECK_FALSE(none.found);
  CHECK(none.exhausted);
}

TEST_CASE("vertex removal: the centre of a 2x2x2 Kuhn grid is taken back, the map stays certified") {
  volmap::TetMeshData m = map_test::kuhn_grid(2);
  const auto bnd = map_test::grid_boundary_flags(2);
  std::vector<std::uint32_t> interior;
  for (std::uint32_t v = 0; v < bnd.size(); ++v)
    if (!bnd[v]) interior.push_back(v);
  REQUIRE(interior.size() == 1);
  const std::uint32_t centre = interior[0];
  std::vector<double> target = m.xyz;  // the identity map: every tet positive
  std::vector<std::uint8_t> locked = bnd;

  SUBCASE("ids below first_removable are never tried") {
    volmap::TetMeshData kept = m;
    const auto r = volmap::remove_added_vertices(kept, locked, target, centre + 1);
    CHECK(r.removed == 0);
    CHECK(kept.tets == m.tets);
  }
  SUBCASE("the centre is removed, fewer tets, the boundary and the other vertices unchanged") {
    volmap::TetMeshData refined = m;
    const auto r = volmap::remove_added_vertices(refined, locked, target, centre);
    REQUIRE(r.removed == 1);
    CHECK(refined.num_vertices() == m.num_vertices() - 1);
    CHECK(refined.num_tets() < m.num_tets());
    CHECK(r.tets_after == refined.num_tets());
    volmap::TetMeshData mapped = refined;
    mapped.xyz = target;
    CHECK(volmap::check_map(refined, mapped).certified());
    for (std::uint32_t v = 0; v < centre; ++v)  // ids below the removed vertex keep their positions
      CHECK(std::equal(&refined.xyz[3 * v], &refined.xyz[3 * v] + 3, &m.xyz[3 * v]));
    std::vector<Face> before, after;
    for (std::uint64_t hf : volmap::boundary_half_faces(m)) {
      Face f = volmap::half_face_vertices(m, hf);
      for (auto& v : f) v = v > centre ? v - 1 : v;  // the renumbering of compaction
      before.push_back(f);
    }
    for (std::uint64_t hf : volmap::boundary_half_faces(refined)) after.push_back(volmap::half_face_vertices(refined, hf));
    CHECK(sorted_faces(before) == sorted_faces(after));
  }
}

TEST_CASE("mapper step 14: a coarse T-shaped part onto the tetrahedron grows by a third without it, not at all with it") {
  // Four unit cubes in a T, one cube thick: all 24 Kuhn tets touch ∂M, so the map fixes every image.
  const volmap::TetMeshData part =
      volmap::generate_kuhn_grid(3, 2, 1, [](std::size_t i, std::size_t j, std::size_t) { return j == 1 || i == 1; });
  const volmap::SurfaceMapResult sm = volmap::map_surface_to_domain(part, volmap::builtin_domain("tet"));
  REQUIRE(sm.mesh.num_vertices() == sm.map.size());  // every vertex on ∂M
  volmap::VolumeMapOptions options;
  options.max_threads = 1;
  options.time_limit_seconds = 60;

  options.fewer_tets = false;
  const volmap::VolumeMapResult grown = volmap::compute_volume_map(sm.mesh, sm.map, options);
  REQUIRE(grown.certified);
  CHECK(double(grown.source.num_tets()) > 1.25 * double(sm.mesh.num_tets()));

  options.fewer_tets = true;
  const volmap::VolumeMapResult r = volmap::compute_volume_map(sm.mesh, sm.map, options);
  REQUIRE(r.certified);
  CHECK(r.certified_by == "boundary-fill");
  CHECK(r.source.num_tets() <= sm.mesh.num_tets());
  volmap::TetMeshData mapped = r.source;
  mapped.xyz = r.target_xyz;
  CHECK(volmap::check_map(r.source, mapped, &sm.map).certified());
}
