// remesh.cpp — interior remesh through tetrahedralize_surface (conventions in remesh.hpp): the
// surface is every input vertex plus the boundary half-faces in their outward winding (kTetFace).
#include <volmap/tetgen/remesh.hpp>

#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/error.hpp>
#include <volmap/tetgen/tetrahedralize.hpp>

#include <algorithm>
#include <cstring>
#include <functional>

namespace volmap {

TetMeshData remesh_interior(const TetMeshData& mesh, const InteriorRemeshOptions& options) {
  // New tets cannot take labels from parents: a labelled input keeps its one label, or is refused.
  const bool labelled = !mesh.tet_labels.empty();
  if (labelled && std::adjacent_find(mesh.tet_labels.begin(), mesh.tet_labels.end(), std::not_equal_to<>()) != mesh.tet_labels.end())
    throw Error(ErrorKind::Failed, "the interior remesh would lose the input's tet labels (more than one label)");
  TriangleSurface surface;
  surface.xyz = mesh.xyz;
  for (const std::uint64_t hf : boundary_half_faces(mesh))
    for (const std::uint32_t v : half_face_vertices(mesh, hf)) surface.tris.push_back(v);
  TetrahedralizeOptions tetgen;
  tetgen.quality = options.quality;
  TetMeshData remeshed = tetrahedralize_surface(surface, tetgen);
  const std::size_t nv = mesh.num_vertices();
  if (remeshed.num_vertices() < nv || std::memcmp(remeshed.xyz.data(), mesh.xyz.data(), 3 * nv * sizeof(double)) != 0)
    throw Error(ErrorKind::Failed, "TetGen did not keep every input vertex in place");
  if (labelled) remeshed.tet_labels.assign(remeshed.num_tets(), mesh.tet_labels.front());
  return remeshed;
}

}  // namespace volmap
