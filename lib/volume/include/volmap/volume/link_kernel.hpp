// volmap/volume/link_kernel.hpp — link-kernel relocation, the cheap pre-step of B1 (docs/mapping.md §7):
// cone repair with R = the star of one vertex and no refinement.
// Conventions: the source TetMesh gives the connectivity (no tombstones: compact() it after edits);
// target positions are 3 doubles per vertex in a flat array; locked[v] != 0 for vertices that never
// move. A VOLMAP-positive tet has orient3d(v0,v1,v2,v3) > 0.
#pragma once

#include <volmap/core/tet_mesh.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace volmap {

struct RelocationResult {
  std::size_t moved = 0;            // vertex moves applied
  int sweeps = 0;
  std::size_t nonpositive_before = 0, nonpositive_after = 0;
};

// Gauss–Seidel sweeps over the free vertices of non-positive tets, moving each to the Chebyshev
// centre of the strict kernel of its target link when that kernel is non-empty (exactly verified).
// A move makes every tet of the vertex's star strictly positive, so the exact non-positive count
// never increases. Throws Error(BadInput) on inconsistent sizes or a mesh with tombstones.
RelocationResult relocate_into_link_kernels(const TetMesh& mesh, const std::vector<std::uint8_t>& locked,
                                            std::vector<double>& target_xyz, int max_sweeps = 20);

}  // namespace volmap
