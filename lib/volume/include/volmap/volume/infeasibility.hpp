// volmap/volume/infeasibility.hpp — exact local proofs that no map with every tet strictly positive
// exists at the given connectivity (docs/mapping.md §10).
// Conventions: the source as a TetMesh without tombstones, VOLMAP-positive tets, `locked[v]` != 0
// for the vertices whose image is fixed (the boundary), `target_xyz` = 3 doubles per vertex of which
// only the locked entries are read. A certificate names the simplex and the constraints that cannot
// all hold; each kind is checked exactly (volmap predicates, or exact rationals for the multipliers):
//   FixedTet             — a tet with four locked vertices whose image has orient3d <= 0.
//   CoincidentEdge       — an edge with two locked vertices mapped to the same point (exact
//                          points_equal): every tet of its star is flat whatever the free
//                          vertices do.
//   DegenerateFace       — a face with three locked vertices whose images are collinear (exact
//                          predicate collinear): its tets are flat.
//   ChordTouchesBoundary — an interior edge (not an edge of ∂M) with both vertices locked whose
//                          image segment meets the image of a face of ∂M that has neither as a
//                          corner (exact segment-triangle test), while the boundary image is
//                          embedded (exact self-intersection test). A map with every tet positive
//                          is then a bijection onto the solid the boundary image bounds, and it
//                          sends the edge's relative interior into that solid's interior, which
//                          the boundary does not meet.
//   EmptyLinkKernel      — a free vertex v and link faces of v (each the face opposite v in a tet
//                          of its star, its three vertices locked). Each tet needs
//                          orient3d(face, x_v) > 0, i.e. n_F·x_v > n_F·a_F with
//                          n_F = (c−a)×(b−a) for the outward face (a,b,c). Multipliers λ_F >= 0,
//                          not all zero, with Σ λ_F n_F = 0 and Σ λ_F (n_F·a_F) >= 0 (Farkas /
//                          Motzkin) show that no point x_v satisfies them all: summing would give
//                          0 > Σ λ_F n_F·a_F >= 0. n_F, the sums and λ are exact rationals.
//   EdgeFanWraps         — an edge ab with both vertices locked and, in the fan of tets around
//                          it (rotation order of the source), two locked ring vertices p and q with
//                          only free ring vertices between them (at least one), whose images lie in
//                          the same open half-plane bounded by the line ab (exact: orient3d(a,b,p,q)
//                          = 0 and p, q on the same side of ab in a projection where (a,b,p) is not
//                          degenerate), while the boundary image is embedded. A positive tet
//                          (a,b,w,w') turns the half-plane of w to that of w' by an angle in (0, π),
//                          so the tets from p to q would turn a whole multiple of 2π. A map with every
//                          tet positive is a bijection (the boundary image being embedded), so the
//                          tets around ab have disjoint wedges: at most 2π in all for an interior
//                          edge, where the rest of its fan adds more, and less than the boundary's
//                          dihedral angle (< 2π) for an edge of ∂M.
//   FreeEdgeLine         — an edge uv with both vertices free and tets (u, v, x, y) of its star with x
//                          and y locked, (x, y) ordered so that (u, v, x, y) is an even permutation of
//                          the tet. orient3d(u, v, x, y) = −side(line(u,v), line(x,y)) (Plücker
//                          coordinates, predicates_rational.hpp), so each tet asks the line through
//                          u's and v's images to satisfy a strict inequality that is linear in its six
//                          coordinates. Multipliers λ >= 0, not all zero, with Σ λ line(x, y) = 0
//                          (Gordan) show that no line, and no pair of points, satisfies them all.
//   FreeEdgeCone         — the same constraints on the line uv, when they admit six-vectors but only
//                          in a thin cone off the Klein quadric: the closed cone {L : −side(L, xy)
//                          >= 0 for the constraint tets} is pointed and the Klein form has one
//                          strict sign on every pair of its extreme rays (cone_holds_no_line), so it
//                          holds no line's coordinates and no placement of u and v.
// A certificate proves infeasibility at this connectivity only; refinement may still admit a map.
#pragma once

#include <volmap/core/tet_mesh.hpp>
#include <volmap/predicates_rational.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace volmap {

enum class InfeasibilityKind { FixedTet, CoincidentEdge, DegenerateFace, ChordTouchesBoundary, EmptyLinkKernel, EdgeFanWraps,
                                FreeEdgeLine, FreeEdgeCone };

struct InfeasibilityCertificate {
  InfeasibilityKind kind = InfeasibilityKind::FixedTet;
  std::vector<std::uint32_t> simplex;  // the tet (4 ids), edge (2), face (3) or free vertex (1)
  std::uint32_t tet = 0;               // a tet that cannot be strictly positive (one of the constraints' tets)
  // EmptyLinkKernel: the tets whose link faces form the constraint set and their exact multipliers.
  // FreeEdgeLine: the tets around the free edge whose opposite edges form the constraint set, and
  // their exact multipliers. FreeEdgeCone: those tets (no multipliers).
  std::vector<std::uint32_t> constraint_tets;
  std::vector<Rational> multipliers;
  // ChordTouchesBoundary: the corners of the face of ∂M whose image the chord's image meets.
  std::vector<std::uint32_t> boundary_face;
  // EdgeFanWraps: the ring vertices p, w_1, ..., w_k, q in fan order (constraint_tets: the k + 1 tets
  // (a, b, p, w_1), ..., (a, b, w_k, q) between them).
  std::vector<std::uint32_t> ring;
};

const char* infeasibility_kind_name(InfeasibilityKind kind);
// One line naming the simplex and constraints (for reports; multipliers as exact fractions).
std::string describe(const InfeasibilityCertificate& certificate);

struct InfeasibilityOptions {
  std::size_t max_certificates = 16;  // stop after this many (0 = no limit)
  // Free vertices with at least this many link faces whose vertices are all locked are tried for
  // an EmptyLinkKernel certificate (their kernel LP first, in double).
  std::size_t min_fixed_link_faces = 2;
  // Edges between free vertices with at least this many tets whose opposite edge is locked are
  // tried for a FreeEdgeLine certificate (the LP over the line's coordinates first, in double).
  std::size_t min_fixed_opposite_edges = 2;
};

// Searches every kind above; each certificate returned has passed verify_certificate. Throws
// Error(BadInput) on inconsistent sizes or a mesh with tombstones.
std::vector<InfeasibilityCertificate> find_local_infeasibility(const TetMesh& source, const std::vector<std::uint8_t>& locked,
                                                               const std::vector<double>& target_xyz,
                                                               const InfeasibilityOptions& options = {});

// Exact check of one certificate against the mesh, the locked mask and the fixed images: the
// simplex and constraint tets exist and contain what the kind says, the vertices the kind needs
// are locked, and the exact condition of the kind holds. False on any mismatch.
bool verify_certificate(const TetMesh& source, const std::vector<std::uint8_t>& locked, const std::vector<double>& target_xyz,
                        const InfeasibilityCertificate& certificate);

}  // namespace volmap
