// volmap/volume/chord_split.hpp — B0 of docs/mapping.md §4: split chord edges (at the source midpoint)
// and chord faces (at the source centroid) so that no interior simplex has all its vertices on the
// boundary. Conventions: VOLMAP-positive tets (orient3d(v0,v1,v2,v3) > 0). The splits are
// TetMesh::split_edge / split_face: every child replaces one vertex of its parent by the new interior
// vertex, so orient3d(child) = λ·orient3d(parent) > 0; every child is verified exactly before the
// split (the point is nudged along the simplex when rounding to doubles would break it). Vertex ids
// never change; new vertices take new slots (vertex properties: their defaults, e.g. locked 0).
#pragma once

#include <volmap/core/mesh_data.hpp>
#include <volmap/core/tet_mesh.hpp>

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

// Splits `edges` first, then those of `faces` that still exist. Edges/faces are given by vertex ids;
// simplices not found (already split) are skipped. Throws Error(Failed) when no split point keeps
// every child exactly positive (a near-degenerate simplex).
ChordSplitResult split_chords(TetMesh& mesh, const std::vector<std::array<std::uint32_t, 2>>& edges,
                              const std::vector<std::array<std::uint32_t, 3>>& faces);

// The same on flat arrays: the result is written back compacted (original ids kept, new vertices
// appended, locked extended with 0).
ChordSplitResult split_chords(TetMeshData& mesh, std::vector<std::uint8_t>& locked,
                              const std::vector<std::array<std::uint32_t, 2>>& edges,
                              const std::vector<std::array<std::uint32_t, 3>>& faces);

}  // namespace volmap
