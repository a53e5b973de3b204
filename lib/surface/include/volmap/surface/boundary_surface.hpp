// volmap/surface/boundary_surface.hpp — the boundary of a TetMesh as an OpenMesh TriMesh (the only volmap
// header that includes OpenMesh). Conventions:
// - Points are Vec3d (OpenMesh's default Vec3f would destroy exactness).
// - Surface vertices are added in increasing tet-vertex id order (deterministic; VOLMAP map files
//   come out sorted). Faces follow the sorted boundary half-faces 4t+i with the vertices of
//   kTetFace[i]: counter-clockwise seen from outside for VOLMAP-positive tets (normals point out).
// - Back-maps: vertex property "tet_vertex" (tet-mesh vertex id), face property "half_face" (4t+i);
//   forward map surface_vertex[vid] (kInvalidIndex for interior vertices).
// - OpenMesh refuses faces at complex (non-manifold) vertices/edges: those half-faces are listed in
//   rejected_half_faces, never dropped silently. OpenMesh's own error stream is muted meanwhile.
#pragma once

#include <volmap/core/tet_mesh.hpp>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <cstdint>
#include <vector>

namespace volmap {

struct SurfaceTraits : public OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
};
using SurfaceMesh = OpenMesh::TriMesh_ArrayKernelT<SurfaceTraits>;

struct BoundarySurface {
  SurfaceMesh mesh;
  OpenMesh::VPropHandleT<std::uint32_t> tet_vertex;  // surface vertex -> tet-mesh vertex id
  OpenMesh::FPropHandleT<std::uint32_t> half_face;   // surface face -> half-face 4t+i
  std::vector<std::uint32_t> surface_vertex;         // tet-mesh vertex id -> surface vertex index
  std::vector<HalfFaceId> rejected_half_faces;       // boundary faces OpenMesh refused (non-manifold)
  std::uint64_t topology_version = 0;                // of the tet mesh it was extracted from

  std::uint32_t tet_vertex_of(SurfaceMesh::VertexHandle v) const { return mesh.property(tet_vertex, v); }
  HalfFaceId half_face_of(SurfaceMesh::FaceHandle f) const { return HalfFaceId(mesh.property(half_face, f)); }
  bool complete() const { return rejected_half_faces.empty(); }
};

BoundarySurface extract_boundary_surface(const TetMesh& mesh);

}  // namespace volmap
