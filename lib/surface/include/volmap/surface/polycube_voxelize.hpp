// volmap/surface/polycube_voxelize.hpp — a star-shaped polycube target from a tet mesh, so that a user
// gets a polycube domain for a mesh in one step (docs/volmap-reference.md §3.1).
// Conventions:
//  - Grid: `resolution` cells along the longest side of the mesh's bounding box (cubic cells of side
//    h = longest side / resolution, starting at the box's minimum corner); cell (i, j, k) is
//    [min + h·(i, j, k), min + h·(i+1, j+1, k+1)].
//  - A cell is inside when its centre lies in a tet of the mesh (exact orient3d, closed tets).
//  - The union grows from the inside cell nearest to the mesh's vertex centroid, adding face-neighbour
//    inside cells in order of distance from that seed (ties: smaller (i, j, k) first), each kept only
//    when the union stays a valid, strictly star-shaped polycube (polycube.hpp's checks), until no
//    candidate is left or kMaxPolycubeCells is reached. Deterministic.
#pragma once

#include <volmap/core/mesh_data.hpp>
#include <volmap/surface/polycube.hpp>

#include <vector>

namespace volmap {

// Throws Error(BadInput) when resolution is outside [1, 64], the mesh has no tets, or no cell centre
// lies inside the mesh (resolution too coarse for its shape).
std::vector<PolycubeCell> voxelize_star_polycube(const TetMeshData& mesh, int resolution);

}  // namespace volmap
