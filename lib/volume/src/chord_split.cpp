// chord_split.cpp — B0 chord splitting (docs/mapping.md §4) with TetMesh edge and face splits.
#include <volmap/volume/chord_split.hpp>

#include <volmap/core/error.hpp>
#include <volmap/volume/chord_cone.hpp>
#include <volmap/volume/chord_flip.hpp>
#include <volmap/predicates.hpp>

#include <algorithm>
#include <functional>
#include <map>

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

// Splits the simplex `verts` (n = 2 or 3) at a point inside it. Returns false (mesh unchanged) when
// it is not in the mesh, or when no verified split point exists (counted in *refused; the simplex
// stays for the later stages).
bool split(TetMesh& mesh, const std::uint32_t* verts, int n, std::size_t* refused) {
  const std::vector<TetId> parents = tets_with(mesh, verts, n);
  if (parents.empty()) return false;
  double p[3];
  if (!split_point(mesh, parents, verts, n, p)) {
    ++*refused;
    return false;
  }
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

// Finds the edge e: `hint` (a tet that held e; slots are reused, so it is checked) or else a walk,
// which a hint spares around a high-degree vertex. Sets a, b to e's local indices in the tet it
// returns in `hint`; false when e is gone.
bool locate_edge(const TetMesh& mesh, const std::array<std::uint32_t, 2>& e, TetId& hint, int& a, int& b) {
  a = b = -1;
  if (hint.is_valid() && hint.idx() < mesh.num_tet_slots() && mesh.tet_is_live(hint)) {
    a = mesh.tet_local_index(hint, VertexId(e[0]));
    b = mesh.tet_local_index(hint, VertexId(e[1]));
  }
  if (a < 0 || b < 0) hint = mesh.find_edge(VertexId(e[0]), VertexId(e[1]), &a, &b);
  return hint.is_valid();
}

// When was each vertex last in an edited region (a counter, not time)? Whether a chord fix is
// admissible depends only on the tets around the chord, the edges between the vertices of those
// tets and the tets across their faces, so a fix that failed cannot succeed before an edit touches
// one of those vertices: the chord's own vertices or its ring (its apexes for a face).
class EditStamps {
 public:
  std::uint64_t now() const { return tick_; }
  // The edge's vertices and its ring; empty when the edge is gone (`hint`: see locate_edge).
  std::vector<std::uint32_t> neighbourhood(const TetMesh& mesh, const std::array<std::uint32_t, 2>& e, TetId& hint) const {
    std::vector<std::uint32_t> out;
    int a = -1, b = -1;
    if (!locate_edge(mesh, e, hint, a, b)) return out;
    mesh.edge_star(hint, a, b, [&](TetId t) {
      for (VertexId v : mesh.tet_vertices(t)) out.push_back(v.idx());
    });
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }
  bool touched_since(const std::vector<std::uint32_t>& vertices, std::uint64_t tick) const {
    for (std::uint32_t v : vertices)
      if (v < stamp_.size() && stamp_[v] > tick) return true;
    return false;
  }
  void edited(const std::vector<std::uint32_t>& vertices, const TetMesh& mesh) {
    ++tick_;
    stamp_.resize(mesh.num_vertex_slots(), 0);
    for (std::uint32_t v : vertices) stamp_[v] = tick_;
  }

 private:
  std::uint64_t tick_ = 1;
  std::vector<std::uint64_t> stamp_;
};

// One blocking chord edge waiting for a fix, when a removal last failed on it (0: never tried) and
// a tet that held it.
struct PendingEdge {
  std::array<std::uint32_t, 2> v;
  std::uint64_t failed_at;
  TetId hint;
  std::vector<std::uint32_t> around;  // its neighbourhood when the removal failed
};

// The tets around the pending edge e (0 when it is gone).
std::size_t pending_degree(const TetMesh& mesh, PendingEdge& e) {
  int a = -1, b = -1;
  return locate_edge(mesh, e.v, e.hint, a, b) ? mesh.edge_degree(e.hint, a, b) : 0;
}

// Cone patches (chord_cone.hpp) where they are cheaper than fixing the pending chords they take
// away: `simplices` are the pending chords' vertices, split_cost(k) what fixing chord k by a split
// would add now (0 when it is gone). Seeds: the vertices by decreasing cost of their chords.
void cone_where_cheaper(TetMesh& mesh, const std::vector<std::vector<std::uint32_t>>& simplices,
                        const std::function<long long(std::size_t)>& split_cost, EditStamps& stamps, ChordSplitResult& r) {
  std::map<std::uint32_t, std::vector<std::size_t>> at;  // vertex -> pending chords
  for (std::size_t k = 0; k < simplices.size(); ++k)
    for (std::uint32_t v : simplices[k]) at[v].push_back(k);
  const PendingChordsAt chords = [&](std::uint32_t v) {
    std::vector<std::pair<std::size_t, long long>> out;
    const auto it = at.find(v);
    if (it != at.end())
      for (std::size_t k : it->second)
        if (const long long c = split_cost(k); c > 0) out.push_back({k, c});
    return out;
  };
  auto total = [&](std::uint32_t v) {
    long long c = 0;
    for (const auto& kc : chords(v)) c += kc.second;
    return c;
  };
  std::vector<std::pair<long long, std::uint32_t>> order;
  for (const auto& entry : at) order.push_back({total(entry.first), entry.first});
  std::sort(order.begin(), order.end(), [](const auto& x, const auto& y) { return x.first > y.first || (x.first == y.first && x.second < y.second); });
  std::vector<std::uint32_t> touched;
  for (const auto& [first_cost, v] : order) {
    if (first_cost <= 0) break;
    if (total(v) <= 0) continue;
    long long added = 0;
    if (!cone_region(mesh, v, chords, ConeRegionLimits{}, &added, &touched)) continue;
    stamps.edited(touched, mesh);
    ++r.cone_patches;
  }
}

}  // namespace

