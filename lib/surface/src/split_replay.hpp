// The input tet mesh as the surface mapper holds it (internal to lib/surface): one TetMesh built
// once, its boundary as an OpenMesh surface, and the replay of the working surface's edge splits on
// the tets.
// Conventions: "output ids" are the input's vertex ids followed by one id per split in split order
// (the map's and the refined mesh's ids). TetMesh refuses vertices used by no tet, so an input with
// such vertices is held on its used vertices, renumbered in order ("tet-mesh ids"); the unused ones
// stay in the output where they were. Replaying split k with TetMesh::split_edge appends tet-mesh
// vertex (used count + k), i.e. output id (input count + k).
#pragma once

#include "working_surface.hpp"

#include <volmap/core/mesh_data.hpp>
#include <volmap/core/tet_mesh.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace volmap::surface_detail {

class SourceTetMesh {
 public:
  // Throws Error(BadInput) for out-of-range ids and everything TetMesh refuses.
  explicit SourceTetMesh(const TetMeshData& mesh);

  const TetMeshData& data() const { return data_; }
  std::uint32_t num_input_vertices() const { return static_cast<std::uint32_t>(data_.num_vertices()); }

  // The input's boundary as an OpenMesh surface whose vertex property tet_vertex holds output ids
  // (before any replay).
  BoundarySurface boundary_surface() const;

  // Replays `splits` (in order) on the tets: every tet around a split edge becomes two. The TetMesh
  // is edited in place (no copy of the input's tets); a later call starts again from the input.
  // A child is positive iff its new vertex lies strictly on the replaced vertex's side; midpoint
  // rounding can break that, so every child is checked exactly. Returns the refined mesh in output
  // ids (new vertices labelled 0) and its outward boundary triangles. Throws Error(Failed) when a
  // child is not strictly positive.
  struct Refined {
    TetMeshData mesh;
    std::vector<std::array<std::uint32_t, 3>> boundary;
  };
  Refined refine(const std::vector<EdgeSplit>& splits);

 private:
  const TetMeshData& data_;
  bool all_used_ = true;
  std::vector<std::uint32_t> compact_of_;   // output id -> tet-mesh id (inputs only)
  std::vector<std::uint32_t> original_of_;  // tet-mesh id -> output id (used inputs only)
  TetMesh tm_;
  bool edited_ = false;  // tm_ holds an earlier replay

  void build_tet_mesh();
  std::uint32_t to_tet_mesh(std::uint32_t vid) const;
  std::uint32_t to_output(std::uint32_t tid) const;
};

}  // namespace volmap::surface_detail
