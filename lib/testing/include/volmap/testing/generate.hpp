// volmap/testing/generate.hpp — synthetic tet meshes for tests and benchmarks.
// Kuhn grid: the box [0,nx]x[0,ny]x[0,nz] (times `spacing`) cut into unit cubes, each split into the
// 6 Kuhn tets (paths corner -> opposite corner along the axes in every order). Every tet is
// VOLMAP-positive (orient3d(v0,v1,v2,v3) > 0, volmap-reference.md §1). The triangulation is
// conforming (all cubes use the same main diagonal direction). Vertex (i,j,k) has id
// i + (nx+1)*(j + (ny+1)*k) when no cell is removed.
#pragma once

#include <volmap/core/mesh_data.hpp>

#include <cstddef>
#include <functional>

namespace volmap {

TetMeshData generate_kuhn_grid(std::size_t nx, std::size_t ny, std::size_t nz, double spacing = 1.0);

// Same, keeping only the cubes (i,j,k) with keep(i,j,k) true; vertices used by no kept tet are
// dropped and the others renumbered in increasing grid order.
TetMeshData generate_kuhn_grid(std::size_t nx, std::size_t ny, std::size_t nz,
                               const std::function<bool(std::size_t, std::size_t, std::size_t)>& keep,
                               double spacing = 1.0);

// The unit cube [0,1]^3 cut into n x n x n cubes: generate_kuhn_grid(n, n, n) with every coordinate
// divided by n, so vertex (i,j,k) is at exactly (i/n, j/n, k/n) rounded once and the boundary lies
// exactly on the planes 0 and 1 (spacing = 1.0/n does not guarantee it: 49 * (1.0/49) < 1).
TetMeshData generate_kuhn_unit_cube(std::size_t n);

}  // namespace volmap