ChordSplitResult remove_blocking_chords(TetMesh& mesh, const ChordRules& rules, const std::vector<std::array<std::uint32_t, 2>>& edges,
                                        const std::vector<std::array<std::uint32_t, 3>>& faces) {
  ChordSplitResult r;
  r.tets_before = mesh.num_tets();
  const std::size_t nv0 = mesh.num_vertices();
  EditStamps stamps;
  // Edges: removals by increasing degree, repeated while they make progress; a removal that failed
  // is tried again only after an edit touched the edge's neighbourhood.
  std::vector<std::pair<std::size_t, PendingEdge>> by_degree;
  for (const auto& e : edges) {
    PendingEdge p{e, 0, TetId::kInvalid, {}};
    const std::size_t degree = pending_degree(mesh, p);
    by_degree.push_back({degree, std::move(p)});
  }
  std::stable_sort(by_degree.begin(), by_degree.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<PendingEdge> pending;
  for (auto& de : by_degree) pending.push_back(std::move(de.second));
  // A removal of e unless it failed before and nothing around it changed since (the neighbourhood
  // stored at the failure holds e's vertices, so any change of e's star is seen). Sets `gone` when
  // e no longer exists.
  auto try_removal = [&](PendingEdge& e, bool& gone) {
    gone = false;
    if (e.failed_at != 0 && !stamps.touched_since(e.around, e.failed_at)) return false;
    std::vector<std::uint32_t> around = stamps.neighbourhood(mesh, e.v, e.hint);
    if (around.empty()) {
      gone = true;
      return false;
    }
    if (remove_chord_edge(mesh, rules, e.v[0], e.v[1], kChordRingLimit, e.hint)) {
      stamps.edited(around, mesh);
      ++r.edges_removed;
      return true;
    }
    e.failed_at = stamps.now();
    e.around = std::move(around);
    return false;
  };
  for (bool progress = true; progress;) {
    progress = false;
    std::vector<PendingEdge> left;
    for (PendingEdge& e : pending) {
      bool gone = false;
      if (try_removal(e, gone))
        progress = true;
      else if (!gone)
        left.push_back(std::move(e));
    }
    pending.swap(left);
  }
  {
    std::vector<std::vector<std::uint32_t>> simplices;
    for (const PendingEdge& e : pending) simplices.push_back({e.v[0], e.v[1]});
    cone_where_cheaper(mesh, simplices, [&](std::size_t k) { return (long long)pending_degree(mesh, pending[k]); }, stamps, r);
  }
  // What is left: a removal if a split or cone nearby made one admissible, else a split.
  for (PendingEdge& e : pending) {
    bool gone = false;
    if (try_removal(e, gone)) continue;
    if (gone) continue;
    const std::vector<std::uint32_t> around = stamps.neighbourhood(mesh, e.v, e.hint);
    if (!around.empty() && split(mesh, e.v.data(), 2, &r.splits_refused)) {
      stamps.edited(around, mesh);
      ++r.edges_split;
    }
  }
  // Faces that still exist: 2-3 flips; then cones where cheaper than the face splits left (4 tets
  // each); then a flip if one has become admissible, else a split.
  auto exists = [&](const std::array<std::uint32_t, 3>& f) { return tets_with(mesh, f.data(), 3).size() == 2; };
  std::vector<std::array<std::uint32_t, 3>> left;
  for (const auto& f : faces) {
    if (!exists(f)) continue;
    if (flip_chord_face(mesh, rules, f))
      ++r.faces_flipped;
    else
      left.push_back(f);
  }
  {
    std::vector<std::vector<std::uint32_t>> simplices;
    for (const auto& f : left) simplices.push_back({f[0], f[1], f[2]});
    cone_where_cheaper(mesh, simplices, [&](std::size_t k) { return exists(left[k]) ? 4LL : 0LL; }, stamps, r);
  }
  for (const auto& f : left) {
    if (!exists(f)) continue;
    if (flip_chord_face(mesh, rules, f))
      ++r.faces_flipped;
    else if (split(mesh, f.data(), 3, &r.splits_refused))
      ++r.faces_split;
  }
  r.tets_after = mesh.num_tets();
  r.vertices_added = mesh.num_vertices() - nv0;
  return r;
}

namespace {

// Takes the fixed tet t out of the mesh: a 2-3 flip of one of its interior faces (largest source
// area first) when admissible, else a split of its largest interior face. False when it has no
// interior face.
bool free_fixed_tet(TetMesh& mesh, const ChordRules& rules, TetId t, ChordSplitResult& r) {
  std::vector<std::pair<double, std::array<std::uint32_t, 3>>> faces;  // (squared double area, vertices)
  for (int i = 0; i < 4; ++i) {
    if (!mesh.half_face_opposite(HalfFaceId(t, i)).is_valid()) continue;
    const auto fv = mesh.half_face_vertices(HalfFaceId(t, i));
    const double* a = mesh.vertex_position(fv[0]);
    const double* b = mesh.vertex_position(fv[1]);
    const double* c = mesh.vertex_position(fv[2]);
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    faces.push_back({n[0] * n[0] + n[1] * n[1] + n[2] * n[2], {fv[0].idx(), fv[1].idx(), fv[2].idx()}});
  }
  if (faces.empty()) return false;
  std::stable_sort(faces.begin(), faces.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  for (const auto& f : faces)
    if (flip_chord_face(mesh, rules, f.second)) {
      ++r.faces_flipped;
      return true;
    }
  if (!split(mesh, faces.front().second.data(), 3, &r.splits_refused)) return false;
  ++r.faces_split;
  return true;
}

}  // namespace

std::size_t free_fixed_nonpositive_tets(TetMesh& mesh, const ChordRules& rules, ChordSplitResult& r) {
  std::vector<std::array<std::uint32_t, 4>> fixed;  // by vertices: the fixes below reuse tet slots
  for (std::uint32_t t = 0; t < mesh.num_tet_slots(); ++t) {
    if (!mesh.tet_is_live(TetId(t))) continue;
    const auto tv = mesh.tet_vertices(TetId(t));
    const std::array<std::uint32_t, 4> v = {tv[0].idx(), tv[1].idx(), tv[2].idx(), tv[3].idx()};
    if (rules.fixed_tet_nonpositive(v)) fixed.push_back(v);  // false unless all four are locked
  }
  const std::size_t nv0 = mesh.num_vertices();
  std::size_t freed = 0;
  for (const auto& v : fixed) {
    const std::vector<TetId> found = tets_with(mesh, v.data(), 4);
    if (!found.empty() && free_fixed_tet(mesh, rules, found.front(), r)) ++freed;  // empty: an earlier fix took it
  }
  r.vertices_added += mesh.num_vertices() - nv0;
  r.tets_after = mesh.num_tets();
  return freed;
}

ChordSplitResult split_chords(TetMesh& mesh, const std::vector<std::array<std::uint32_t, 2>>& edges,
                              const std::vector<std::array<std::uint32_t, 3>>& faces) {
  ChordSplitResult r;
  r.tets_before = mesh.num_tets();
  const std::size_t nv0 = mesh.num_vertices();
  for (const auto& e : edges)
    if (split(mesh, e.data(), 2, &r.splits_refused)) ++r.edges_split;
  for (const auto& f : faces)
    if (split(mesh, f.data(), 3, &r.splits_refused)) ++r.faces_split;
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
