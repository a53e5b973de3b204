// Working boundary surface of the surface mapper (internal to lib/surface): the OpenMesh TriMesh of
// boundary_surface.hpp, the labels the mapper puts on it (OpenMesh properties) and the boundary edge
// splits made on it, in order.
// Conventions:
// - Faces are counter-clockwise seen from outside. Around a vertex the outgoing halfedges turn
//   counter-clockwise seen from outside with ccw_rotated_halfedge_handle: in a face (v,x,y) the
//   halfedge v->x is followed by v->y. The domain's rotation system turns the same way.
// - Vertex property `vid` is the vertex's id in the mapper's output mesh: the input's ids, then one
//   new id per split, in split order. Surface vertex indices increase with vid, so the vertices in
//   index order are the map's lines in vid order.
// - A split puts the new vertex at the midpoint 0.5*(a+b) of its edge: the same doubles
//   TetMesh::split_edge gets when the split is replayed on the tets (split_replay.hpp).
// - Labels: `on_graph` (vertex: a node or arc vertex of the embedded domain graph), `arc_label`
//   (edge: 0 when the edge is on no arc, else 1 + 2*arc + r where r = 0 iff the edge's halfedge 0
//   runs along the arc from its `from` node to its `to` node), `chart` (face: its chart, set by the
//   chart embedding after the last split). Elements created by splits start unlabelled (0): only
//   edges off every arc are split.
#pragma once

#include <volmap/surface/boundary_surface.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace volmap::surface_detail {

using VertexHandle = SurfaceMesh::VertexHandle;
using HalfedgeHandle = SurfaceMesh::HalfedgeHandle;
using EdgeHandle = SurfaceMesh::EdgeHandle;
using FaceHandle = SurfaceMesh::FaceHandle;

// One boundary edge split, in output vertex ids: edge (a,b) split at its midpoint p, new vertex m.
struct EdgeSplit {
  std::uint32_t a, b, m;
  std::array<double, 3> p;
};

// The three vertices of face f, counter-clockwise from outside.
inline std::array<VertexHandle, 3> face_vertices(const SurfaceMesh& m, FaceHandle f) {
  const HalfedgeHandle h = m.halfedge_handle(f);
  const HalfedgeHandle n = m.next_halfedge_handle(h);
  return {m.from_vertex_handle(h), m.to_vertex_handle(h), m.to_vertex_handle(n)};
}

class WorkingSurface {
 public:
  // `first_new_vid`: the output id of the first split vertex (the input's vertex count).
  WorkingSurface(const BoundarySurface& boundary, std::uint32_t first_new_vid);

  SurfaceMesh mesh;
  OpenMesh::VPropHandleT<std::uint32_t> vid;
  OpenMesh::VPropHandleT<char> on_graph;
  OpenMesh::EPropHandleT<std::int32_t> arc_label;
  OpenMesh::FPropHandleT<std::int32_t> chart;
  std::vector<EdgeSplit> splits;

  std::size_t num_vertices() const { return mesh.n_vertices(); }
  std::uint32_t vid_of(VertexHandle v) const { return mesh.property(vid, v); }
  const double* point(VertexHandle v) const { return mesh.point(v).data(); }
  bool is_on_graph(VertexHandle v) const { return mesh.property(on_graph, v) != 0; }
  bool is_arc_edge(EdgeHandle e) const { return mesh.property(arc_label, e) != 0; }

  double length(VertexHandle a, VertexHandle b) const {
    const double* p = point(a);
    const double* q = point(b);
    const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
    return std::sqrt(dx * dx + dy * dy + dz * dz);
  }

  // Calls f(h) for every halfedge leaving v, counter-clockwise from outside.
  template <class F>
  void for_each_outgoing(VertexHandle v, F&& f) const {
    const HalfedgeHandle first = mesh.halfedge_handle(v);
    HalfedgeHandle h = first;
    do {
      f(h);
      h = mesh.ccw_rotated_halfedge_handle(h);
    } while (h != first);
  }

  // The first halfedge leaving v (counter-clockwise from mesh.halfedge_handle(v)) with pred(h), or an
  // invalid handle.
  template <class P>
  HalfedgeHandle find_outgoing(VertexHandle v, P&& pred) const {
    const HalfedgeHandle first = mesh.halfedge_handle(v);
    HalfedgeHandle h = first;
    do {
      if (pred(h)) return h;
      h = mesh.ccw_rotated_halfedge_handle(h);
    } while (h != first);
    return HalfedgeHandle();
  }

  // Neighbours of v, counter-clockwise from outside (cleared first).
  void ring(VertexHandle v, std::vector<VertexHandle>& out) const;

  // Splits edge e at its midpoint with OpenMesh's 2-to-4 split and records it; returns the new vertex.
  VertexHandle split_edge(EdgeHandle e);

 private:
  std::uint32_t next_vid_;
};

}  // namespace volmap::surface_detail
