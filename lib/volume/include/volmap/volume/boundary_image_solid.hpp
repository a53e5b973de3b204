// volmap/volume/boundary_image_solid.hpp — the solid D bounded by the boundary image (the prescribed
// images of ∂M's triangles), and whether the straight image of an interior chord stays inside it.
// A map with every tet strictly positive sends the relative interior of every interior edge and face
// into the interior of D. On a non-convex D (the star's valleys, polycubes) a chord between two
// boundary vertices can cross ∂D or pass outside it, and then no placement of the free vertices
// saves it (docs/mapping.md §3).
// Conventions: ∂M's triangles in outward order (TetMesh::boundary_half_faces), images read from
// target_xyz (3 doubles per vertex slot; only boundary vertices are read); the image is taken to be
// embedded (a valid surface map). "Touches" tests are exact (volmap predicates) after a screen in
// double: a boundary triangle is skipped when the chord's points lie strictly on one side of its
// plane, or when a chord endpoint lies within 1e-12 of the bounds' extent of that plane (such an
// endpoint, a vertex of the embedded image, could meet the triangle only by lying on it). So a
// chord grazing ∂D to within rounding may be missed; "inside" casts rays
// from a point rounded to doubles (a chord's midpoint or centroid) and counts exact crossings, so
// it routes work (which chords B0 removes) and never decides validity. Queries are const and keep no
// state.
#pragma once

#include <volmap/check/box_tree.hpp>
#include <volmap/core/tet_mesh.hpp>

#include <array>
#include <cstdint>
#include <initializer_list>
#include <vector>

namespace volmap {

// The images of ∂M's faces form an embedded surface (exact self-intersection test). Everything in
// this file presumes it: a self-overlapping image (LIM's deformation benchmarks, locally injective
// maps) bounds no solid, and its chords may cross it in a valid locally injective map.
bool boundary_image_is_embedded(const TetMesh& mesh, const std::vector<double>& target_xyz);

class BoundaryImageSolid {
 public:
  BoundaryImageSolid(const TetMesh& mesh, const std::vector<double>& target_xyz);

  // Exact: the closed segment between the images of a and b meets a boundary triangle with neither
  // a nor b as a corner. (Triangles at a or b meet it only at that corner unless the chord lies in
  // their plane, which the facet-plane rule of ChordRules already decides.)
  bool segment_touches_boundary(std::uint32_t a, std::uint32_t b) const { return touched_triangle(a, b) != kNone; }
  // The same, naming the corners of the first such boundary triangle found (kNone: there is none).
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  std::uint32_t touched_triangle(std::uint32_t a, std::uint32_t b) const;
  const std::array<std::uint32_t, 3>& triangle(std::uint32_t f) const { return tris_[f]; }
  // Exact: the closed image triangle (a, b, c) meets a boundary triangle other than in the corners
  // and the edge the two share by id.
  bool triangle_touches_boundary(std::uint32_t a, std::uint32_t b, std::uint32_t c) const;
  // The point lies strictly inside D: an odd number of exact proper crossings along a ray (rays
  // that graze an edge or vertex are replaced by the next of a few fixed directions). False on ∂D
  // and when every ray grazes.
  bool contains(const double* p) const;

  // The chord (a, b) cannot lie inside D: it touches ∂D, or its midpoint is not inside. (Faces:
  // ChordRules::face_image_blocks composes the answer from its edges, the touch test and, when the
  // face has an edge of ∂M, its centroid.)
  bool segment_leaves(std::uint32_t a, std::uint32_t b) const;

 private:
  const double* image(std::uint32_t v) const { return &target_[3 * std::size_t(v)]; }
  // +1 a proper crossing of segment [p, q] with triangle f, 0 none, -1 grazing (retry), -2 p on f.
  int ray_crossing(const double* p, const double* q, std::uint32_t f) const;

  // Signed distance of p to triangle f's plane, in double; |value| <= plane_tolerance_ counts as
  // "in the plane".
  double plane_distance(std::uint32_t f, const double* p) const {
    const auto& h = planes_[f];
    return h[0] * p[0] + h[1] * p[1] + h[2] * p[2] - h[3];
  }
  // The closed triangle f and the segment / triangle through these points are strictly apart by
  // f's plane (a double screen before the exact tests; see the .cpp).
  bool clearly_beside(std::uint32_t f, std::initializer_list<const double*> points) const;

  std::vector<double> target_;
  std::vector<std::array<std::uint32_t, 3>> tris_;  // boundary triangles, outward
  std::vector<std::array<double, 4>> planes_;       // unit normal and offset of each triangle's plane
  double plane_tolerance_ = 0;
  BoxTree tree_;
  double reach_ = 0;  // a ray of this length from any point of the box below leaves every triangle's box
  Box3 bounds_{};
};

}  // namespace volmap
