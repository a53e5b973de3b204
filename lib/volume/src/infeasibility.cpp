// infeasibility.cpp — exact local infeasibility certificates (docs/mapping.md §10; conventions in
// infeasibility.hpp). The search may use doubles (the kernel LP, to pick the constraints); every
// certificate it returns has passed verify_certificate, which decides with exact predicates and
// exact rationals only.
#include <volmap/volume/infeasibility.hpp>

#include <volmap/check/self_intersection.hpp>
#include <volmap/core/error.hpp>
#include <volmap/volume/boundary_image_solid.hpp>
#include <volmap/volume/kernel_lp.hpp>
#include <volmap/volume/radial_start.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace volmap {

namespace {

// Candidate multipliers for the vectors `columns` (each of one length): the one-dimensional null
// vector of the matrix they are the columns of, negated when its entries are all <= 0. Empty when
// the null space is not one-dimensional.
std::vector<Rational> candidate_multipliers(const std::vector<std::vector<Rational>>& columns) {
  if (columns.empty()) return {};
  std::vector<std::vector<Rational>> rows(columns[0].size(), std::vector<Rational>(columns.size()));
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (std::size_t c = 0; c < columns.size(); ++c) rows[r][c] = columns[c][r];
  std::vector<Rational> lambda = one_dimensional_null_vector(std::move(rows));
  if (std::all_of(lambda.begin(), lambda.end(), [](const Rational& x) { return x <= 0; }))
    for (Rational& x : lambda) x = -x;
  return lambda;
}

// Calls f(subset) for every subset of {0..n-1} of size 1..max_size in increasing size; stops when f
// returns true (and returns true then).
template <class F>
bool for_each_small_subset(std::size_t n, std::size_t max_size, F&& f) {
  std::vector<std::size_t> s;
  for (std::size_t size = 1; size <= std::min(max_size, n); ++size) {
    s.resize(size);
    std::iota(s.begin(), s.end(), std::size_t(0));
    while (true) {
      if (f(s)) return true;
      std::size_t i = size;
      while (i > 0 && s[i - 1] == n - size + i - 1) --i;
      if (i == 0) break;
      ++s[i - 1];
      for (std::size_t j = i; j < size; ++j) s[j] = s[j - 1] + 1;
    }
  }
  return false;
}

bool tet_contains(const TetMesh& mesh, std::uint32_t t, std::uint32_t v) {
  for (VertexId u : mesh.tet_vertices(TetId(t)))
    if (u.idx() == v) return true;
  return false;
}

// The face of tet t opposite v, when v is a vertex of t and the face's vertices are all locked.
bool locked_link_face(const TetMesh& mesh, const std::vector<std::uint8_t>& locked, std::uint32_t t, std::uint32_t v,
                      std::array<std::uint32_t, 3>& face) {
  if (t >= mesh.num_tet_slots() || !mesh.tet_is_live(TetId(t)) || !tet_contains(mesh, t, v)) return false;
  const auto f = mesh.half_face_vertices(HalfFaceId(TetId(t), mesh.tet_local_index(TetId(t), VertexId(v))));
  for (int i = 0; i < 3; ++i) {
    face[std::size_t(i)] = f[std::size_t(i)].idx();
    if (!locked[face[std::size_t(i)]]) return false;
  }
  return true;
}

const double* at(const std::vector<double>& X, std::uint32_t v) { return X.data() + 3 * std::size_t(v); }

// The two vertices of tet t other than u and v, ordered so that (u, v, x, y) is an even permutation
// of the tet's vertex order (orient3d(u, v, x, y) is then the tet's own orientation). False when t
// is not a live tet holding both u and v.
bool opposite_edge_oriented(const TetMesh& mesh, std::uint32_t t, std::uint32_t u, std::uint32_t v, std::uint32_t* x,
                            std::uint32_t* y) {
  if (t >= mesh.num_tet_slots() || !mesh.tet_is_live(TetId(t)) || u == v) return false;
  const auto tv = mesh.tet_vertices(TetId(t));
  int pos[4], n = 2;
  pos[0] = pos[1] = -1;
  for (int i = 0; i < 4; ++i) {
    const std::uint32_t w = tv[std::size_t(i)].idx();
    if (w == u) pos[0] = i;
    else if (w == v) pos[1] = i;
    else if (n < 4) pos[n++] = i;
  }
  if (pos[0] < 0 || pos[1] < 0 || n != 4) return false;
  int inversions = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) inversions += pos[i] > pos[j];
  if (inversions % 2 != 0) std::swap(pos[2], pos[3]);
  *x = tv[std::size_t(pos[2])].idx();
  *y = tv[std::size_t(pos[3])].idx();
  return true;
}

