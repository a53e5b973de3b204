// volmap/check/self_intersection.hpp — exact self-intersection test of a triangle surface given as flat
// arrays (xyz: 3 doubles per vertex; tris: 3 vertex ids per triangle, 0-based).
//
// A surface is free of self-intersections when its realisation is an embedding:
//   * two triangles that share no vertex id share no point (closed triangles: touching counts);
//   * two triangles sharing exactly one vertex id meet only in that vertex;
//   * two triangles sharing an edge (two ids) meet only in that edge (so a coplanar fold counts);
//   * no two triangles have the same three ids;
//   * no triangle is degenerate (collinear or repeated corners: its image is not a triangle);
//   * no two distinct referenced vertex ids sit at identical coordinates (coincident vertices).
// Every sign is an exact volmap::orient3d / orient2d (no epsilon). Only bounding-box rejection uses
// plain double comparisons, which are exact. Triangle orientation (winding) is irrelevant here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace volmap {

struct TrianglePair {
  std::uint32_t first = 0;   // triangle index, first < second
  std::uint32_t second = 0;
  bool operator==(const TrianglePair& o) const { return first == o.first && second == o.second; }
};

struct SelfIntersectionOptions {
  std::size_t max_reported = 8;  // how many pairs / triangles / vertex pairs to list (smallest first)
  bool parallel = true;          // TBB over triangles
};

struct SelfIntersectionResult {
  std::size_t intersecting_pairs = 0;      // all triangle pairs that intersect improperly
  std::vector<TrianglePair> first_pairs;   // the smallest (first, second) pairs, at most max_reported
  std::size_t degenerate_triangles = 0;    // collinear corners or repeated ids
  std::vector<std::uint32_t> first_degenerate;
  std::size_t coincident_vertices = 0;     // pairs of consecutive distinct ids at equal positions
  std::vector<std::pair<std::uint32_t, std::uint32_t>> first_coincident;
  std::size_t candidate_pairs = 0;         // pairs whose boxes overlap (work done; for benchmarks)

  bool clean() const { return intersecting_pairs == 0 && degenerate_triangles == 0 && coincident_vertices == 0; }
};

// Finds every improper intersection of the surface. Throws Error(BadInput) when a triangle refers to
// a vertex id >= num_vertices or a referenced coordinate is not finite.
SelfIntersectionResult find_self_intersections(const double* xyz, std::size_t num_vertices,
                                               const std::uint32_t* tris, std::size_t num_tris,
                                               const SelfIntersectionOptions& options = {});

inline SelfIntersectionResult find_self_intersections(const std::vector<double>& xyz,
                                                      const std::vector<std::uint32_t>& tris,
                                                      const SelfIntersectionOptions& options = {}) {
  return find_self_intersections(xyz.data(), xyz.size() / 3, tris.data(), tris.size() / 3, options);
}

// --- exact primitives (exposed for tests) ---------------------------------------------------------
// All points are 3 doubles. Triangles must be non-degenerate unless stated.

// True when the closed triangles (a,b,c) and (d,e,f) share at least one point (purely geometric).
bool triangles_intersect(const double* a, const double* b, const double* c, const double* d,
                         const double* e, const double* f);

// True when the closed segment pq and the closed triangle abc share a point.
bool segment_intersects_triangle(const double* p, const double* q, const double* a, const double* b,
                                 const double* c);

// True when the triangle's three corners are collinear (or coincide).
bool triangle_is_degenerate(const double* a, const double* b, const double* c);

// True when triangles t and u (3 vertex ids each, into xyz) intersect other than in the vertices
// and edge they share by id. Both must be non-degenerate.
bool triangle_pair_intersects(const double* xyz, const std::uint32_t* t, const std::uint32_t* u);

}  // namespace volmap
