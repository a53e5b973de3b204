// bad_tet_flip.cpp — flips that take non-positive tets out of the map (conventions in
// bad_tet_flip.hpp; the edge-removal and 2-3 flip edits are TetMesh's).
#include <volmap/volume/bad_tet_flip.hpp>

#include <volmap/predicates.hpp>
#include <volmap/volume/chord_rules.hpp>

#include "polygon_triangulation.hpp"

#include <algorithm>
#include <limits>
#include <vector>

namespace volmap {

namespace {

// Source and target positions of one state, and the two exact signs every new tet must pass.
class TwoGeometries {
 public:
  explicit TwoGeometries(const MapState& s) : s_(s) {}
  const double* source(std::uint32_t v) const { return s_.source.vertex_position(VertexId(v)); }
  const double* target(std::uint32_t v) const { return s_.target[VertexId(v)].data(); }
  bool positive_in_both(const std::array<std::uint32_t, 4>& t) const {
    return fp_.orient3d(target(t[0]), target(t[1]), target(t[2]), target(t[3])) > 0 &&
           fp_.orient3d(source(t[0]), source(t[1]), source(t[2]), source(t[3])) > 0;
  }
  bool target_positive(TetId t) const {
    const auto v = s_.source.tet_vertices(t);
    return fp_.orient3d(target(v[0].idx()), target(v[1].idx()), target(v[2].idx()), target(v[3].idx())) > 0;
  }
  double source_shape(const std::array<std::uint32_t, 4>& t) const {
    return tet_shape(source(t[0]), source(t[1]), source(t[2]), source(t[3]));
  }

 private:
  const MapState& s_;
  const FpEnvironmentScope fp_;
};

std::array<std::uint32_t, 4> ids(const std::array<VertexId, 4>& v) { return {v[0].idx(), v[1].idx(), v[2].idx(), v[3].idx()}; }

// The best admissible triangulation of an edge's ring (polygon_triangulation.hpp): a triangle scores
// the worst source shape of its two tets; a diagonal must not be an edge already.
class RingTriangulation {
 public:
  RingTriangulation(const TetMesh& mesh, const TwoGeometries& g, TetId t, int a, int b)
      : mesh_(mesh), g_(g), va_(mesh.tet_vertex(t, a).idx()), vb_(mesh.tet_vertex(t, b).idx()) {
    for (VertexId v : mesh.edge_ring(t, a, b)) ring_.push_back(v.idx());
    double worst = std::numeric_limits<double>::infinity();
    mesh.edge_star(t, a, b, [&](TetId s) { worst = std::min(worst, g.source_shape(ids(mesh.tet_vertices(s)))); });
    floor_ = kFixShapeRatio * worst;
  }

  // Triangles (i, k, j), i < k < j, of the best triangulation; empty when none is admissible.
  std::vector<std::array<int, 3>> solve() const {
    return volume_detail::best_polygon_triangulation(
        int(ring_.size()), [this](int i, int k, int j) { return triangle(i, k, j); },
        [this](int i, int j) { return !is_edge(ring_[std::size_t(i)], ring_[std::size_t(j)]); });
  }

 private:
  bool is_edge(std::uint32_t x, std::uint32_t y) const {
    int lx = -1, ly = -1;
    return mesh_.find_edge(VertexId(x), VertexId(y), &lx, &ly).is_valid();
  }

  // The two tets of triangle (i, k, j) (TetMesh::remove_edge's convention): worst source shape, or
  // not admissible when either is not positive in both geometries or is too flat.
  double triangle(int i, int k, int j) const {
    const std::uint32_t x = ring_[std::size_t(i)], y = ring_[std::size_t(k)], z = ring_[std::size_t(j)];
    const std::array<std::uint32_t, 4> lower = {x, y, z, va_}, upper = {z, y, x, vb_};
    if (!g_.positive_in_both(lower) || !g_.positive_in_both(upper)) return volume_detail::kNotAdmissible;
    const double worst = std::min(g_.source_shape(lower), g_.source_shape(upper));
    return worst >= floor_ ? worst : volume_detail::kNotAdmissible;
  }