// Is (a, b) an edge of a face of ∂M?
bool edge_on_boundary(const TetMesh& mesh, std::uint32_t a, std::uint32_t b) {
  for (HalfFaceId h : mesh.boundary_half_faces()) {
    const auto f = mesh.half_face_vertices(h);
    int hits = 0;
    for (VertexId v : f) hits += v.idx() == a || v.idx() == b;
    if (hits == 2) return true;
  }
  return false;
}

// Is (a, b, c), in any order, a face of ∂M?
bool is_boundary_face(const TetMesh& mesh, std::array<std::uint32_t, 3> abc) {
  std::sort(abc.begin(), abc.end());
  for (HalfFaceId h : mesh.boundary_half_faces()) {
    const auto f = mesh.half_face_vertices(h);
    std::array<std::uint32_t, 3> g = {f[0].idx(), f[1].idx(), f[2].idx()};
    std::sort(g.begin(), g.end());
    if (g == abc) return true;
  }
  return false;
}

// The tets around edge e = (a, b) in rotation order (TetMesh::edge_star_ordered) into `fan`: each as
// (tet, w, w') with orient3d(a, b, w, w') > 0 in the source (the source tets are positive),
// consecutive entries sharing w' = next w. An edge of ∂M gives an open chain from one boundary face
// to the other, an interior edge a cycle (*closed). False when consecutive tets do not share their
// ring vertex that way (not a manifold fan).
struct FanTet {
  std::uint32_t tet, w, w_next;
};
bool ordered_fan(const TetMesh& mesh, EdgeId e, std::uint32_t a, std::uint32_t b, std::vector<FanTet>& fan, bool* closed) {
  fan.clear();
  const std::vector<double>& S = mesh.positions();
  bool two_others = true;
  const std::pair<TetId, int> start = mesh.edge_tet(e);
  *closed = mesh.edge_star_ordered(start.first, kTetEdge[start.second][0], kTetEdge[start.second][1], [&](TetId t) {
    std::uint32_t o[2] = {0, 0}, n = 0;
    for (VertexId v : mesh.tet_vertices(t))
      if (v.idx() != a && v.idx() != b && n < 2) o[n++] = v.idx();
    two_others = two_others && n == 2;
    if (n == 2 && orient3d(at(S, a), at(S, b), at(S, o[0]), at(S, o[1])) < 0) std::swap(o[0], o[1]);
    fan.push_back({t.idx(), o[0], o[1]});
  });
  if (!two_others || fan.empty()) return false;
  if (fan.size() > 1 && fan[0].w_next != fan[1].w) std::reverse(fan.begin(), fan.end());  // walked the other way
  for (std::size_t i = 1; i < fan.size(); ++i)
    if (fan[i - 1].w_next != fan[i].w) return false;
  return true;
}

// The row r with r·(d, m) = −side(line, L) for a line L = (d, m): the tet (u, v, x, y) is positive iff
// r·line(u, v) > 0 for r = cone_row(line(x, y)).
SixVector cone_row(const PluckerLine& xy) {
  return {-xy.m[0], -xy.m[1], -xy.m[2], -xy.d[0], -xy.d[1], -xy.d[2]};
}

class CertificateSearch {
 public:
  CertificateSearch(const TetMesh& mesh, const std::vector<std::uint8_t>& locked, const std::vector<double>& X,
                    const InfeasibilityOptions& options)
      : mesh_(mesh), locked_(locked), X_(X), options_(options) {}

  std::vector<InfeasibilityCertificate> run() {
    fixed_tets();
    coincident_edges();
    degenerate_faces();
    chords_touching_boundary();
    empty_link_kernels();
    wrapping_edge_fans();
    free_edge_lines();
    return std::move(found_);
  }

 private:
  const TetMesh& mesh_;
  const std::vector<std::uint8_t>& locked_;
  const std::vector<double>& X_;
  const InfeasibilityOptions& options_;
  std::vector<InfeasibilityCertificate> found_;

  bool full() const { return options_.max_certificates > 0 && found_.size() >= options_.max_certificates; }
  void keep(InfeasibilityCertificate c) {
    if (!full() && verify_certificate(mesh_, locked_, X_, c)) found_.push_back(std::move(c));
  }
  bool all_locked(const std::uint32_t* v, int n) const {
    for (int i = 0; i < n; ++i)
      if (!locked_[v[i]]) return false;
    return true;
  }

