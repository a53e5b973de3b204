// volmap/volume/chord_rules.hpp — when does an interior simplex whose vertices all lie on ∂M block
// every map at fixed connectivity (docs/mapping.md §3)? The rules, for one source mesh and its
// prescribed boundary images, usable on the mesh as it is edited by B0 (§4): ∂M never changes, so
// the boundary triangles at each boundary vertex are captured once; vertices added later are free.
// On a non-convex, embedded boundary image (boundary_image_is_convex false,
// boundary_image_is_embedded true) a chord also blocks when its straight image leaves the solid the
// image bounds (boundary_image_solid.hpp). A self-overlapping image bounds no solid: the rule is off.
// Conventions: boundary triangles outward (a point p is inside the domain next to the outward
// triangle (a,b,c) iff orient3d(a,b,c,p) > 0); signs are exact (volmap predicates); only "lies in the
// plane of a boundary triangle" uses a tolerance (1e-6 × the largest extent of the boundary image),
// because map files are rounded: a pre-check routes work, the certifier decides.
#pragma once

#include <volmap/core/tet_mesh.hpp>
#include <volmap/volume/boundary_image_solid.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace volmap {

// Shape of a tet in double: 6·volume / (sum of squared edge lengths)^{3/2}, positive for a positive
// tet. It only ranks B0's candidate fixes and bounds their flatness, never decides validity: a fix
// may not make its worst tet flatter than kFixShapeRatio times the worst tet it replaces (near-flat
// tets stop later splits from finding an exactly positive point and hurt the untanglers).
double tet_shape(const double* p0, const double* p1, const double* p2, const double* p3);
inline constexpr double kFixShapeRatio = 0.1;

class ChordRules {
 public:
  // locked[v] != 0 for the boundary vertices of `mesh`; target_xyz: 3 doubles per vertex (only the
  // locked entries are read, the prescribed images). Throws Error(BadInput) on inconsistent sizes.
  ChordRules(const TetMesh& mesh, const std::vector<std::uint8_t>& locked, const std::vector<double>& target_xyz);

  bool locked(std::uint32_t v) const { return v < locked_.size() && locked_[v]; }
  const double* image(std::uint32_t v) const { return &target_[3 * std::size_t(v)]; }
  double tolerance() const { return tol_; }

  // An interior edge (a, b) with both ends locked blocks when its image lies in ∂D: the images
  // coincide, or one end's image lies in the plane of a boundary triangle at the other end; or, on
  // a non-convex image, when its image leaves D (BoundaryImageSolid::segment_leaves; remembered per
  // edge, so the rules are not to be queried from several threads).
  bool edge_blocks(std::uint32_t a, std::uint32_t b) const;
  // An interior face (a, b, c) with all three locked blocks (whatever its apexes) when its image is
  // degenerate (exactly collinear) or lies in the plane of a boundary triangle at its smallest id;
  // or, on a non-convex image, when its image leaves D: one of its edges that is not an edge of ∂M
  // leaves D (BoundaryImageSolid::segment_leaves), it touches ∂D away from the corners and edges it
  // shares with ∂M, or (with an edge of ∂M) its centroid is not inside. A face whose edges lie in
  // D's interior and that misses ∂D lies in D's interior, so only then is no point tested.
  bool face_image_blocks(std::uint32_t a, std::uint32_t b, std::uint32_t c) const;
  // A tet whose four vertices are locked has a fixed image: true when that image is not strictly
  // positive. (An interior face whose two tets are both fixed blocks exactly when one of them is.)
  bool fixed_tet_nonpositive(const std::array<std::uint32_t, 4>& v) const;

 private:
  // Are the images of others[0..n) within the tolerance of the plane of a boundary triangle at a?
  bool in_facet_plane_at(std::uint32_t a, const std::uint32_t* others, int n) const;

  std::vector<std::uint8_t> locked_;
  std::vector<double> target_;  // 3 per vertex of the mesh as given
  double tol_ = 0;
  // Boundary triangles at each vertex (CSR): one corner of each triangle's image, its (unnormalised)
  // normal and the normal's length; triangles degenerate in double are left out (no plane).
  std::vector<std::uint32_t> offsets_;
  std::vector<std::array<double, 7>> planes_;
  // Does the chord (a, b) leave D? (remembered per edge)
  bool edge_leaves(std::uint32_t a, std::uint32_t b) const;

  std::unique_ptr<BoundaryImageSolid> solid_;  // only for a non-convex image
  std::unordered_set<std::uint64_t> boundary_edges_;  // edges of ∂M (with solid_ only)
  mutable std::unordered_map<std::uint64_t, bool> edge_leaves_;
};

}  // namespace volmap
