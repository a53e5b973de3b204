// volmap/volume/boundary_image_solid.hpp — the solid D bounded by the boundary image (the prescribed
// images of ∂M's triangles), and whether the straight image of an interior chord stays inside it.
// A map with every tet strictly positive sends the relative interior of every interior edge and face
// into the interior of D. On a non-convex D (the star's valleys, polycubes) a chord between two
// boundary vertices can cross ∂D or pass outside it, and then no placement of the free vertices
// saves it (docs/mapping.md §3).
// Conventions: ∂M's triangles in outward order (TetMesh::boundary_half_faces), images read from
// target_xyz (3 doubles per vertex slot; only boundary vertices are read); the image is taken to be
// embedded (a valid surface map). "Touches" tests are exact (volmap predicates); "inside" casts rays
// from a point rounded to doubles (the chord's midpoint or centroid) and counts exact crossings, so
// it routes work (which chords B0 removes) and never decides validity. Queries are const and keep no
// state.
#pragma once

#include <volmap/check/box_tree.hpp>
#include <volmap/core/tet_mesh.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace volmap {

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

  // The chord (a, b) / (a, b, c) cannot lie inside D: it touches ∂D, or its midpoint / centroid is
  // not inside.
  bool segment_leaves(std::uint32_t a, std::uint32_t b) const;
  bool triangle_leaves(std::uint32_t a, std::uint32_t b, std::uint32_t c) const;

 private:
  const double* image(std::uint32_t v) const { return &target_[3 * std::size_t(v)]; }
  // +1 a proper crossing of segment [p, q] with triangle f, 0 none, -1 grazing (retry), -2 p on f.
  int ray_crossing(const double* p, const double* q, std::uint32_t f) const;

  std::vector<double> target_;
  std::vector<std::array<std::uint32_t, 3>> tris_;  // boundary triangles, outward
  BoxTree tree_;
  double reach_ = 0;  // a ray of this length from any point of the box below leaves every triangle's box
  Box3 bounds_{};
};

}  // namespace volmap