  const TetMesh& mesh_;
  const TwoGeometries& g_;
  const std::uint32_t va_, vb_;
  std::vector<std::uint32_t> ring_;
  double floor_ = 0;
};

// Removes one interior edge of t by an admissible triangulation of its ring.
bool remove_an_edge(TetMesh& mesh, const TwoGeometries& g, TetId t, int max_ring, BadTetFlipResult& r) {
  for (const auto& e : kTetEdge) {
    std::size_t degree = 0;
    if (!mesh.edge_star(t, e[0], e[1], [&degree](TetId) { ++degree; }) || degree > std::size_t(max_ring)) continue;
    const std::vector<std::array<int, 3>> triangles = RingTriangulation(mesh, g, t, e[0], e[1]).solve();
    if (triangles.empty()) continue;
    mesh.remove_edge(t, e[0], e[1], triangles);
    ++r.edges_removed;
    return true;
  }
  return false;
}

// Flips one interior face of t 2-3 when the three new tets are positive in both geometries and no
// flatter than kFixShapeRatio times the worse of the two they replace.
bool flip_a_face(TetMesh& mesh, const TwoGeometries& g, TetId t, BadTetFlipResult& r) {
  const auto tv = ids(mesh.tet_vertices(t));
  for (int apex = 0; apex < 4; ++apex) {
    const HalfFaceId h(t, apex);
    const HalfFaceId o = mesh.half_face_opposite(h);
    if (!o.is_valid()) continue;
    const std::uint32_t e = mesh.half_face_apex(o).idx();
    const double floor = kFixShapeRatio * std::min(g.source_shape(tv), g.source_shape(ids(mesh.tet_vertices(o.tet()))));
    bool admissible = true;
    for (int j = 0; j < 4 && admissible; ++j) {  // flip_2_3's children: t with face vertex j replaced by e
      if (j == apex) continue;
      std::array<std::uint32_t, 4> v = tv;
      v[std::size_t(j)] = e;
      admissible = g.positive_in_both(v) && g.source_shape(v) >= floor;
    }
    if (!admissible || !mesh.can_flip_2_3(h)) continue;  // can_flip_2_3: the topology (no edge de yet)
    mesh.flip_2_3(h);
    ++r.faces_flipped;
    return true;
  }
  return false;
}

}  // namespace

// One exact scan finds the non-positive tets. A move puts only positive tets in place (in the
// slots of the tets it removes, or new ones) and leaves every other tet in its slot, so no tet turns
// non-positive and those slots are all the passes need to visit.
BadTetFlipResult flip_nonpositive_tets(MapState& state, int max_passes, int max_ring) {
  state.require_compact();
  TetMesh& mesh = state.source;
  BadTetFlipResult r;
  r.tets_before = mesh.num_tets();
  std::vector<std::uint32_t> bad = nonpositive_tets(state.target_xyz(), mesh.tet_vertex_array());
  r.bad_before = bad.size();
  const TwoGeometries g(state);
  const auto still_bad = [&](std::uint32_t t) { return mesh.tet_is_live(TetId(t)) && !g.target_positive(TetId(t)); };
  for (int pass = 0; pass < max_passes; ++pass) {
    std::size_t moves = 0;
    for (std::uint32_t t : bad)
      if (still_bad(t) && (remove_an_edge(mesh, g, TetId(t), max_ring, r) || flip_a_face(mesh, g, TetId(t), r))) ++moves;
    bad.erase(std::remove_if(bad.begin(), bad.end(), [&](std::uint32_t t) { return !still_bad(t); }), bad.end());
    if (moves == 0) break;
  }
  r.bad_after = bad.size();
  if (mesh.num_free_tet_slots() > 0) mesh.compact();
  r.tets_after = mesh.num_tets();
  return r;
}

}  // namespace volmap
