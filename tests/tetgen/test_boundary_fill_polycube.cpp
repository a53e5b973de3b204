// The boundary fill of docs/mapping.md §8 step 14 (boundary_fill.hpp) on a real coarse CAD part:
// the 7-connected polycube of shared/data (seven cubes in a 3D cross), tetrahedralised by TetGen
// without quality refinement (every vertex on ∂M) and mapped onto the tetrahedron. Oracle: the
// cross is star-shaped about its centre and the tetrahedron is convex, so the cone from one interior
// point over the boundary's 2V − 4 triangles (V boundary vertices) is a fill valid in both spaces;
// the fill must have at most that many tets (V = 20 here: 36). Searching only the tet centroids'
// points, the fill without a certified map found none, and the mapper ended at 38 tets.
#include <doctest/doctest.h>
#include <volmap/check/map_check.hpp>
#include <volmap/surface/domain.hpp>
#include <volmap/surface/surface_map.hpp>
#include <volmap/tetgen/tetrahedralize.hpp>
#include <volmap/volume/boundary_fill.hpp>

#include "test_support.hpp"

#include <cstddef>
#include <limits>

TEST_CASE("boundary fill: the coarse 7-connected polycube onto the tetrahedron has at most the cone's 2V - 4 tets") {
  VOLMAP_REQUIRE_DATA(stl, "surfaces/nightmare_of_polycubes/7-connected.stl");
  volmap::TetrahedralizeOptions coarse;
  coarse.coarse = true;
  const volmap::TetMeshData part = volmap::tetrahedralize_surface(volmap::read_triangle_surface(stl.string()), coarse);
  const volmap::SurfaceMapResult sm = volmap::map_surface_to_domain(part, volmap::builtin_domain("tet"));
  REQUIRE(sm.mesh.num_vertices() == sm.map.size());  // every vertex on ∂M: the map fixes them all
  const std::size_t cone_tets = 2 * sm.mesh.num_vertices() - 4;

  const volmap::BoundaryFill fill =
      volmap::fill_boundary_with_fewer_tets(sm.mesh, sm.map, {}, std::numeric_limits<std::size_t>::max());
  REQUIRE(fill.found);
  CAPTURE(fill.search);
  CHECK(fill.source.num_tets() <= cone_tets);
  volmap::TetMeshData mapped = fill.source;
  mapped.xyz = fill.target_xyz;
  CHECK(volmap::check_map(fill.source, mapped, &sm.map).certified());
}