  void fixed_tets() {
    const std::vector<std::uint32_t>& tv = mesh_.tet_vertex_array();
    for (std::uint32_t t = 0; t < mesh_.num_tet_slots() && !full(); ++t) {
      const std::uint32_t* v = &tv[4 * std::size_t(t)];
      if (all_locked(v, 4) && orient3d(at(X_, v[0]), at(X_, v[1]), at(X_, v[2]), at(X_, v[3])) <= 0)
        keep({InfeasibilityKind::FixedTet, {v[0], v[1], v[2], v[3]}, t, {}, {}, {}, {}});
    }
  }

  void coincident_edges() {
    for (std::uint32_t e = 0; e < mesh_.num_edges() && !full(); ++e) {
      const auto ends = mesh_.edge_vertices(EdgeId(e));
      const std::uint32_t v[2] = {ends[0].idx(), ends[1].idx()};
      if (!all_locked(v, 2)) continue;
      if (points_equal(at(X_, v[0]), at(X_, v[1])))
        keep({InfeasibilityKind::CoincidentEdge, {v[0], v[1]}, mesh_.edge_tet(EdgeId(e)).first.idx(), {}, {}, {}, {}});
    }
  }

  void degenerate_faces() {
    for (std::uint32_t h = 0; h < 4 * mesh_.num_tet_slots() && !full(); ++h) {
      const HalfFaceId hf(h);
      const HalfFaceId o = mesh_.half_face_opposite(hf);
      if (o.is_valid() && o.idx() < h) continue;  // each interior face once
      const auto f = mesh_.half_face_vertices(hf);
      const std::uint32_t v[3] = {f[0].idx(), f[1].idx(), f[2].idx()};
      if (all_locked(v, 3) && collinear(at(X_, v[0]), at(X_, v[1]), at(X_, v[2])))
        keep({InfeasibilityKind::DegenerateFace, {v[0], v[1], v[2]}, h / 4, {}, {}, {}, {}});
    }
  }

  // Only on a clearly non-convex image: on a convex one a chord meets ∂D only inside a facet, which
  // DegenerateFace, FixedTet or the untanglers' own count already expose.
  void chords_touching_boundary() {
    if (full() || boundary_image_is_convex(mesh_, X_) || !boundary_image_is_embedded(mesh_, X_)) return;
    const BoundaryImageSolid solid(mesh_, X_);
    for (std::uint32_t e = 0; e < mesh_.num_edges() && !full(); ++e) {
      const auto ends = mesh_.edge_vertices(EdgeId(e));
      const std::uint32_t v[2] = {ends[0].idx(), ends[1].idx()};
      if (!all_locked(v, 2) || !mesh_.edge_star(EdgeId(e), [](TetId) {})) continue;  // an edge of ∂M
      const std::uint32_t f = solid.touched_triangle(v[0], v[1]);
      if (f == BoundaryImageSolid::kNone) continue;
      const auto& t = solid.triangle(f);
      keep({InfeasibilityKind::ChordTouchesBoundary, {v[0], v[1]}, mesh_.edge_tet(EdgeId(e)).first.idx(), {}, {}, {t[0], t[1], t[2]}, {}});
    }
  }

  void empty_link_kernels() {
    std::vector<std::uint32_t> tets;
    std::vector<double> tri;
    for (std::uint32_t v = 0; v < mesh_.num_vertex_slots() && !full(); ++v) {
      if (locked_[v] || !mesh_.vertex_is_live(VertexId(v))) continue;
      tets.clear();
      tri.clear();
      for (TetId t : mesh_.vertex_tets(VertexId(v))) {
        std::array<std::uint32_t, 3> face;
        if (!locked_link_face(mesh_, locked_, t.idx(), v, face)) continue;
        tets.push_back(t.idx());
        for (std::uint32_t u : face) tri.insert(tri.end(), at(X_, u), at(X_, u) + 3);
      }
      if (tets.size() >= std::max<std::size_t>(1, options_.min_fixed_link_faces)) try_link_kernel(v, tets, tri);
    }
  }

