// Exact surface-map check (see surface_map_check.hpp). Every cone sign is volmap::orient3d; exact
// corner hits use volmap::points_equal.
#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>
#include <volmap/surface/surface_map_check.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace volmap {

namespace {

bool has_at_most_6_decimals(double x) {
  const double s = x * 1e6;
  return std::fabs(s - std::nearbyint(s)) < 1e-3;
}

}  // namespace

SurfaceMapCheckResult check_surface_map(const TetMeshData& mesh, const BoundaryMap& map, const Domain* domain,
                                        const SurfaceMapCheckOptions& options) {
  const std::vector<std::uint64_t> faces = boundary_half_faces(mesh);
  std::vector<std::array<std::uint32_t, 3>> boundary(faces.size());
  for (std::size_t i = 0; i < faces.size(); ++i) boundary[i] = half_face_vertices(mesh, faces[i]);
  return check_surface_map(mesh.num_vertices(), boundary, map, domain, options);
}

SurfaceMapCheckResult check_surface_map(std::size_t nv, const std::vector<std::array<std::uint32_t, 3>>& faces,
                                        const BoundaryMap& map, const Domain* domain,
                                        const SurfaceMapCheckOptions& options) {
  SurfaceMapCheckResult r;
  std::vector<char> is_boundary(nv, 0);
  for (const auto& t : faces)
    for (auto v : t) {
      if (v >= nv) throw Error(ErrorKind::BadInput, "", 0, "a boundary triangle names vertex " + std::to_string(v) + " of " + std::to_string(nv));
      is_boundary[v] = 1;
    }
  std::vector<std::uint32_t> bverts;
  for (std::uint32_t v = 0; v < nv; ++v)
    if (is_boundary[v]) bverts.push_back(v);
  r.boundary_triangles = faces.size();
  r.boundary_vertices = bverts.size();
  r.map_entries = map.size();

  // slot[v] = index of v's map entry, -1 none; boundary flag.
  std::vector<std::int32_t> slot(nv, -1);
  for (std::size_t i = 0; i < map.size(); ++i) {
    const std::uint32_t v = map.vids[i];
    if (v >= nv || !is_boundary[v]) {
      ++r.not_boundary;
      continue;
    }
    if (slot[v] >= 0) {
      ++r.duplicates;
      continue;
    }
    slot[v] = static_cast<std::int32_t>(i);
  }
  for (auto v : bverts)
    if (slot[v] < 0) ++r.missing;
  if (r.missing || r.not_boundary || r.duplicates) {
    r.reason = "the map does not cover the boundary exactly once (" + std::to_string(r.missing) + " missing, " +
               std::to_string(r.not_boundary) + " not boundary vertices, " + std::to_string(r.duplicates) +
               " duplicates)";
    return r;
  }
  for (double x : map.xyz)
    if (!std::isfinite(x)) {
      r.reason = "the map has a non-finite coordinate";
      return r;
    }

  // Kernel point.
  if (options.override_kernel) {
    r.kernel = options.kernel;
  } else if (domain && domain->has_fixed_kernel()) {
    r.kernel = domain->kernel;
  } else {
    r.kernel = compensated_centroid(bverts.size(), [&](std::size_t i) { return &map.xyz[3 * std::size_t(slot[bverts[i]])]; });
  }

  for (const auto& tri : faces) {
    const int s = orient3d(&map.xyz[3 * slot[tri[0]]], &map.xyz[3 * slot[tri[1]]],
                           &map.xyz[3 * slot[tri[2]]], r.kernel.data());
    if (s > 0)
      ++r.positive;
    else if (s < 0)
      ++r.negative;
    else
      ++r.zero;
  }
  bool cones_ok = r.zero == 0 && (r.negative == 0 || (options.accept_either_sign && r.positive == 0));
  if (!cones_ok) {
    r.reason = std::to_string(r.negative) + " boundary triangles inverted and " + std::to_string(r.zero) +
               " degenerate with respect to the kernel point";
  }

  if (options.sphere_radius > 0) {
    r.domain_checked = true;
    r.tolerance = options.position_tolerance;
    if (!(r.tolerance > 0)) {  // as for polyhedral domains: 1e-9 * size, or 1e-6 for 6-decimal maps
      r.tolerance = 1e-9 * 2 * options.sphere_radius;
      if (std::all_of(map.xyz.begin(), map.xyz.end(), has_at_most_6_decimals)) r.tolerance = std::max(r.tolerance, 1e-6);
    }
    for (std::size_t i = 0; i < map.size(); ++i) {
      double d2 = 0;
      for (int k = 0; k < 3; ++k) {
        const double dk = map.xyz[3 * i + k] - options.sphere_centre[k];
        d2 += dk * dk;
      }
      const double dist = std::fabs(std::sqrt(d2) - options.sphere_radius);
      r.max_domain_distance = std::max(r.max_domain_distance, dist);
      if (dist > r.tolerance) ++r.off_domain;
    }
    if (cones_ok && r.off_domain)
      r.reason = std::to_string(r.off_domain) + " image points off the sphere (max distance " +
                 std::to_string(r.max_domain_distance) + ")";
  } else if (domain) {
    r.domain_checked = true;
    double tol = options.position_tolerance;
    if (!(tol > 0)) {
      tol = 1e-9 * domain->size;
      bool rounded6 = true;
      for (double x : map.xyz)
        if (!has_at_most_6_decimals(x)) {
          rounded6 = false;
          break;
        }
      if (rounded6) tol = std::max(tol, 1e-6);
    }
    r.tolerance = tol;
    for (std::size_t i = 0; i < map.size(); ++i) {
      const Point3 p{map.xyz[3 * i], map.xyz[3 * i + 1], map.xyz[3 * i + 2]};
      const double dist = distance_to_domain_boundary(*domain, p);
      r.max_domain_distance = std::max(r.max_domain_distance, dist);
      if (dist > tol) ++r.off_domain;
    }
    r.corners_expected = domain->num_nodes();
    for (const auto& t : domain->targets) {
      std::size_t hits = 0;
      for (std::size_t i = 0; i < map.size(); ++i)
        hits += points_equal(&map.xyz[3 * i], t.data());
      r.corners_exact += hits == 1;
    }
    if (cones_ok && r.off_domain)
      r.reason = std::to_string(r.off_domain) + " image points off the domain boundary (max distance " +
                 std::to_string(r.max_domain_distance) + ")";
    else if (cones_ok && r.corners_exact != r.corners_expected)
      r.reason = std::to_string(r.corners_expected - r.corners_exact) +
                 " domain corners are not hit exactly by exactly one image point";
  }
  r.ok = r.reason.empty();
  return r;
}

}  // namespace volmap
