// volmap/core/boundary_faces.hpp — boundary faces and vertices of a raw TetMeshData (no half-face
// structure needed). Conventions: half-face id 4t+i is the face of tet t opposite its local vertex i;
// its vertices, in the order that is outward for a VOLMAP-positive tet (orient3d(v0,v1,v2,v3) > 0),
// are kTetFace[i] (local_tables.hpp): F0=(1,3,2) F1=(0,2,3) F2=(0,3,1) F3=(0,1,2).
// A face is a boundary face when exactly one tet has it (faces are compared as sorted vertex
// triples, found by sorting, never by hashing). Faces shared by three or more tets (non-manifold)
// are not boundary faces.
#pragma once

#include <volmap/core/local_tables.hpp>
#include <volmap/core/mesh_data.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace volmap {

// The three vertex ids of half-face `hf` (= 4t+i) in outward order (kTetFace).
inline std::array<std::uint32_t, 3> half_face_vertices(const TetMeshData& mesh, std::uint64_t hf) {
  const std::uint32_t* tet = &mesh.tets[(hf / 4) * 4];
  const std::uint8_t* local = kTetFace[hf % 4];
  return {tet[local[0]], tet[local[1]], tet[local[2]]};
}

// Sorted ids 4t+i of the half-faces that belong to one tet only. Throws Error(BadInput) when a
// tet references a vertex id >= mesh.num_vertices(). O(#tets) counting sort + small per-vertex sorts.
std::vector<std::uint64_t> boundary_half_faces(const TetMeshData& mesh);

// Sorted, unique ids of the vertices on boundary faces.
std::vector<std::uint32_t> boundary_vertex_ids(const TetMeshData& mesh);
// Same, from an already computed boundary_half_faces() list.
std::vector<std::uint32_t> boundary_vertex_ids(const TetMeshData& mesh, const std::vector<std::uint64_t>& boundary_faces);

}  // namespace volmap
