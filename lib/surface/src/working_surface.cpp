// Working boundary surface of the surface mapper (conventions in working_surface.hpp).
#include "working_surface.hpp"

namespace volmap::surface_detail {

WorkingSurface::WorkingSurface(const BoundarySurface& boundary, std::uint32_t first_new_vid)
    : mesh(boundary.mesh), vid(boundary.tet_vertex), next_vid_(first_new_vid) {
  mesh.add_property(on_graph, "on_graph");
  mesh.add_property(arc_label, "arc_label");
  mesh.add_property(chart, "chart");
}

void WorkingSurface::ring(VertexHandle v, std::vector<VertexHandle>& out) const {
  out.clear();
  for_each_outgoing(v, [&](HalfedgeHandle h) { out.push_back(mesh.to_vertex_handle(h)); });
}

VertexHandle WorkingSurface::split_edge(EdgeHandle e) {
  const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
  const VertexHandle a = mesh.from_vertex_handle(h), b = mesh.to_vertex_handle(h);
  const double* p = point(a);
  const double* q = point(b);
  const std::array<double, 3> mid{0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1]), 0.5 * (p[2] + q[2])};
  const VertexHandle m = mesh.add_vertex(SurfaceMesh::Point(mid[0], mid[1], mid[2]));
  mesh.property(vid, m) = next_vid_;
  splits.push_back({vid_of(a), vid_of(b), next_vid_, mid});
  ++next_vid_;
  mesh.split(e, m);
  return m;
}

}  // namespace volmap::surface_detail
