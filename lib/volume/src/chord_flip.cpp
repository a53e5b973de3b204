// chord_flip.cpp — edge removal and 2-3 flips that take a blocking chord out of the source without a
// new vertex (docs/mapping.md §4; conventions in chord_flip.hpp and TetMesh::remove_edge). A new tet
// is admissible when it is exactly positive in the source and, if its four vertices are locked, its
// fixed image is positive; a new edge or face is admissible when it is not a blocking chord.
#include <volmap/volume/chord_flip.hpp>

#include <volmap/predicates.hpp>

#include "polygon_triangulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace volmap {

namespace {

constexpr double kInvalid = volume_detail::kNotAdmissible;

// A new tet: exactly positive in the source, and not a fixed non-positive image.
bool admissible_tet(const TetMesh& mesh, const ChordRules& rules, const FpEnvironmentScope& fp, const std::array<std::uint32_t, 4>& v) {
  const double* p[4];
  for (int i = 0; i < 4; ++i) p[i] = mesh.vertex_position(VertexId(v[i]));
  return fp.orient3d(p[0], p[1], p[2], p[3]) > 0 && !rules.fixed_tet_nonpositive(v);
}

// Is the tet across half-face h (from outside the edited cavity) a fixed non-positive tet that B0
// will not remove? A new fixed tet glued to it would make their common face a blocking chord face
// (both apexes fixed, on the same side) that nothing removes. A fixed non-positive tet with an
// interior blocking edge goes with that edge's removal or split.
bool glued_to_lasting_bad(const TetMesh& mesh, const ChordRules& rules, HalfFaceId h) {
  const HalfFaceId o = mesh.half_face_opposite(h);
  if (!o.is_valid()) return false;
  const TetId t = o.tet();
  const auto v = mesh.tet_vertices(t);
  if (!rules.fixed_tet_nonpositive({v[0].idx(), v[1].idx(), v[2].idx(), v[3].idx()})) return false;
  for (const auto& e : kTetEdge)
    if (rules.edge_blocks(v[e[0]].idx(), v[e[1]].idx()) && mesh.edge_star(t, e[0], e[1], [](TetId) {})) return false;
  return true;
}

bool all_locked(const ChordRules& rules, const std::array<std::uint32_t, 4>& v) {
  return rules.locked(v[0]) && rules.locked(v[1]) && rules.locked(v[2]) && rules.locked(v[3]);
}

double shape_of(const TetMesh& mesh, const std::array<std::uint32_t, 4>& v) {
  return tet_shape(mesh.vertex_position(VertexId(v[0])), mesh.vertex_position(VertexId(v[1])), mesh.vertex_position(VertexId(v[2])),
               mesh.vertex_position(VertexId(v[3])));
}

std::array<std::uint32_t, 4> ids(const std::array<VertexId, 4>& v) { return {v[0].idx(), v[1].idx(), v[2].idx(), v[3].idx()}; }

double shape_floor(double worst_replaced) { return kFixShapeRatio * worst_replaced; }

// Best triangulation of an edge's ring (polygon_triangulation.hpp): a triangle scores the worst
// shape of its two tets (kInvalid when not admissible); a diagonal must be admissible.
class RingTriangulator {
 public:
  RingTriangulator(const TetMesh& mesh, const ChordRules& rules, TetId t, int a, int b)
      : mesh_(mesh), rules_(rules), va_(mesh.tet_vertex(t, a).idx()), vb_(mesh.tet_vertex(t, b).idx()) {
    for (VertexId v : mesh.edge_ring(t, a, b)) r_.push_back(v.idx());
    n_ = int(r_.size());
    neighbours_.resize(std::size_t(n_));
    read_side_neighbours(t, a, b);
    double ring_worst = std::numeric_limits<double>::infinity();
    mesh.edge_star(t, a, b, [&](TetId s) { ring_worst = std::min(ring_worst, shape_of(mesh, ids(mesh.tet_vertices(s)))); });
    floor_ = shape_floor(ring_worst);
  }

