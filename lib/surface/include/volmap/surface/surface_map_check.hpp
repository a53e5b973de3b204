// volmap/surface/surface_map_check.hpp — the exact surface-map sanity check (VOLMAP `surface_mapping_check`,
// volmap-reference.md §5, with quirks 11 and 12 fixed).
//
// For every boundary triangle (u,v,w) of the tet mesh, in the outward winding of its tet
// (F0=(1,3,2) F1=(0,2,3) F2=(0,3,1) F3=(0,1,2) for VOLMAP-positive tets), the image must satisfy
// orient3d(f(u), f(v), f(w), c) > 0 exactly, with c the kernel point: the centroid of the mapped
// boundary points (each point counted once, summed with compensated summation), or a custom or
// polycube domain's kernel. Sphere maps are judged like every other map (kernel = centroid, VOLMAP's criterion); the
// sphere only adds the test that the points lie on it. The map must cover every boundary vertex exactly once and nothing else. With a domain, every
// image point must lie on the domain boundary (distance <= tolerance) and every node target must be
// hit exactly (bitwise) by exactly one image point: maps made by VOLMAP do not say which vertices are
// the corners, so the corners are identified as the map points equal to a target.
#pragma once

#include <volmap/surface/domain.hpp>
#include <volmap/core/mesh_data.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace volmap {

struct SurfaceMapCheckOptions {
  // Distance allowed between an image point and the domain boundary. <= 0: automatic,
  // 1e-9 * domain size, or 1e-6 (the dataset's rounding) when every coordinate has <= 6 decimals.
  double position_tolerance = 0;
  // Accept an all-negative map as well (the reference's behaviour, quirk 12); default: positive only.
  bool accept_either_sign = false;
  // Use `kernel` instead of the centroid / the custom or polycube domain's kernel.
  bool override_kernel = false;
  Point3 kernel{};
  // Sphere domain: when sphere_radius > 0, points must lie on the sphere of that radius around
  // sphere_centre within the tolerance instead of on a polyhedral domain (the kernel is unchanged).
  double sphere_radius = 0;
  Point3 sphere_centre{};
};

struct SurfaceMapCheckResult {
  std::size_t boundary_vertices = 0;
  std::size_t boundary_triangles = 0;
  std::size_t map_entries = 0;
  std::size_t missing = 0;       // boundary vertices without a map line
  std::size_t not_boundary = 0;  // map lines whose vid is interior or out of range
  std::size_t duplicates = 0;    // repeated vids
  std::size_t positive = 0, zero = 0, negative = 0;  // triangle cones, exact
  Point3 kernel{};
  bool domain_checked = false;
  std::size_t off_domain = 0;    // image points farther than the tolerance from the domain boundary
  double max_domain_distance = 0;
  double tolerance = 0;
  std::size_t corners_expected = 0;
  std::size_t corners_exact = 0;  // targets hit exactly by exactly one image point
  bool ok = false;
  std::string reason;  // first failure, human readable ("" when ok)
};

SurfaceMapCheckResult check_surface_map(const TetMeshData& mesh, const BoundaryMap& map,
                                        const Domain* domain = nullptr,
                                        const SurfaceMapCheckOptions& options = {});

// The same check on a boundary already extracted: `boundary` holds the outward vertex-id triples of
// every boundary triangle of a mesh with `num_vertices` vertices.
SurfaceMapCheckResult check_surface_map(std::size_t num_vertices,
                                        const std::vector<std::array<std::uint32_t, 3>>& boundary,
                                        const BoundaryMap& map, const Domain* domain = nullptr,
                                        const SurfaceMapCheckOptions& options = {});

// The check's default kernel point: the centroid of `count` points, point_at(i) giving the i-th
// (3 doubles), each coordinate summed in index order with Neumaier's compensated summation. The
// check sums the map's points in increasing vid order; a mapper that wants the same kernel passes
// its points in that order.
template <class PointAt>
Point3 compensated_centroid(std::size_t count, PointAt&& point_at) {
  double sum[3] = {0, 0, 0}, comp[3] = {0, 0, 0};
  for (std::size_t i = 0; i < count; ++i) {
    const double* p = point_at(i);
    for (int k = 0; k < 3; ++k) {
      const double t = sum[k] + p[k];
      comp[k] += (sum[k] >= 0 ? sum[k] : -sum[k]) >= (p[k] >= 0 ? p[k] : -p[k]) ? (sum[k] - t) + p[k]
                                                                                 : (p[k] - t) + sum[k];
      sum[k] = t;
    }
  }
  const auto n = static_cast<double>(count);
  return {(sum[0] + comp[0]) / n, (sum[1] + comp[1]) / n, (sum[2] + comp[2]) / n};
}

}  // namespace volmap
