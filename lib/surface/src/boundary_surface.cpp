// Boundary surface extraction into OpenMesh (conventions in boundary_surface.hpp).
#include <volmap/surface/boundary_surface.hpp>

#include <OpenMesh/Core/System/omstream.hh>

namespace volmap {

BoundarySurface extract_boundary_surface(const TetMesh& tm) {
  BoundarySurface s;
  s.topology_version = tm.topology_version();
  s.mesh.add_property(s.tet_vertex, "tet_vertex");
  s.mesh.add_property(s.half_face, "half_face");
  const Span<HalfFaceId> faces = tm.boundary_half_faces();
  s.surface_vertex.assign(tm.num_vertex_slots(), kInvalidIndex);
  for (HalfFaceId h : faces)
    for (VertexId v : tm.half_face_vertices(h)) s.surface_vertex[v.idx()] = 0;
  std::size_t nsv = 0;
  for (std::uint32_t& x : s.surface_vertex)
    if (x != kInvalidIndex) ++nsv;
  s.mesh.reserve(nsv, 3 * faces.size() / 2, faces.size());
  std::uint32_t next = 0;
  for (std::size_t v = 0; v < s.surface_vertex.size(); ++v) {
    if (s.surface_vertex[v] == kInvalidIndex) continue;
    const double* p = tm.vertex_position(VertexId(std::uint32_t(v)));
    const auto vh = s.mesh.add_vertex(SurfaceMesh::Point(p[0], p[1], p[2]));
    s.mesh.property(s.tet_vertex, vh) = std::uint32_t(v);
    s.surface_vertex[v] = next++;
  }
  const bool was_enabled = ::omerr().is_enabled();
  ::omerr().disable();
  for (HalfFaceId h : faces) {
    const auto fv = tm.half_face_vertices(h);
    const auto fh = s.mesh.add_face(SurfaceMesh::VertexHandle(int(s.surface_vertex[fv[0].idx()])),
                                    SurfaceMesh::VertexHandle(int(s.surface_vertex[fv[1].idx()])),
                                    SurfaceMesh::VertexHandle(int(s.surface_vertex[fv[2].idx()])));
    if (!fh.is_valid()) {
      s.rejected_half_faces.push_back(h);
      continue;
    }
    s.mesh.property(s.half_face, fh) = h.idx();
  }
  if (was_enabled) ::omerr().enable();
  return s;
}

}  // namespace volmap
