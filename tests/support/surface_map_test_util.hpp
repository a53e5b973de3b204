// A surface map made and re-checked for a test: map_surface_to_domain, then the independent exact
// check (cones, coverage, every point on the domain, every corner exact). Include after doctest.
#pragma once
#include <volmap/surface/surface_map.hpp>
#include <volmap/surface/surface_map_check.hpp>

namespace volmap_test {

inline volmap::SurfaceMapResult map_and_recheck(const volmap::TetMeshData& mesh, const volmap::Domain& d,
                                                 const volmap::SurfaceMapOptions& options = {}) {
  volmap::SurfaceMapResult r;
  REQUIRE_NOTHROW(r = volmap::map_surface_to_domain(mesh, d, options));
  const auto c = volmap::check_surface_map(r.mesh, r.map, &d);
  CHECK(c.ok);
  CHECK(c.positive == c.boundary_triangles);
  CHECK(c.corners_exact == d.num_nodes());
  CHECK(c.max_domain_distance <= 1e-9 * d.size);
  if (d.has_fixed_kernel()) CHECK(c.kernel == d.kernel);
  return r;
}

}  // namespace volmap_test
