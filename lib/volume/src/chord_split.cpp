// chord_split.cpp — B0 chord splitting (docs/mapping.md §4) with TetMesh edge and face splits.
#include <volmap/volume/chord_split.hpp>

#include <volmap/core/error.hpp>
#include <volmap/volume/chord_flip.hpp>
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

bool edge_exists(const TetMesh& mesh, const std::array<std::uint32_t, 2>& e) {
  return mesh.find_edge(VertexId(e[0]), VertexId(e[1]), nullptr, nullptr).is_valid();
}

std::size_t edge_degree(const TetMesh& mesh, const std::array<std::uint32_t, 2>& e) {
  int a = -1, b = -1;
  const TetId t = mesh.find_edge(VertexId(e[0]), VertexId(e[1]), &a, &b);
  return t.is_valid() ? mesh.edge_degree(t, a, b) : 0;
}

}  // namespace

ChordSplitResult remove_blocking_chords(TetMesh& mesh, const ChordRules& rules, const std::vector<std::array<std::uint32_t, 2>>& edges,
                                        const std::vector<std::array<std::uint32_t, 3>>& faces) {
  ChordSplitResult r;
  r.tets_before = mesh.num_tets();
  const std::size_t nv0 = mesh.num_vertices();
  // Edges: removals by increasing degree, repeated while they make progress.
  std::vector<std::pair<std::size_t, std::array<std::uint32_t, 2>>> by_degree;
  for (const auto& e : edges) by_degree.push_back({edge_degree(mesh, e), e});
  std::stable_sort(by_degree.begin(), by_degree.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<std::array<std::uint32_t, 2>> pending;
  for (const auto& de : by_degree) pending.push_back(de.second);
  for (bool progress = true; progress;) {
    progress = false;
    std::vector<std::array<std::uint32_t, 2>> left;
    for (const auto& e : pending) {
      if (!edge_exists(mesh, e)) continue;
      if (remove_chord_edge(mesh, rules, e[0], e[1])) {
        ++r.edges_removed;
        progress = true;
      } else {
        left.push_back(e);
      }
    }
    pending.swap(left);
  }
  // What is left: a removal if a split nearby made one admissible, else a split.
  for (const auto& e : pending) {
    if (!edge_exists(mesh, e)) continue;
    if (remove_chord_edge(mesh, rules, e[0], e[1]))
      ++r.edges_removed;
    else if (split(mesh, e.data(), 2))
      ++r.edges_split;
  }
  // Faces that still exist: a 2-3 flip, else a split.
  for (const auto& f : faces) {
    if (tets_with(mesh, f.data(), 3).size() != 2) continue;
    if (flip_chord_face(mesh, rules, f))
      ++r.faces_flipped;
    else if (split(mesh, f.data(), 3))
      ++r.faces_split;
  }
  r.tets_after = mesh.num_tets();
  r.vertices_added = mesh.num_vertices() - nv0;
  return r;
}

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
