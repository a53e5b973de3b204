// volmap/volume/chord_split.hpp — B0 of docs/mapping.md §4: split chord edges (at the source midpoint)
// and chord faces (at the source centroid) so that no interior simplex has all its vertices on the
// boundary. Conventions: flat TetMeshData, VOLMAP-positive tets (orient3d(v0,v1,v2,v3) > 0).
// Children are formed by replacing one parent vertex IN PLACE by the new interior vertex, so each
// child has orient3d = λ·orient3d(parent) > 0; every child is verified exactly (the new point is
// nudged along the simplex when rounding to doubles would break it). Original vertex ids 0..nv−1
// are kept and new vertices appended; a split tet keeps its index for its first child and the other
// children are appended (labels copied). New vertices are interior (on_boundary = 0).
#pragma once

#include <volmap/core/mesh_data.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace volmap {

struct ChordSplitResult {
  std::size_t edges_split = 0;
  std::size_t faces_split = 0;
  std::size_t tets_before = 0;
  std::size_t tets_after = 0;
  std::size_t vertices_added = 0;
};

// Splits `edges` first, then those of `faces` that still exist. Edges/faces must be interior
// simplices of `mesh`; simplices not found (already split) are skipped. on_boundary is extended.
ChordSplitResult split_chords(TetMeshData& mesh, std::vector<std::uint8_t>& on_boundary,
                              const std::vector<std::array<std::uint32_t, 2>>& edges,
                              const std::vector<std::array<std::uint32_t, 3>>& faces);

}  // namespace volmap
