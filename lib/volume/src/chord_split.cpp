// chord_split.cpp — B0 chord splitting (docs/mapping.md §4), in-place vertex replacement.
#include <volmap/volume/chord_split.hpp>

#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>

#include <algorithm>

namespace volmap {

namespace {

struct Splitter {
  TetMeshData& mesh;
  std::vector<std::uint8_t>& on_boundary;
  std::vector<std::vector<std::uint32_t>> vertex_tets;  // one-off refinement step: adjacency lists

  Splitter(TetMeshData& m, std::vector<std::uint8_t>& b) : mesh(m), on_boundary(b) {
    vertex_tets.resize(m.num_vertices());
    for (std::size_t t = 0; t < m.num_tets(); ++t)
      for (int i = 0; i < 4; ++i) vertex_tets[m.tets[4 * t + i]].push_back(std::uint32_t(t));
  }

  const double* P(std::uint32_t v) const { return &mesh.xyz[3 * std::size_t(v)]; }

  // Tets containing all of `verts`.
  std::vector<std::uint32_t> tets_with(const std::uint32_t* verts, int n) const {
    std::vector<std::uint32_t> out;
    for (std::uint32_t t : vertex_tets[verts[0]]) {
      const std::uint32_t* tv = &mesh.tets[4 * std::size_t(t)];
      bool all = true;
      for (int j = 1; j < n && all; ++j) all = std::find(tv, tv + 4, verts[j]) != tv + 4;
      if (all) out.push_back(t);
    }
    return out;
  }

  // Are all children (each parent with one of `verts` replaced by point p) strictly positive?
  bool children_positive(const std::vector<std::uint32_t>& parents, const std::uint32_t* verts, int n, const double* p) const {
    const FpEnvironmentScope fp;  // one MXCSR check for all children
    for (std::uint32_t t : parents) {
      const std::uint32_t* tv = &mesh.tets[4 * std::size_t(t)];
      for (int j = 0; j < n; ++j) {
        const double* q[4];
        for (int i = 0; i < 4; ++i) q[i] = tv[i] == verts[j] ? p : P(tv[i]);
        if (fp.orient3d(q[0], q[1], q[2], q[3]) <= 0) return false;
      }
    }
    return true;
  }

  // Splits the simplex `verts` (n = 2 or 3) at a point inside it. Returns false when not found.
  bool split(const std::uint32_t* verts, int n) {
    const std::vector<std::uint32_t> parents = tets_with(verts, n);
    if (parents.empty()) return false;
    double p[3];
    bool ok = false;
    // Barycentric weights: the centroid first, then slightly perturbed ones (rounding nudges).
    for (int attempt = 0; attempt < 16 && !ok; ++attempt) {
      double w[3] = {1.0 / n, 1.0 / n, 1.0 / n};
      if (attempt > 0) {
        const double d = 0.01 * attempt;
        w[attempt % n] += d;
        w[(attempt + 1) % n] -= d;
      }
      for (int i = 0; i < 3; ++i) {
        p[i] = 0;
        for (int j = 0; j < n; ++j) p[i] += w[j] * P(verts[j])[i];
      }
      ok = children_positive(parents, verts, n, p);
    }
    if (!ok) throw Error(ErrorKind::Failed, "", 0, "chord split: no exactly positive split point for a near-degenerate simplex");
    const std::uint32_t w = std::uint32_t(mesh.num_vertices());
    mesh.xyz.insert(mesh.xyz.end(), p, p + 3);
    if (!mesh.vertex_labels.empty()) mesh.vertex_labels.push_back(0);
    on_boundary.push_back(0);
    vertex_tets.emplace_back();
    for (std::uint32_t t : parents) {
      std::uint32_t parent[4];
      std::copy(&mesh.tets[4 * std::size_t(t)], &mesh.tets[4 * std::size_t(t)] + 4, parent);
      const std::int32_t label = mesh.tet_labels.empty() ? 0 : mesh.tet_labels[t];
      for (int j = 0; j < n; ++j) {
        std::uint32_t child[4];
        for (int i = 0; i < 4; ++i) child[i] = parent[i] == verts[j] ? w : parent[i];
        std::uint32_t id;
        if (j == 0) {
          id = t;
          std::copy(child, child + 4, &mesh.tets[4 * std::size_t(t)]);
          auto& lst = vertex_tets[verts[0]];
          lst.erase(std::find(lst.begin(), lst.end(), t));
        } else {
          id = std::uint32_t(mesh.num_tets());
          mesh.tets.insert(mesh.tets.end(), child, child + 4);
          if (!mesh.tet_labels.empty()) mesh.tet_labels.push_back(label);
          for (int i = 0; i < 4; ++i)
            if (child[i] != w && child[i] != verts[0]) {
              // verts[j] is absent from this child: drop t from its list only once (below).
              if (child[i] != verts[j]) vertex_tets[child[i]].push_back(id);
            }
          vertex_tets[verts[0]].push_back(id);
        }
        vertex_tets[w].push_back(id);
      }
      // verts[j] (j >= 1) no longer belongs to tet t (t now holds the child without verts[0] only
      // when j == 0 replaced verts[0]); t still contains verts[1..n-1]. Nothing else to fix.
    }
    return true;
  }
};

}  // namespace

ChordSplitResult split_chords(TetMeshData& mesh, std::vector<std::uint8_t>& on_boundary,
                              const std::vector<std::array<std::uint32_t, 2>>& edges,
                              const std::vector<std::array<std::uint32_t, 3>>& faces) {
  if (on_boundary.size() != mesh.num_vertices()) throw Error(ErrorKind::BadInput, "", 0, "chord split: boundary flags size mismatch");
  ChordSplitResult r;
  r.tets_before = mesh.num_tets();
  const std::size_t nv0 = mesh.num_vertices();
  Splitter s(mesh, on_boundary);
  for (const auto& e : edges)
    if (s.split(e.data(), 2)) ++r.edges_split;
  for (const auto& f : faces)
    if (s.split(f.data(), 3)) ++r.faces_split;
  r.tets_after = mesh.num_tets();
  r.vertices_added = mesh.num_vertices() - nv0;
  return r;
}

}  // namespace volmap
