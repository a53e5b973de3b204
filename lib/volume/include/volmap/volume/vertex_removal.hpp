// volmap/volume/vertex_removal.hpp — docs/mapping.md §8 step 14: taking back vertices that
// refinement added. An interior vertex v whose star's boundary (its link, a closed surface) has a
// fill on the link's own vertices that is strictly positive in the source AND in the map
// (steiner_free_fill.hpp) with fewer tets than the star is removed: the star becomes that fill. The
// map stays valid (the fill tiles the star's region in both spaces) and the mesh loses
// |star| − |fill| tets; a vertex added by a cone patch over a region of coarse tets often takes
// back more tets than the patch added.
// Conventions: only live interior vertices with ids >= first_removable (those refinement appended)
// are tried, in id order, over a few passes; ∂M and every other vertex position are untouched; no
// new tet is much flatter than the flattest star tet it replaces (kFixShapeRatio, chord_rules.hpp,
// the shape taken as the worse of the two spaces). The flat-array form compacts: ids below
// first_removable kept, the surviving added vertices renumbered in order.
#pragma once

#include <volmap/core/mesh_data.hpp>
#include <volmap/core/properties.hpp>
#include <volmap/core/tet_mesh.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace volmap {

struct VertexRemovalLimits {
  std::size_t max_nodes_per_vertex = 2000;  // fill-search tets tried per vertex
  int passes = 2;                           // sweeps over the vertices (a removal can unblock another)
  double time_limit_seconds = 0;            // 0 = none
};

struct VertexRemovalResult {
  std::size_t tried = 0, removed = 0;
  std::size_t tets_before = 0, tets_after = 0;
};

VertexRemovalResult remove_added_vertices(TetMesh& mesh, PositionProperty& target, std::uint32_t first_removable,
                                          const VertexRemovalLimits& limits = {});

// The same on flat arrays (3 target doubles and one locked flag per vertex); throws Error(BadInput)
// on inconsistent arrays. Unchanged arrays when nothing was removed.
VertexRemovalResult remove_added_vertices(TetMeshData& source, std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                                          std::uint32_t first_removable, const VertexRemovalLimits& limits = {});

}  // namespace volmap
