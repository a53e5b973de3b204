// volmap/volume/kernel_descent.hpp — exact local descent at fixed connectivity (docs/mapping.md §10):
// Gauss–Seidel moves of single free vertices, driven by the non-positive tets, to the max-min
// point of their link's kernel LP even when that kernel is empty.
// Conventions: as link_kernel.hpp (TetMesh without tombstones gives the connectivity; target
// positions 3 doubles per vertex; locked[v] != 0 never moves; VOLMAP-positive = orient3d > 0).
// A move of v to the LP's Chebyshev point q (which maximises the smallest distance of q to the
// inner side of its link faces) is kept only when, counted exactly, it leaves fewer non-positive
// tets in v's star, or as many and a larger smallest normalised volume there (a double measure,
// used only to break ties). The exact non-positive count of the mesh therefore never increases.
// When a move is kept, the free vertices of the star's tets that are still non-positive are queued.
#pragma once

#include <volmap/core/tet_mesh.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace volmap {

struct KernelDescentResult {
  std::size_t moves = 0, visits = 0;
  std::size_t nonpositive_before = 0, nonpositive_after = 0;
};

// At most max_visits vertex visits (0 = 50 × the number of non-positive tets at the start, at
// least 1000). Throws Error(BadInput) on inconsistent sizes or a mesh with tombstones.
KernelDescentResult descend_into_link_kernels(const TetMesh& mesh, const std::vector<std::uint8_t>& locked,
                                              std::vector<double>& target_xyz, std::size_t max_visits = 0);

}  // namespace volmap
