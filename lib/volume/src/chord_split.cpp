// chord_split.cpp — B0 chord splitting (docs/mapping.md §4) with TetMesh edge and face splits.
#include <volmap/volume/chord_split.hpp>

#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>

#include <algorithm>

namespace volmap {

namespace {

// The tets holding every vertex of the simplex `verts` (n = 2 or 3).
std::vector<TetId> tets_with(const TetMesh& mesh, const std::uint32_t* verts, int n) {
  std::vector<TetId> star, out;
  mesh.vertex_star(VertexId(verts[0]), star);
  for (TetId t : star) {
    bool all = true;
    for (int j = 1; j < n && all; ++j) all = mesh.tet_local_index(t, VertexId(verts[j])) >= 0;
    if (all) out.push_back(t);
  }
  return out;
}

// Are all children (each parent with one of `verts` replaced by point p) strictly positive?
bool children_positive(const TetMesh& mesh, const std::vector<TetId>& parents, const std::uint32_t* verts, int n, const double* p) {
  const FpEnvironmentScope fp;  // one MXCSR check for all children
  for (TetId t : parents) {
    const auto tv = mesh.tet_vertices(t);
    for (int j = 0; j < n; ++j) {
      const double* q[4];
      for (int i = 0; i < 4; ++i) q[i] = tv[i].idx() == verts[j] ? p : mesh.vertex_position(tv[i]);
      if (fp.orient3d(q[0], q[1], q[2], q[3]) <= 0) return false;
    }
  }
  return true;
}

// A point inside the simplex that keeps every child exactly positive: the centroid first, then
// slightly perturbed barycentric weights (rounding nudges).
bool split_point(const TetMesh& mesh, const std::vector<TetId>& parents, const std::uint32_t* verts, int n, double* p) {
  for (int attempt = 0; attempt < 16; ++attempt) {
    double w[3] = {1.0 / n, 1.0 / n, 1.0 / n};
    if (attempt > 0) {
      const double d = 0.01 * attempt;
      w[attempt % n] += d;
      w[(attempt + 1) % n] -= d;
    }
    for (int i = 0; i < 3; ++i) {
      p[i] = 0;
      for (int j = 0; j < n; ++j) p[i] += w[j] * mesh.vertex_position(VertexId(verts[j]))[i];
    }
    if (children_positive(mesh, parents, verts, n, p)) return true;
  }
  return false;
}

// Splits the simplex `verts` (n = 2 or 3) at a point inside it. Returns false when it is not in the mesh.
bool split(TetMesh& mesh, const std::uint32_t* verts, int n) {
  const std::vector<TetId> parents = tets_with(mesh, verts, n);
  if (parents.empty()) return false;
  double p[3];
  if (!split_point(mesh, parents, verts, n, p))
    throw Error(ErrorKind::Failed, "", 0, "chord split: no exactly positive split point for a near-degenerate simplex");
  const TetId t = parents.front();
  if (n == 2) {
    mesh.split_edge(t, mesh.tet_local_index(t, VertexId(verts[0])), mesh.tet_local_index(t, VertexId(verts[1])), p);
  } else {
    int apex = 0;  // the local vertex of t off the face
    while (apex < 4 && std::find(verts, verts + 3, mesh.tet_vertex(t, apex).idx()) != verts + 3) ++apex;
    mesh.split_face(HalfFaceId(t, apex), p);
  }
  return true;
}

}  // namespace

ChordSplitResult split_chords(TetMesh& mesh, const std::vector<std::array<std::uint32_t, 2>>& edges,
                              const std::vector<std::array<std::uint32_t, 3>>& faces) {
  ChordSplitResult r;
  r.tets_before = mesh.num_tets();
  const std::size_t nv0 = mesh.num_vertices();
  for (const auto& e : edges)
    if (split(mesh, e.data(), 2)) ++r.edges_split;
  for (const auto& f : faces)
    if (split(mesh, f.data(), 3)) ++r.faces_split;
  r.tets_after = mesh.num_tets();
  r.vertices_added = mesh.num_vertices() - nv0;
  return r;
}

ChordSplitResult split_chords(TetMeshData& data, std::vector<std::uint8_t>& locked,
                              const std::vector<std::array<std::uint32_t, 2>>& edges,
                              const std::vector<std::array<std::uint32_t, 3>>& faces) {
  if (locked.size() != data.num_vertices()) throw Error(ErrorKind::BadInput, "", 0, "chord split: locked flags size mismatch");
  TetMesh mesh(data);
  const ChordSplitResult r = split_chords(mesh, edges, faces);
  if (r.vertices_added == 0) return r;
  const bool had_tet_labels = !data.tet_labels.empty(), had_vertex_labels = !data.vertex_labels.empty();
  data = mesh.to_data();  // splits delete nothing: original ids kept, new vertices appended
  if (!had_tet_labels) data.tet_labels.clear();
  if (!had_vertex_labels) data.vertex_labels.clear();
  locked.resize(data.num_vertices(), 0);
  return r;
}

}  // namespace volmap
