// volmap/core/mesh_data.hpp — plain flat arrays of a tet mesh as read from / written to files.
// Conventions: vertex ids are 0-based; tets are 4 ids each in the file's order (never reordered);
// VOLMAP-positive tets have orient3d(v0,v1,v2,v3) > 0 (see <volmap/predicates.hpp>).
// This is the exchange format between IO and everything else; the navigable half-face structure
// (volmap::TetMesh) is built from it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace volmap {

struct TetMeshData {
  std::vector<double> xyz;                // 3 * num_vertices
  std::vector<std::int32_t> vertex_labels;  // num_vertices (0 when the file has none)
  std::vector<std::uint32_t> tets;        // 4 * num_tets, 0-based
  std::vector<std::int32_t> tet_labels;   // num_tets (0 when the file has none)

  std::size_t num_vertices() const { return xyz.size() / 3; }
  std::size_t num_tets() const { return tets.size() / 4; }
};

// Boundary map: one prescribed target position per boundary vertex.
struct BoundaryMap {
  std::vector<std::uint32_t> vids;  // 0-based vertex ids, in file order
  std::vector<double> xyz;          // 3 * vids.size()
  std::vector<std::uint32_t> source_lines;  // 1-based file line of each entry (empty when not read from a file)
  std::size_t size() const { return vids.size(); }
};

}  // namespace volmap