  // Edges between locked vertices whose fan holds two locked ring vertices in one half-plane of the
  // edge's line with free ring vertices between them (EdgeFanWraps). The argument needs an embedded
  // boundary image; that test (the costly part) runs once, at the first candidate.
  void wrapping_edge_fans() {
    if (full()) return;
    int embedded = -1;  // not tested yet
    std::vector<FanTet> fan;
    std::vector<std::size_t> locked_at;  // positions in `fan` whose w is locked
    for (std::uint32_t e = 0; e < mesh_.num_edges() && !full(); ++e) {
      const auto ends = mesh_.edge_vertices(EdgeId(e));
      const std::uint32_t a = ends[0].idx(), b = ends[1].idx();
      if (!locked_[a] || !locked_[b] || points_equal(at(X_, a), at(X_, b))) continue;
      bool closed = false;
      if (!ordered_fan(mesh_, EdgeId(e), a, b, fan, &closed)) continue;
      // The ring in fan order; a cycle is walked twice so that a segment may pass its start.
      locked_at.clear();
      const std::size_t n = fan.size(), walk = closed ? 2 * n : n;
      for (std::size_t i = 0; i < walk; ++i)
        if (locked_[fan[i % n].w]) locked_at.push_back(i);
      if (!closed && locked_[fan.back().w_next]) locked_at.push_back(n);  // the chain's last vertex
      for (std::size_t j = 0; j + 1 < locked_at.size() && !full(); ++j) {
        const std::size_t first = locked_at[j], last = locked_at[j + 1];
        if (last - first < 2 || first >= n) continue;  // no free vertex between, or a repeat of the cycle
        const std::uint32_t p = fan[first].w, q = fan[(last - 1) % n].w_next;
        if (!same_half_plane(at(X_, a), at(X_, b), at(X_, p), at(X_, q))) continue;
        if (embedded < 0) embedded = boundary_image_is_embedded(mesh_, X_) ? 1 : 0;
        if (embedded == 0) return;
        InfeasibilityCertificate c{InfeasibilityKind::EdgeFanWraps, {a, b}, fan[first].tet, {}, {}, {}, {}};
        for (std::size_t i = first; i < last; ++i) {
          c.constraint_tets.push_back(fan[i % n].tet);
          c.ring.push_back(fan[i % n].w);
        }
        c.ring.push_back(q);
        keep(std::move(c));
      }
    }
  }

  struct OppositeEdge {
    std::uint32_t tet, x, y;
  };

  // Edges between two free vertices whose star has tets with a locked opposite edge (FreeEdgeLine,
  // FreeEdgeCone).
  void free_edge_lines() {
    std::vector<OppositeEdge> opposite;
    for (std::uint32_t e = 0; e < mesh_.num_edges() && !full(); ++e) {
      const auto ends = mesh_.edge_vertices(EdgeId(e));
      const std::uint32_t u = ends[0].idx(), v = ends[1].idx();
      if (locked_[u] || locked_[v]) continue;
      opposite.clear();
      mesh_.edge_star(EdgeId(e), [&](TetId t) {
        OppositeEdge o{t.idx(), 0, 0};
        if (opposite_edge_oriented(mesh_, t.idx(), u, v, &o.x, &o.y) && locked_[o.x] && locked_[o.y]) opposite.push_back(o);
      });
      if (opposite.size() >= std::max<std::size_t>(1, options_.min_fixed_opposite_edges)) try_free_edge(u, v, opposite);
    }
  }

