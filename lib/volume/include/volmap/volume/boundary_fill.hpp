// volmap/volume/boundary_fill.hpp — docs/mapping.md §8 step 14: a new tetrahedralisation of ∂M valid
// in the source and in the map at once (steiner_free_fill.hpp) with fewer tets than a given count.
// The vertices it may use: the input's (all of them, each at its source position and at its image:
// the boundary map's, or for an interior vertex the certified map's) and, optionally, the points a
// certified map added (at their positions in both spaces). Searches, the fewest tets kept:
//   1. when the map fixes every vertex (all on ∂M): the input's own tets if all are positive at the
//      images, else a fill on ∂M's own vertices;
//   2. with a certified map: a fill with its interior vertices and the points it added as options;
//   3. when the map fixes every vertex: one interior point — first a strict kernel point of ∂M in
//      each space when both exist (the cone from it over ∂M is then a fill of 2V − 4 tets, V the
//      boundary vertices), then the centroid (in both spaces) of each input tet in turn, the
//      non-positive ones first.
// Each search runs as restarts with other tie-breaks and doubling node limits; a fill found bounds
// every later search (only fewer tets are searched for).
// Coarse CAD parts and Platonic solids, whose tets all touch ∂M, get a certified map with as many
// tets as the input or a few more, where splits and cone patches added a third or more.
// Conventions: a valid input and map (as compute_volume_map checks them); the result keeps the
// input's vertex ids, the points it uses appended after them (in the certified map's order, or the
// interior point); tets VOLMAP-positive in both spaces; no tet labels unless the fill is the input's
// own tets (vertex labels: 0 for added points).
#pragma once

#include <volmap/core/mesh_data.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace volmap {

struct BoundaryFillLimits {
  std::size_t max_nodes = 120000;           // tets tried, over all searches
  std::size_t max_nodes_per_search = 40000;  // tets tried by search 1 or 2 (over its restarts)
  std::size_t max_nodes_per_point = 2000;   // tets tried with one interior point (search 3)
  double time_limit_seconds = 0;           // 0 = none
};

// A certified map of the input: its source (the input's vertex ids first, added points after) and
// the images of all its vertices.
struct CertifiedPoints {
  const TetMeshData* source = nullptr;
  const std::vector<double>* target_xyz = nullptr;
};

struct BoundaryFill {
  bool found = false;
  TetMeshData source;               // the input's vertices, the points used, the fill's tets
  std::vector<double> target_xyz;   // 3 per vertex of source
  std::vector<std::uint8_t> locked;  // 1 per vertex of source: on ∂M
  std::string search;               // which search found it ("own tets", "boundary vertices", ...)
  std::string why_not;              // when !found
};

// A fill with fewer than must_beat tets, or found false (why_not says why). `certified` may be
// empty (no certified map: searches 1 and 3 only).
BoundaryFill fill_boundary_with_fewer_tets(const TetMeshData& input, const BoundaryMap& map, const CertifiedPoints& certified,
                                           std::size_t must_beat, const BoundaryFillLimits& limits = {});

}  // namespace volmap
