// volmap/volume/interior_remesh.hpp — the last resort of a mapper allowed to refine: a new
// tetrahedralisation of the source's interior (docs/mapping.md §8 step 11).
// Contract of a remesher: it returns a tet mesh of the same solid whose boundary triangles are the
// input's (same vertex ids, as a set of faces), whose vertices 0..nv−1 are the input's vertices at
// bit-identical positions, with any new vertex appended in the interior, and whose tets are all
// VOLMAP-positive (orient3d > 0); tet labels, if any, one per tet. The mapper never trusts it:
// interior_remesh_problem checks all of this exactly before the remeshed source is used. The volume
// wing has no mesher of its own; the tools pass TetGen's (volmap/tetgen/remesh.hpp), tests may pass
// any function. The mapper passes the seconds the remesh may take (0 = no limit): a remesher past
// them throws (or returns late, which the mapper's clock then charges to the remeshed run).
#pragma once

#include <volmap/core/mesh_data.hpp>

#include <functional>
#include <string>

namespace volmap {

using InteriorRemesher = std::function<TetMeshData(const TetMeshData& source, double time_limit_seconds)>;

// Empty when `remeshed` keeps the contract above for `input`, else the first problem found in words.
std::string interior_remesh_problem(const TetMeshData& input, const TetMeshData& remeshed);

}  // namespace volmap