  // The max-min LP over the six coordinates of the line uv (double; rows normalised, in a frame
  // centred at the locked points; each tet asks side(uv, xy) < 0) decides whether to look and where:
  // an optimum at most kGordanSlack gets the Gordan subsets, one up to kThinCone the cone test.
  void try_free_edge(std::uint32_t u, std::uint32_t v, const std::vector<OppositeEdge>& opposite) {
    const std::size_t m = opposite.size();
    double centre[3] = {0, 0, 0};
    for (const OppositeEdge& o : opposite)
      for (int i = 0; i < 3; ++i) centre[i] += (at(X_, o.x)[i] + at(X_, o.y)[i]) / double(2 * m);
    std::vector<double> rows;
    rows.reserve(6 * m);
    for (const OppositeEdge& o : opposite) {
      double p[3], q[3];
      for (int i = 0; i < 3; ++i) {
        p[i] = at(X_, o.x)[i] - centre[i];
        q[i] = at(X_, o.y)[i] - centre[i];
      }
      // −(moment, direction) of xy: its product with (direction, moment) of uv is −side(uv, xy).
      const double r[6] = {-(p[1] * q[2] - p[2] * q[1]), -(p[2] * q[0] - p[0] * q[2]), -(p[0] * q[1] - p[1] * q[0]),
                           -(q[0] - p[0]),               -(q[1] - p[1]),               -(q[2] - p[2])};
      double len = 0;
      for (double x : r) len += x * x;
      len = std::sqrt(len);
      for (double x : r) rows.push_back(len > 0 ? x / len : 0.0);
    }
    double line[6], slack = 0;
    std::vector<double> weight;
    const bool solved = max_min_slack_in_box(rows, 6, line, &slack, &weight);
    if (solved && slack > kThinCone) return;  // a line, or a wide cone of six-vectors, satisfies them all
    // The rows the LP's dual weighs most first (its support is the Gordan set when the double LP is
    // right), then the rows tightest at its optimum.
    std::vector<std::size_t> order(m);
    std::iota(order.begin(), order.end(), std::size_t(0));
    if (solved) {
      std::vector<double> residual(m, 0.0);
      for (std::size_t j = 0; j < m; ++j)
        for (int i = 0; i < 6; ++i) residual[j] += rows[6 * j + std::size_t(i)] * line[i];
      std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return weight[a] != weight[b] ? weight[a] > weight[b] : residual[a] < residual[b];
      });
    }
    std::vector<PluckerLine> lines(m);
    for (std::size_t j = 0; j < m; ++j) lines[j] = plucker_line(at(X_, opposite[j].x), at(X_, opposite[j].y));
    if ((!solved || slack <= kGordanSlack) && gordan_subsets(u, v, opposite, order, lines)) return;
    if (solved) cone_without_lines(u, v, opposite, order, lines);
  }

  // Thresholds of the line LP's optimum (rows and box normalised): Gordan multipliers are looked for
  // below the first, the cone test runs below the second.
  static constexpr double kGordanSlack = 1e-9;
  static constexpr double kThinCone = 1e-5;
  static constexpr std::size_t kMaxConeRows = 10;  // C(10, 5) = 252 exact eliminations at most

  // Subsets of up to seven rows (Carathéodory: a minimal Gordan set in six unknowns has at most seven
  // members), first in `order` first, each with the one-dimensional rational null vector. True when
  // a certificate was kept.
  bool gordan_subsets(std::uint32_t u, std::uint32_t v, const std::vector<OppositeEdge>& opposite,
                      const std::vector<std::size_t>& order, const std::vector<PluckerLine>& lines) {
    const std::size_t m = opposite.size();
    std::vector<PluckerLine> sub;
    std::vector<std::vector<Rational>> columns;
    for (std::size_t pool : {std::min<std::size_t>(m, 8), m <= 11 ? m : std::size_t(0)}) {
      if (pool == 0) break;
      const bool hit = for_each_small_subset(pool, 7, [&](const std::vector<std::size_t>& s) {
        sub.clear();
        columns.clear();
        for (std::size_t i : s) {
          const PluckerLine& l = lines[order[i]];
          sub.push_back(l);
          columns.push_back({l.d[0], l.d[1], l.d[2], l.m[0], l.m[1], l.m[2]});
        }
        std::vector<Rational> lambda = candidate_multipliers(columns);
        if (!gordan_certifies_no_line(sub, lambda)) return false;
        InfeasibilityCertificate c{InfeasibilityKind::FreeEdgeLine, {u, v}, opposite[order[s[0]]].tet, {}, lambda, {}, {}};
        for (std::size_t i : s) c.constraint_tets.push_back(opposite[order[i]].tet);
        keep(std::move(c));
        return true;
      });
      if (hit) return true;
      if (pool == m) break;
    }
    return false;
  }

  // The cone test on the rows first in `order` (the tightest at the LP optimum), at most
  // kMaxConeRows of them: fewer rows give a wider cone, so a certificate on them holds for all.
  void cone_without_lines(std::uint32_t u, std::uint32_t v, const std::vector<OppositeEdge>& opposite,
                          const std::vector<std::size_t>& order, const std::vector<PluckerLine>& lines) {
    const std::size_t n = std::min(opposite.size(), kMaxConeRows);
    std::vector<SixVector> rows(n);
    InfeasibilityCertificate c{InfeasibilityKind::FreeEdgeCone, {u, v}, opposite[order[0]].tet, {}, {}, {}, {}};
    for (std::size_t i = 0; i < n; ++i) {
      rows[i] = cone_row(lines[order[i]]);
      c.constraint_tets.push_back(opposite[order[i]].tet);
    }
    if (cone_holds_no_line(rows)) keep(std::move(c));
  }

  // The kernel LP bounds its point by the triangles' bounding box, which is flat when the faces
  // are coplanar (a partial link on a domain facet). A triangle with a zero normal is left out of
  // the LP but widens the box: one spanning the box grown by its diagonal on every side.
  static std::vector<double> padded_by_a_flat_triangle(std::vector<double> tri) {
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (std::size_t k = 0; k < tri.size() / 3; ++k)
      for (int i = 0; i < 3; ++i) {
        lo[i] = std::min(lo[i], tri[3 * k + i]);
        hi[i] = std::max(hi[i], tri[3 * k + i]);
      }
    const double diag = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
    for (int corner = 0; corner < 3; ++corner)
      for (int i = 0; i < 3; ++i) tri.push_back(corner < 2 ? lo[i] - diag : hi[i] + diag);
    return tri;
  }

  // The kernel LP (double) decides whether to look; the constraints most violated at its
  // Chebyshev point are tried first, then all of them when there are few.
  void try_link_kernel(std::uint32_t v, const std::vector<std::uint32_t>& tets, const std::vector<double>& tri) {
    double q[3], slack = 0;
    const bool solved = chebyshev_point(padded_by_a_flat_triangle(tri), q, &slack);
    if (solved && slack > 1e-9) return;  // a clearly non-empty kernel
    const std::size_t m = tets.size();
    std::vector<std::size_t> order(m);
    std::iota(order.begin(), order.end(), std::size_t(0));
    if (solved) {
      std::vector<double> residual(m);
      for (std::size_t j = 0; j < m; ++j) {
        double n[3];
        const double len = inward_face_normal(&tri[9 * j], &tri[9 * j + 3], &tri[9 * j + 6], 1.0, n);
        residual[j] = len > 0 ? (n[0] * (q[0] - tri[9 * j]) + n[1] * (q[1] - tri[9 * j + 1]) + n[2] * (q[2] - tri[9 * j + 2])) / len
                              : -1e300;
      }
      std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return residual[a] < residual[b]; });
    }
    std::vector<StrictHalfspace> ks(m);
    for (std::size_t j = 0; j < m; ++j) ks[j] = strict_halfspace(&tri[9 * j], &tri[9 * j + 3], &tri[9 * j + 6]);
    for (std::size_t pool : {std::min<std::size_t>(m, 8), m <= 14 ? m : std::size_t(0)}) {
      if (pool == 0) break;
      std::vector<StrictHalfspace> sub;
      std::vector<std::vector<Rational>> normals;
      const bool hit = for_each_small_subset(pool, 4, [&](const std::vector<std::size_t>& s) {
        sub.clear();
        normals.clear();
        for (std::size_t i : s) {
          sub.push_back(ks[order[i]]);
          normals.push_back({sub.back().n[0], sub.back().n[1], sub.back().n[2]});
        }
        std::vector<Rational> lambda = candidate_multipliers(normals);
        if (!farkas_certifies_empty(sub, lambda)) return false;
        InfeasibilityCertificate c{InfeasibilityKind::EmptyLinkKernel, {v}, tets[order[s[0]]], {}, lambda, {}, {}};
        for (std::size_t i : s) c.constraint_tets.push_back(tets[order[i]]);
        keep(std::move(c));
        return true;
      });
      if (hit || pool == m) break;
    }
  }
};

}  // namespace

