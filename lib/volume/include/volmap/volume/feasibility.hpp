// volmap/volume/feasibility.hpp — exact O(T) obstructions to a fixed-connectivity, fixed-boundary map
// (docs/mapping.md §3). Conventions: the source as a TetMesh without tombstones (or flat TetMeshData),
// VOLMAP-positive tets, `locked[v]` != 0 for the boundary vertices (those with a prescribed image),
// `target_xyz` = 3 doubles per vertex of which only the locked entries are read (the prescribed map). Signs are exact (volmap predicates); only the
// inference "these boundary images lie in one planar facet of the domain" uses a tolerance
// (1e-6 × domain scale), because map files are rounded: the pre-check routes work, the certifier
// decides.
#pragma once

#include <volmap/core/mesh_data.hpp>
#include <volmap/core/tet_mesh.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace volmap {

struct FeasibilityReport {
  // Tets whose 4 vertices are on the boundary and whose fixed image has orient3d <= 0.
  std::vector<std::uint32_t> fixed_nonpositive_tets;
  // Interior edges with both endpoints on the boundary (all of them), and the subset whose images
  // lie in one planar domain facet (these make fixed connectivity infeasible).
  std::vector<std::array<std::uint32_t, 2>> chord_edges;
  std::vector<std::array<std::uint32_t, 2>> blocking_chord_edges;
  // Interior faces with 3 boundary vertices, and the subset that blocks: degenerate image, image in
  // a facet plane, or both opposite vertices on the boundary and on the same side of it.
  std::vector<std::array<std::uint32_t, 3>> chord_faces;
  std::vector<std::array<std::uint32_t, 3>> blocking_chord_faces;
  // Interior vertices whose neighbours are all boundary vertices (their position must lie in the
  // strict kernel of a fixed link; reported, not decided).
  std::vector<std::uint32_t> fixed_link_vertices;
  std::size_t all_boundary_tets = 0;
  // Exact sign of the volume enclosed by the boundary image (outward source orientation). The
  // target volumes of any tetrahedralisation with this boundary sum to it, so when it is <= 0 (a
  // mirrored or collapsed boundary map) no refinement can give every tet a positive volume.
  int boundary_volume_sign = 1;

  bool infeasible_at_fixed_connectivity() const {
    return !fixed_nonpositive_tets.empty() || !blocking_chord_edges.empty() || !blocking_chord_faces.empty() ||
           infeasible_with_any_refinement();
  }
  bool infeasible_with_any_refinement() const { return boundary_volume_sign <= 0; }
};

// Throws Error(BadInput) on inconsistent sizes or a mesh with tombstones.
FeasibilityReport analyze_feasibility(const TetMesh& source, const std::vector<std::uint8_t>& locked,
                                      const std::vector<double>& target_xyz);
// The same, building the TetMesh (Error(BadInput) when the arrays do not form one).
FeasibilityReport analyze_feasibility(const TetMeshData& source, const std::vector<std::uint8_t>& locked,
                                      const std::vector<double>& target_xyz);

}  // namespace volmap