  // The triangles of the best admissible triangulation, or empty when there is none. Most rings
  // have none whatever their diagonals, so the search runs first without the test that a diagonal
  // is not an edge yet (a star walk per ring vertex): it only removes diagonals, so no triangulation
  // without it means none with it.
  std::vector<std::array<int, 3>> solve() {
    const auto triangle_score = [this](int i, int k, int j) { return triangle(i, k, j); };
    if (volume_detail::best_polygon_triangulation(n_, triangle_score, [this](int i, int j) { return unblocked_diagonal(i, j); })
            .empty())
      return {};
    return volume_detail::best_polygon_triangulation(n_, triangle_score, [this](int i, int j) { return admissible_diagonal(i, j); });
  }

 private:
  // The new edge (ring[i], ring[j]) and the faces with va and vb are not blocking.
  bool unblocked_diagonal(int i, int j) const {
    const std::uint32_t x = r_[i], y = r_[j];
    return !rules_.edge_blocks(x, y) && !rules_.face_image_blocks(va_, x, y) && !rules_.face_image_blocks(vb_, x, y);
  }
  // ... and the edge is not in the mesh yet.
  bool admissible_diagonal(int i, int j) { return unblocked_diagonal(i, j) && !(ring_neighbours(i) & (1u << j)); }

  // Bit j set iff ring[j] shares a tet with ring[i] (one star walk per ring vertex, on demand; the
  // ring has at most 31 vertices, see remove_chord_edge).
  std::uint32_t ring_neighbours(int i) {
    std::uint32_t& mask = neighbours_[std::size_t(i)];
    if (mask & kKnown) return mask;
    mask = kKnown;
    mesh_.vertex_star_unsorted(VertexId(r_[i]), star_);
    for (TetId s : star_)
      for (VertexId v : mesh_.tet_vertices(s))
        if (const int p = position(v.idx()); p < n_) mask |= 1u << p;
    return mask;
  }

  // For each side (ring[i], ring[i+1]): is the tet across its face with va (with vb) a fixed
  // non-positive tet? (The faces of the ring tets opposite vb and va.)
  void read_side_neighbours(TetId t, int a, int b) {
    bad_a_.assign(std::size_t(n_), 0);
    bad_b_.assign(std::size_t(n_), 0);
    mesh_.edge_star(t, a, b, [&](TetId s, int la, int lb) {
      int c = -1, d = -1;
      for (int i = 0; i < 4; ++i)
        if (i != la && i != lb) (c < 0 ? c : d) = i;
      const int pc = position(mesh_.tet_vertex(s, c).idx()), pd = position(mesh_.tet_vertex(s, d).idx());
      const int side = (pc + 1) % n_ == pd ? pc : pd;  // the side (side, side+1) this tet spans
      bad_a_[std::size_t(side)] = glued_to_lasting_bad(mesh_, rules_, HalfFaceId(s, lb));
      bad_b_[std::size_t(side)] = glued_to_lasting_bad(mesh_, rules_, HalfFaceId(s, la));
    });
  }
  int position(std::uint32_t v) const { return int(std::find(r_.begin(), r_.end(), v) - r_.begin()); }

  // A new tet with va (vb) covering the ring side (p, p+1) takes over the ring's face there.
  bool glued_to_bad(const std::array<std::uint32_t, 4>& tet, int i, int k, int j, const std::vector<std::uint8_t>& bad) const {
    if (!all_locked(rules_, tet)) return false;
    return (k == i + 1 && bad[std::size_t(i)]) || (j == k + 1 && bad[std::size_t(k)]) || (i == 0 && j == n_ - 1 && bad[std::size_t(j)]);
  }

  // The two tets of triangle (i, k, j) and its face: worst shape, or kInvalid when not admissible.
  double triangle(int i, int k, int j) const {
    if (rules_.face_image_blocks(r_[i], r_[k], r_[j])) return kInvalid;
    const std::array<std::uint32_t, 4> lower = {r_[i], r_[k], r_[j], va_}, upper = {r_[j], r_[k], r_[i], vb_};
    if (!admissible_tet(mesh_, rules_, fp_, lower) || !admissible_tet(mesh_, rules_, fp_, upper)) return kInvalid;
    if (glued_to_bad(lower, i, k, j, bad_a_) || glued_to_bad(upper, i, k, j, bad_b_)) return kInvalid;
    const double worst = std::min(shape_of(mesh_, lower), shape_of(mesh_, upper));
    return worst >= floor_ ? worst : kInvalid;
  }