const char* infeasibility_kind_name(InfeasibilityKind kind) {
  switch (kind) {
    case InfeasibilityKind::FixedTet: return "fixed-tet";
    case InfeasibilityKind::CoincidentEdge: return "coincident-edge";
    case InfeasibilityKind::DegenerateFace: return "degenerate-face";
    case InfeasibilityKind::ChordTouchesBoundary: return "chord-touches-boundary";
    case InfeasibilityKind::EmptyLinkKernel: return "empty-link-kernel";
    case InfeasibilityKind::EdgeFanWraps: return "edge-fan-wraps";
    case InfeasibilityKind::FreeEdgeLine: return "free-edge-line";
    case InfeasibilityKind::FreeEdgeCone: return "free-edge-cone";
  }
  return "?";
}

std::string describe(const InfeasibilityCertificate& c) {
  auto ids = [](const std::vector<std::uint32_t>& v) {
    std::string s;
    for (std::uint32_t x : v) s += (s.empty() ? "" : " ") + std::to_string(x);
    return s;
  };
  auto weighted_tets = [&c] {  // " t (x λ)" per constraint tet
    std::string w;
    for (std::size_t j = 0; j < c.constraint_tets.size() && j < c.multipliers.size(); ++j)
      w += " " + std::to_string(c.constraint_tets[j]) + " (x " + c.multipliers[j].str() + ")";
    return w;
  };
  std::string s = std::string(infeasibility_kind_name(c.kind)) + ": ";
  switch (c.kind) {
    case InfeasibilityKind::FixedTet:
      return s + "tet " + std::to_string(c.tet) + " (vertices " + ids(c.simplex) + ", all fixed) has orient3d <= 0";
    case InfeasibilityKind::CoincidentEdge:
      return s + "fixed vertices " + ids(c.simplex) + " have the same image: tet " + std::to_string(c.tet) + " is flat";
    case InfeasibilityKind::DegenerateFace:
      return s + "fixed vertices " + ids(c.simplex) + " have collinear images: tet " + std::to_string(c.tet) + " is flat";
    case InfeasibilityKind::ChordTouchesBoundary:
      return s + "the image of the interior edge between fixed vertices " + ids(c.simplex) + " (tet " + std::to_string(c.tet) +
             ") meets the image of the boundary face " + ids(c.boundary_face);
    case InfeasibilityKind::EmptyLinkKernel:
      return s + "free vertex " + ids(c.simplex) + ": the fixed link faces of tets" + weighted_tets() + " have no common strict inner side";
    case InfeasibilityKind::EdgeFanWraps:
      return s + "around the edge between fixed vertices " + ids(c.simplex) + ", the fixed ring vertices " +
             std::to_string(c.ring.front()) + " and " + std::to_string(c.ring.back()) +
             " lie in one half-plane of its line, so the tets from one to the other (" + ids(c.constraint_tets) +
             ") would turn a full circle";
    case InfeasibilityKind::FreeEdgeLine:
      return s + "free edge " + ids(c.simplex) + ": the tets" + weighted_tets() +
             " ask the line through its image to pass on one side of each fixed opposite edge, and no line does";
    case InfeasibilityKind::FreeEdgeCone:
      return s + "free edge " + ids(c.simplex) + ": the tets " + ids(c.constraint_tets) +
             " ask the line through its image to pass on one side of each fixed opposite edge; the six-vectors that do form a "
             "cone off the Klein quadric, which holds no line";
  }
  return s;
}

