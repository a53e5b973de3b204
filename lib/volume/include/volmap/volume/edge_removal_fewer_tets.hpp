// volmap/volume/edge_removal_fewer_tets.hpp — docs/mapping.md §8 step 14c: 3-2 flips that take
// tets out of a certified map. An interior edge with exactly three tets around it is replaced by the
// two tets on its ring triangle (TetMesh::flip_3_2) when both are strictly positive in the source
// AND in the map (exact orient3d) and neither is flatter than kFixShapeRatio times the flattest of
// the three they replace (chord_rules.hpp; the shape taken as the worse of the two spaces). The two
// new tets tile the region of the three in both spaces, so the map stays valid and loses one tet
// per flip. Only the n = 3 edge removal lowers the count (n tets -> 2n - 4).
// Conventions: vertices, their positions in both spaces and ∂M are untouched (a boundary edge is
// never flipped); every live tet is visited, flips repeat over passes until none applies.
#pragma once

#include <volmap/core/mesh_data.hpp>
#include <volmap/core/properties.hpp>
#include <volmap/core/tet_mesh.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace volmap {

struct EdgeRemovalLimits {
  int passes = 8;                 // sweeps over the tets (a flip can open another)
  double time_limit_seconds = 0;  // 0 = none
};

struct EdgeRemovalResult {
  std::size_t flips = 0;
  std::size_t tets_before = 0, tets_after = 0;
};

EdgeRemovalResult remove_degree3_edges(TetMesh& mesh, const PositionProperty& target, const EdgeRemovalLimits& limits = {});

// The same on flat arrays (3 target doubles and one locked flag per vertex); throws Error(BadInput)
// on inconsistent arrays. Unchanged arrays when nothing was flipped; the vertex ids never change.
EdgeRemovalResult remove_degree3_edges(TetMeshData& source, std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                                       const EdgeRemovalLimits& limits = {});

}  // namespace volmap
