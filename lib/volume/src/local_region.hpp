// local_region.hpp — the sub-problem of a local untangling stage: the vertices within `rings` vertex
// rings of some seed tets are free (unless locked), every tet touching a free vertex is in the
// sub-problem, every other vertex of those tets is held. Tets outside the sub-problem have no free
// vertex, so a solve on the sub-problem changes nothing else and the exact count of the whole map
// moves only by the sub-problem's count.
// Conventions: the mesh has no tombstones (vertex and tet ids are dense); sub-problem vertices are
// numbered in increasing global id, their tets keep the mesh's tet order and vertex order (so a
// VOLMAP-positive source tet stays positive). Internal header (lib/src).
#pragma once

#include <volmap/core/tet_mesh.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace volmap {

struct LocalRegion {
  std::vector<std::uint32_t> vertices;  // global id of each sub-problem vertex
  std::vector<std::uint32_t> tets;      // 4 sub-problem ids per tet
  std::vector<std::uint8_t> locked;     // 1 per sub-problem vertex: held (locked, or outside the rings)
  std::vector<double> source, target;   // 3 per sub-problem vertex, copied from the whole map
  std::size_t num_tets() const { return tets.size() / 4; }
  // Copies the free vertices' targets back into the whole map (3 doubles per mesh vertex).
  void write_back(std::vector<double>& target_xyz) const;
};

// `locked` and `target_xyz`: one flag / three doubles per mesh vertex. Throws Error(BadInput) when
// the mesh has tombstones or the arrays do not match it.
LocalRegion extract_local_region(const TetMesh& mesh, const std::vector<std::uint8_t>& locked,
                                 const std::vector<double>& target_xyz, const std::vector<std::uint32_t>& seed_tets, int rings);

}  // namespace volmap