std::vector<InfeasibilityCertificate> find_local_infeasibility(const TetMesh& source, const std::vector<std::uint8_t>& locked,
                                                               const std::vector<double>& target_xyz,
                                                               const InfeasibilityOptions& options) {
  const std::size_t nv = source.num_vertex_slots();
  if (locked.size() != nv || target_xyz.size() != 3 * nv)
    throw Error(ErrorKind::BadInput, "", 0, "find_local_infeasibility: inconsistent array sizes");
  if (source.num_free_tet_slots() != 0 || source.num_vertices() != nv)
    throw Error(ErrorKind::BadInput, "", 0, "find_local_infeasibility: the mesh has tombstones (compact it first)");
  return CertificateSearch(source, locked, target_xyz, options).run();
}

bool verify_certificate(const TetMesh& mesh, const std::vector<std::uint8_t>& locked, const std::vector<double>& X,
                        const InfeasibilityCertificate& c) {
  const std::size_t nv = mesh.num_vertex_slots();
  if (locked.size() != nv || X.size() != 3 * nv) return false;
  for (std::uint32_t v : c.simplex)
    if (v >= nv || !mesh.vertex_is_live(VertexId(v))) return false;
  if (c.tet >= mesh.num_tet_slots() || !mesh.tet_is_live(TetId(c.tet))) return false;
  auto in_tet = [&](std::uint32_t t) {
    return std::all_of(c.simplex.begin(), c.simplex.end(), [&](std::uint32_t v) { return tet_contains(mesh, t, v); });
  };
  auto simplex_locked = [&] { return std::all_of(c.simplex.begin(), c.simplex.end(), [&](std::uint32_t v) { return locked[v] != 0; }); };
  switch (c.kind) {
    case InfeasibilityKind::FixedTet: {
      if (c.simplex.size() != 4 || !simplex_locked()) return false;
      const auto tv = mesh.tet_vertices(TetId(c.tet));
      for (int i = 0; i < 4; ++i)
        if (tv[std::size_t(i)].idx() != c.simplex[std::size_t(i)]) return false;
      return orient3d(at(X, c.simplex[0]), at(X, c.simplex[1]), at(X, c.simplex[2]), at(X, c.simplex[3])) <= 0;
    }
    case InfeasibilityKind::CoincidentEdge: {
      if (c.simplex.size() != 2 || c.simplex[0] == c.simplex[1] || !simplex_locked() || !in_tet(c.tet)) return false;
      return points_equal(at(X, c.simplex[0]), at(X, c.simplex[1]));
    }
    case InfeasibilityKind::DegenerateFace: {
      if (c.simplex.size() != 3 || !simplex_locked() || !in_tet(c.tet)) return false;
      const std::uint32_t a = c.simplex[0], b = c.simplex[1], d = c.simplex[2];
      return a != b && b != d && a != d && collinear(at(X, a), at(X, b), at(X, d));
    }
    case InfeasibilityKind::ChordTouchesBoundary: {
      if (c.simplex.size() != 2 || c.simplex[0] == c.simplex[1] || !simplex_locked() || !in_tet(c.tet)) return false;
      if (c.boundary_face.size() != 3 || edge_on_boundary(mesh, c.simplex[0], c.simplex[1])) return false;
      const std::array<std::uint32_t, 3> f = {c.boundary_face[0], c.boundary_face[1], c.boundary_face[2]};
      for (std::uint32_t v : f)
        if (v >= nv || !locked[v] || v == c.simplex[0] || v == c.simplex[1]) return false;
      if (!is_boundary_face(mesh, f) || triangle_is_degenerate(at(X, f[0]), at(X, f[1]), at(X, f[2]))) return false;
      return segment_intersects_triangle(at(X, c.simplex[0]), at(X, c.simplex[1]), at(X, f[0]), at(X, f[1]), at(X, f[2])) &&
             boundary_image_is_embedded(mesh, X);
    }
    case InfeasibilityKind::EdgeFanWraps: {
      // The tets (a, b, ring[i], ring[i+1]), each positive in the source with this order, i.e. a path
      // of the fan; the ends locked, the inner ring vertices free; then the exact geometric condition.
      if (c.simplex.size() != 2 || c.simplex[0] == c.simplex[1] || !simplex_locked()) return false;
      const std::size_t k = c.constraint_tets.size();
      if (k < 2 || c.ring.size() != k + 1 || c.tet != c.constraint_tets[0]) return false;
      const std::uint32_t a = c.simplex[0], b = c.simplex[1];
      for (std::uint32_t v : c.ring)
        if (v >= nv || v == a || v == b) return false;
      if (!locked[c.ring.front()] || !locked[c.ring.back()] || c.ring.front() == c.ring.back()) return false;
      for (std::size_t i = 1; i < k; ++i)
        if (locked[c.ring[i]]) return false;
      const std::vector<double>& S = mesh.positions();
      for (std::size_t i = 0; i < k; ++i) {
        const std::uint32_t t = c.constraint_tets[i];
        if (t >= mesh.num_tet_slots() || !mesh.tet_is_live(TetId(t))) return false;
        for (std::uint32_t v : {a, b, c.ring[i], c.ring[i + 1]})
          if (!tet_contains(mesh, t, v)) return false;
        if (orient3d(at(S, a), at(S, b), at(S, c.ring[i]), at(S, c.ring[i + 1])) <= 0) return false;
      }
      return !points_equal(at(X, a), at(X, b)) &&
             same_half_plane(at(X, a), at(X, b), at(X, c.ring.front()), at(X, c.ring.back())) &&
             boundary_image_is_embedded(mesh, X);
    }
    case InfeasibilityKind::FreeEdgeLine:
    case InfeasibilityKind::FreeEdgeCone: {
      const bool cone = c.kind == InfeasibilityKind::FreeEdgeCone;  // no multipliers; Gordan: one per tet
      const bool multipliers_fit = cone ? c.multipliers.empty() : c.multipliers.size() == c.constraint_tets.size();
      if (c.simplex.size() != 2 || c.simplex[0] == c.simplex[1] || locked[c.simplex[0]] || locked[c.simplex[1]] ||
          c.constraint_tets.empty() || !multipliers_fit || c.tet != c.constraint_tets[0])
        return false;
      std::vector<PluckerLine> lines;
      for (std::uint32_t t : c.constraint_tets) {
        std::uint32_t x = 0, y = 0;
        if (!opposite_edge_oriented(mesh, t, c.simplex[0], c.simplex[1], &x, &y) || !locked[x] || !locked[y]) return false;
        lines.push_back(plucker_line(at(X, x), at(X, y)));
      }
      if (!cone) return gordan_certifies_no_line(lines, c.multipliers);
      std::vector<SixVector> rows;
      for (const PluckerLine& l : lines) rows.push_back(cone_row(l));
      return cone_holds_no_line(rows);
    }
    case InfeasibilityKind::EmptyLinkKernel: {
      if (c.simplex.size() != 1 || locked[c.simplex[0]] || c.constraint_tets.empty() ||
          c.constraint_tets.size() != c.multipliers.size() || !in_tet(c.tet))
        return false;
      std::vector<StrictHalfspace> ks;
      for (std::uint32_t t : c.constraint_tets) {
        std::array<std::uint32_t, 3> f;
        if (!locked_link_face(mesh, locked, t, c.simplex[0], f)) return false;
        ks.push_back(strict_halfspace(at(X, f[0]), at(X, f[1]), at(X, f[2])));
      }
      return farkas_certifies_empty(ks, c.multipliers);
    }
  }
  return false;
}

}  // namespace volmap
