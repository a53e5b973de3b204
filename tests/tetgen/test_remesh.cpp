// remesh_interior (volmap/tetgen/remesh.hpp): TetGen's new interior keeps every input vertex (interior
// ones included) at its id and bit-identical position and the boundary triangles as they are —
// checked by the mapper's own exact contract check (interior_remesh_problem) and by counts — and on
// a coarse mesh without interior vertices it adds interior points. Where TetGen aborts on the
// boundary PLC (the coarse fish of the thin shapes), the input's tets are refined instead.
#include <doctest/doctest.h>

#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>
#include <volmap/tetgen/remesh.hpp>
#include <volmap/tetgen/tetrahedralize.hpp>
#include <volmap/testing/generate.hpp>
#include <volmap/volume/interior_remesh.hpp>

#ifdef VOLMAP_TEST_THIN_SHAPES
#include "support/shapes.hpp"
#endif

#include <algorithm>

using namespace volmap;

namespace {

std::size_t interior_vertex_count(const TetMeshData& m) { return m.num_vertices() - boundary_vertex_ids(m).size(); }

// TetGen without quality refinement on the boundary of a Kuhn grid: no interior vertex at all.
TetMeshData coarse_cube(std::size_t n) {
  const TetMeshData grid = generate_kuhn_unit_cube(n);
  TriangleSurface surface;  // the boundary vertices only (renumbered), so TetGen adds no interior point
  std::vector<std::uint32_t> id(grid.num_vertices(), 0xFFFFFFFFu);
  for (const std::uint64_t hf : boundary_half_faces(grid))
    for (const std::uint32_t v : half_face_vertices(grid, hf)) {
      if (id[v] == 0xFFFFFFFFu) {
        id[v] = std::uint32_t(surface.num_vertices());
        for (int d = 0; d < 3; ++d) surface.xyz.push_back(grid.xyz[3 * v + std::size_t(d)]);
      }
      surface.tris.push_back(id[v]);
    }
  TetrahedralizeOptions coarse;
  coarse.coarse = true;
  return tetrahedralize_surface(surface, coarse);
}

}  // namespace

TEST_CASE("remesh_interior keeps the vertices, interior ones too, and the boundary triangles") {
  const TetMeshData grid = generate_kuhn_unit_cube(4);
  REQUIRE(interior_vertex_count(grid) == 27);
  const TetMeshData remeshed = remesh_interior(grid);
  CHECK(interior_remesh_problem(grid, remeshed).empty());
  CHECK(remeshed.num_vertices() >= grid.num_vertices());
  CHECK(boundary_half_faces(remeshed).size() == boundary_half_faces(grid).size());
  CHECK(count_nonpositive(remeshed.xyz, remeshed.tets) == 0);
}

TEST_CASE("remesh_interior gives a coarse mesh interior vertices") {
  const TetMeshData coarse = coarse_cube(6);
  REQUIRE(interior_vertex_count(coarse) == 0);
  InteriorRemeshOptions options;
  options.quality = 1.414;
  const TetMeshData remeshed = remesh_interior(coarse, options);
  CHECK(interior_remesh_problem(coarse, remeshed).empty());
  CHECK(interior_vertex_count(remeshed) > 0);
}

TEST_CASE("remesh_interior keeps a single tet label and refuses several") {
  TetMeshData grid = generate_kuhn_unit_cube(2);
  grid.tet_labels.assign(grid.num_tets(), 7);
  const TetMeshData remeshed = remesh_interior(grid);
  REQUIRE(remeshed.tet_labels.size() == remeshed.num_tets());
  CHECK(std::count(remeshed.tet_labels.begin(), remeshed.tet_labels.end(), 7) == std::ptrdiff_t(remeshed.num_tets()));
  grid.tet_labels[3] = 8;
  CHECK_THROWS_AS(remesh_interior(grid), Error);
}

TEST_CASE("remesh_interior stops TetGen at its time limit, and a limit it meets changes nothing") {
  // TetGen cannot be interrupted: it runs in a child that is killed at the limit. A 10,368-tet
  // grid takes TetGen tens of milliseconds, far beyond 1 ms.
  const TetMeshData grid = generate_kuhn_unit_cube(12);
  InteriorRemeshOptions hurried;
  hurried.time_limit_seconds = 1e-3;
  try {
    (void)remesh_interior(grid, hurried);
    FAIL("the remesh should have been stopped");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Failed);
    CHECK(std::string(e.reason()).find("did not finish within") != std::string::npos);
  }
  const TetMeshData small = generate_kuhn_unit_cube(3);
  InteriorRemeshOptions patient;
  patient.time_limit_seconds = 600;
  const TetMeshData limited = remesh_interior(small, patient), unlimited = remesh_interior(small);
  CHECK(limited.tets == unlimited.tets);
  CHECK(limited.xyz == unlimited.xyz);
}

TEST_CASE("tetrahedralize_surface stops TetGen at its time limit") {
  const TetMeshData grid = generate_kuhn_unit_cube(12);
  TriangleSurface surface;
  surface.xyz = grid.xyz;
  for (const std::uint64_t hf : boundary_half_faces(grid))
    for (const std::uint32_t v : half_face_vertices(grid, hf)) surface.tris.push_back(v);
  TetrahedralizeOptions hurried;
  hurried.quality = 1.1;  // much quality refinement: many Steiner points
  hurried.time_limit_seconds = 1e-3;
  CHECK_THROWS_WITH_AS(tetrahedralize_surface(surface, hurried), doctest::Contains("did not finish within"), Error);
}

#ifdef VOLMAP_TEST_THIN_SHAPES
TEST_CASE("remesh_interior: where TetGen aborts on the boundary PLC, the input's tets are refined instead") {
  // The fish of the thin shapes, tetrahedralised without quality refinement (volmap-tetrahedralize
  // --coarse): TetGen's boundary recovery aborts on its PLC with the interior points at every
  // quality bound, so this remesh used to throw.
  const SurfaceData fish = make_builtin_shape("fins");
  TriangleSurface surface;
  surface.xyz = fish.xyz;
  surface.tris = fish.tris;
  TetrahedralizeOptions coarse;
  coarse.coarse = true;
  const TetMeshData mesh = tetrahedralize_surface(surface, coarse);
  const TetMeshData remeshed = remesh_interior(mesh);
  CHECK(interior_remesh_problem(mesh, remeshed) == "");
  CHECK(interior_vertex_count(remeshed) > interior_vertex_count(mesh));
}
#endif