  const FpEnvironmentScope fp_;
  const TetMesh& mesh_;
  const ChordRules& rules_;
  const std::uint32_t va_, vb_;
  int n_ = 0;
  std::vector<std::uint32_t> r_;
  std::vector<std::uint8_t> bad_a_, bad_b_;
  double floor_ = 0;
  static constexpr std::uint32_t kKnown = 1u << 31;  // ring_neighbours computed (n_ <= 31)
  std::vector<std::uint32_t> neighbours_;
  std::vector<TetId> star_;
};

}  // namespace

bool remove_chord_edge(TetMesh& mesh, const ChordRules& rules, std::uint32_t a, std::uint32_t b, int max_ring, TetId hint) {
  int la = -1, lb = -1;
  if (hint.is_valid() && hint.idx() < mesh.num_tet_slots() && mesh.tet_is_live(hint)) {
    la = mesh.tet_local_index(hint, VertexId(a));
    lb = mesh.tet_local_index(hint, VertexId(b));
  }
  const TetId t = la >= 0 && lb >= 0 ? hint : mesh.find_edge(VertexId(a), VertexId(b), &la, &lb);
  if (!t.is_valid()) return false;
  std::size_t degree = 0;
  if (!mesh.edge_star(t, la, lb, [&degree](TetId) { ++degree; }) || degree > std::size_t(std::min(max_ring, 31))) return false;
  const std::vector<std::array<int, 3>> triangles = RingTriangulator(mesh, rules, t, la, lb).solve();
  if (triangles.empty()) return false;
  mesh.remove_edge(t, la, lb, triangles);
  return true;
}

bool flip_chord_face(TetMesh& mesh, const ChordRules& rules, const std::array<std::uint32_t, 3>& face) {
  int la = -1, lb = -1;
  const TetId t = mesh.find_edge(VertexId(face[0]), VertexId(face[1]), &la, &lb);
  if (!t.is_valid()) return false;
  // The tet on the face: around the edge (face[0], face[1]), the one holding face[2].
  TetId on_face = TetId::kInvalid;
  mesh.edge_star(t, la, lb, [&](TetId s) {
    if (!on_face.is_valid() && mesh.tet_local_index(s, VertexId(face[2])) >= 0) on_face = s;
  });
  if (!on_face.is_valid()) return false;
  int apex = 0;
  while (std::find(face.begin(), face.end(), mesh.tet_vertex(on_face, apex).idx()) != face.end()) ++apex;
  const HalfFaceId h(on_face, apex);
  if (!mesh.can_flip_2_3(h)) return false;  // topology and exact source positivity
  const std::uint32_t d = mesh.half_face_apex(h).idx(), e = mesh.half_face_apex(mesh.half_face_opposite(h)).idx();
  if (rules.edge_blocks(d, e)) return false;
  for (std::uint32_t x : face)
    if (rules.face_image_blocks(d, e, x)) return false;
  // The new tets: on_face with each face vertex v_j in turn replaced by e (flip_2_3's children);
  // child j takes over the faces opposite v_j of both old tets.
  const auto tv = mesh.tet_vertices(on_face);
  const TetId other = mesh.half_face_opposite(h).tet();
  const auto ov = mesh.tet_vertices(other);
  const double floor = shape_floor(std::min(shape_of(mesh, ids(tv)), shape_of(mesh, ids(ov))));
  for (int j = 0; j < 4; ++j) {
    if (j == apex) continue;
    std::array<std::uint32_t, 4> v = ids(tv);
    v[j] = e;
    if (shape_of(mesh, v) < floor) return false;
    if (!all_locked(rules, v)) continue;
    if (rules.fixed_tet_nonpositive(v) || glued_to_lasting_bad(mesh, rules, HalfFaceId(on_face, j)) ||
        glued_to_lasting_bad(mesh, rules, HalfFaceId(other, mesh.tet_local_index(other, tv[j]))))
      return false;
  }
  mesh.flip_2_3(h);
  return true;
}

}  // namespace volmap
