// cone_repair.cpp — B1 of docs/mapping.md §7 (star-patch cone repair, original vertices kept), its
// strict-kernel LP and the vertex-star pre-step.
// Orientation: for an outward face (a,b,c) (kTetFace order of a VOLMAP-positive tet), a point q
// is on the tet's side iff orient3d(a,b,c,q) > 0, i.e. n·(q − a) > 0 with n = (c−a)×(b−a).
// The LP is a dense condensed-tableau simplex (Bland's rule) in 4 variables (q, s): maximise s
// subject to n̂_F·(q − a_F) ≥ s for every face and q in the faces' bounding box; solved in double,
// the point is then verified with exact orient3d.
// Growth of R (not in §7's text): steepest ascent on the kernel-LP slack over the tets behind the most
// violated ∂R faces, stopped after ConeRepairOptions::stall_growth_steps steps without progress, then
// retried with other lookaheads (the greedy is path dependent); see repair_cluster.
#include <volmap/volume/cone_repair.hpp>

#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>

namespace volmap {

namespace {

// maximise c·x s.t. A x <= b, x >= 0 with b >= 0 (origin feasible). A is m×n row-major.
// Returns false when unbounded or out of iterations; x receives the solution.
bool simplex_max(int m, int n, std::vector<double>& A, std::vector<double>& b, std::vector<double> c, double* x) {
  std::vector<int> row_label(m), col_label(n);  // labels: 0..n-1 original vars, n.. slacks
  for (int j = 0; j < n; ++j) col_label[j] = j;
  for (int i = 0; i < m; ++i) row_label[i] = n + i;
  const double eps = 1e-12;
  for (int iter = 0; iter < 50 * (m + n); ++iter) {
    int e = -1;
    for (int j = 0; j < n; ++j)
      if (c[j] > eps && (e < 0 || col_label[j] < col_label[e])) e = j;
    if (e < 0) break;  // optimal
    int r = -1;
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < m; ++i) {
      const double a = A[std::size_t(i) * n + e];
      if (a > eps) {
        const double ratio = b[i] / a;
        if (ratio < best - 1e-15 || (ratio <= best + 1e-15 && r >= 0 && row_label[i] < row_label[r])) {
          best = ratio;
          r = i;
        }
      }
    }
    if (r < 0) return false;  // unbounded
    const double piv = A[std::size_t(r) * n + e];
    // Row r.
    for (int j = 0; j < n; ++j)
      if (j != e) A[std::size_t(r) * n + j] /= piv;
    b[r] /= piv;
    A[std::size_t(r) * n + e] = 1.0 / piv;
    for (int i = 0; i < m; ++i) {
      if (i == r) continue;
      const double aie = A[std::size_t(i) * n + e];
      if (aie == 0) continue;
      for (int j = 0; j < n; ++j)
        if (j != e) A[std::size_t(i) * n + j] -= aie * A[std::size_t(r) * n + j];
      b[i] -= aie * b[r];
      A[std::size_t(i) * n + e] = -aie / piv;
    }
    const double ce = c[e];
    for (int j = 0; j < n; ++j)
      if (j != e) c[j] -= ce * A[std::size_t(r) * n + j];
    c[e] = -ce / piv;
    std::swap(row_label[r], col_label[e]);
  }
  for (int j = 0; j < n; ++j) x[j] = 0;
  for (int i = 0; i < m; ++i)
    if (row_label[i] < n) x[row_label[i]] = b[i];
  return true;
}

}  // namespace

namespace {

// Normal n = ((c − a)·scale) × ((b − a)·scale) of the outward face (a,b,c): it points to the tet's
// side (the file's convention above). Returns |n| (0 for a face degenerate in double).
double inward_face_normal(const double* a, const double* b, const double* c, double scale, double* n) {
  double u[3], v[3];
  for (int i = 0; i < 3; ++i) {
    u[i] = (c[i] - a[i]) * scale;
    v[i] = (b[i] - a[i]) * scale;
  }
  n[0] = u[1] * v[2] - u[2] * v[1];
  n[1] = u[2] * v[0] - u[0] * v[2];
  n[2] = u[0] * v[1] - u[1] * v[0];
  return std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

// Chebyshev centre of the kernel LP (see the file comment), in double. Faces whose normal vanishes in
// double are left out (the exact verification of the caller rejects them). Returns false when the LP
// could not be set up or solved; otherwise q is the max-min point and *slack the optimal s in the
// normalised frame (> 0 iff the double LP found an interior point).
bool chebyshev_point(const std::vector<double>& tri, double* q, double* slack) {
  const std::size_t nf = tri.size() / 9;
  if (nf == 0) return false;
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (std::size_t k = 0; k < 3 * nf; ++k)
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], tri[3 * k + i]);
      hi[i] = std::max(hi[i], tri[3 * k + i]);
    }
  const double diag = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
  if (!(diag > 0)) return false;
  // Work in a frame centred at lo and scaled by 1/diag (conditioning).
  const double inv = 1.0 / diag;
  const double S0 = 2.0;
  const int n = 4;
  std::vector<double> A, b;
  A.reserve((nf + 4) * n);
  b.reserve(nf + 4);
  for (std::size_t f = 0; f < nf; ++f) {
    const double* a = &tri[9 * f];
    const double* bb = a + 3;
    const double* c = a + 6;
    double nn[3];
    const double len = inward_face_normal(a, bb, c, inv, nn);
    if (!(len > 0)) continue;  // degenerate in double: no strict kernel (left to the exact check)
    // n̂·(q' − a') ≥ s  ⇔  −n̂·q' + s' ≤ −n̂·a' + S0   (q' = (q − lo)/diag, s' = s + S0)
    double rhs = S0;
    for (int i = 0; i < 3; ++i) {
      const double ni = nn[i] / len;
      A.push_back(-ni);
      rhs -= ni * (a[i] - lo[i]) * inv;
    }
    A.push_back(1.0);
    b.push_back(std::max(rhs, 0.0));
  }
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) A.push_back(i == j ? 1.0 : 0.0);
    b.push_back(i < 3 ? (hi[i] - lo[i]) * inv : S0 + 1.0);
  }
  const int m = int(b.size());
  double x[4];
  if (!simplex_max(m, n, A, b, {0, 0, 0, 1}, x)) return false;
  *slack = x[3] - S0;
  for (int i = 0; i < 3; ++i) q[i] = lo[i] + x[i] * diag;
  return true;
}

// Exact: q strictly on the inner side of every triangle (fp: the caller's environment scope).
bool verified_inside(const FpEnvironmentScope& fp, const std::vector<double>& tri, const double* q) {
  for (std::size_t f = 0; f < tri.size() / 9; ++f)
    if (fp.orient3d(&tri[9 * f], &tri[9 * f + 3], &tri[9 * f + 6], q) <= 0) return false;
  return true;
}

bool strict_kernel_point_in(const FpEnvironmentScope& fp, const std::vector<double>& tri, double* q) {
  double slack = 0;
  if (!chebyshev_point(tri, q, &slack) || !(slack > 0)) return false;
  return verified_inside(fp, tri, q);
}

}  // namespace

bool strict_kernel_point(const std::vector<double>& tri, double* q) {
  const FpEnvironmentScope fp;
  return strict_kernel_point_in(fp, tri, q);
}

namespace {

constexpr std::uint64_t kNoFace = ~std::uint64_t(0);
constexpr std::uint32_t kNoTet = ~std::uint32_t(0);

using Tri = std::array<std::uint32_t, 3>;

Tri sorted(Tri f) {
  std::sort(f.begin(), f.end());
  return f;
}

// orient3d in plain double (only for barycentric coordinates and ranking; never for a validity sign).
double signed_volume(const double* a, const double* b, const double* c, const double* d) {
  const double ax = a[0] - d[0], ay = a[1] - d[1], az = a[2] - d[2];
  const double bx = b[0] - d[0], by = b[1] - d[1], bz = b[2] - d[2];
  const double cx = c[0] - d[0], cy = c[1] - d[1], cz = c[2] - d[2];
  return ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx);
}

// A face of ∂R: outward vertex order, the half-face on the other side (kNoFace on ∂M), R's tet.
struct RegionFace {
  Tri v;
  std::uint64_t outside;
  std::uint32_t inner_tet;
};

// Tet slots with face adjacency, edited patch by patch (slots of R reused, extra ones appended,
// dead slots dropped by finish()).
class ConeRepairer {
 public:
  ConeRepairer(TetMeshData& source, std::vector<std::uint8_t>& on_boundary, std::vector<double>& target, const ConeRepairOptions& options)
      : src_(source), onb_(on_boundary), tx_(target), opt_(options) {
    const std::size_t nt = src_.num_tets(), nv = src_.num_vertices();
    has_labels_ = src_.tet_labels.size() == nt;
    alive_.assign(nt, 1);
    nb_.assign(4 * nt, kNoFace);
    in_region_.assign(nt, 0);
    seen_.assign(nt, 0);
    struct Key {
      Tri f;
      std::uint64_t hf;
    };
    std::vector<Key> keys(4 * nt);
    for (std::size_t t = 0; t < nt; ++t)
      for (int i = 0; i < 4; ++i) keys[4 * t + i] = {sorted(face(std::uint32_t(t), i)), 4 * t + i};
    std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) { return a.f < b.f; });
    for (std::size_t k = 0; k + 1 < keys.size(); ++k)
      if (keys[k].f == keys[k + 1].f) {
        nb_[keys[k].hf] = keys[k + 1].hf;
        nb_[keys[k + 1].hf] = keys[k].hf;
        ++k;
      }
    v2t_.assign(nv, kNoTet);
    for (std::size_t t = 0; t < nt; ++t)
      for (int i = 0; i < 4; ++i) v2t_[src_.tets[4 * t + i]] = std::uint32_t(t);
    vmark_.assign(nv, 0);
  }

  bool out_of_time() const {
    return opt_.time_limit_seconds > 0 &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count() >= opt_.time_limit_seconds;
  }

  ConeRepairResult run() {
    ConeRepairResult& res = res_;
    res.tets_before = src_.num_tets();
    const std::size_t nv0 = src_.num_vertices();
    for (int round = 0; round < std::max(1, opt_.max_rounds); ++round) {
      std::vector<std::vector<std::uint32_t>> clusters = find_clusters();
      if (round == 0) res.clusters = clusters.size();
      if (clusters.empty()) {
        res.failed_clusters = 0;
        break;
      }
      std::sort(clusters.begin(), clusters.end(), [](const auto& a, const auto& b) { return a.size() < b.size(); });
      std::size_t applied = 0, failed = 0;
      for (auto& cluster : clusters) {
        if (out_of_time()) break;
        // Earlier patches of this round may have replaced some of these tets (their slots now hold
        // positive tets): keep the ones still non-positive.
        cluster.erase(std::remove_if(cluster.begin(), cluster.end(), [&](std::uint32_t t) { return !alive_[t] || target_sign(t) > 0; }),
                      cluster.end());
        if (cluster.empty()) continue;
        ++res.attempts;
        if (repair_cluster(cluster)) {
          ++applied;
          res.max_region = std::max(res.max_region, region_.size());
        } else {
          ++failed;
        }
      }
      res.patches += applied;
      res.failed_clusters = failed;
      if (out_of_time()) {
        res.failed_clusters = find_clusters().size();
        break;
      }
      if (applied == 0) break;
      if (round + 1 == std::max(1, opt_.max_rounds)) res.failed_clusters = find_clusters().size();
    }
    finish();
    res.tets_after = src_.num_tets();
    res.vertices_added = src_.num_vertices() - nv0;
    return res;
  }

 private:
  // One floating-point environment check for the whole repair (the repairer lives on the stack of
  // cone_repair(), single-threaded): every exact sign below is fp_.orient3d, the unchecked predicate.
  const FpEnvironmentScope fp_;
  TetMeshData& src_;
  std::vector<std::uint8_t>& onb_;
  std::vector<double>& tx_;
  ConeRepairOptions opt_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  ConeRepairResult res_;
  bool has_labels_ = false;
  std::vector<std::uint8_t> alive_;
  std::vector<std::uint64_t> nb_;
  std::vector<std::uint32_t> v2t_;
  std::vector<std::uint32_t> in_region_, seen_, vmark_;
  std::uint32_t region_stamp_ = 0, seen_stamp_ = 0, vstamp_ = 0;
  long long net_added_ = 0;
  std::vector<std::uint32_t> region_;
  std::vector<RegionFace> faces_;
  bool aimed_ = false;  // grow_region with a fixed target point

  Tri face(std::uint32_t t, int i) const {
    const std::uint32_t* tv = &src_.tets[4 * std::size_t(t)];
    const std::uint8_t* l = kTetFace[i];
    return {tv[l[0]], tv[l[1]], tv[l[2]]};
  }
  const double* S(std::uint32_t v) const { return &src_.xyz[3 * std::size_t(v)]; }
  const double* T(std::uint32_t v) const { return &tx_[3 * std::size_t(v)]; }
  int target_sign(std::uint32_t t) const {
    const std::uint32_t* v = &src_.tets[4 * std::size_t(t)];
    return fp_.orient3d(T(v[0]), T(v[1]), T(v[2]), T(v[3]));
  }

  std::vector<std::vector<std::uint32_t>> find_clusters() {
    const std::size_t ns = alive_.size();
    std::vector<std::uint8_t> bad(ns, 0);
    for (std::size_t t = 0; t < ns; ++t)
      if (alive_[t] && target_sign(std::uint32_t(t)) <= 0) bad[t] = 1;
    std::vector<std::vector<std::uint32_t>> out;
    for (std::size_t t0 = 0; t0 < ns; ++t0) {
      if (bad[t0] != 1) continue;
      std::vector<std::uint32_t> c{std::uint32_t(t0)};
      bad[t0] = 2;
      for (std::size_t k = 0; k < c.size(); ++k)
        for (int i = 0; i < 4; ++i) {
          const std::uint64_t o = nb_[4 * std::size_t(c[k]) + i];
          if (o != kNoFace && bad[o / 4] == 1) {
            bad[o / 4] = 2;
            c.push_back(std::uint32_t(o / 4));
          }
        }
      out.push_back(std::move(c));
    }
    return out;
  }

  // Tets around vertex v (face-connected through faces containing v).
  void star(std::uint32_t v, std::vector<std::uint32_t>& out) {
    out.clear();
    const std::uint32_t t0 = v2t_[v];
    if (t0 == kNoTet) return;
    ++seen_stamp_;
    seen_[t0] = seen_stamp_;
    out.push_back(t0);
    for (std::size_t k = 0; k < out.size(); ++k) {
      const std::uint32_t t = out[k];
      for (int i = 0; i < 4; ++i) {
        if (src_.tets[4 * std::size_t(t) + i] == v) continue;  // the face opposite v does not contain v
        const std::uint64_t o = nb_[4 * std::size_t(t) + i];
        if (o == kNoFace || seen_[o / 4] == seen_stamp_) continue;
        seen_[o / 4] = seen_stamp_;
        out.push_back(std::uint32_t(o / 4));
      }
    }
  }

  bool add_to_region(std::uint32_t t) {
    if (in_region_[t] == region_stamp_) return false;
    in_region_[t] = region_stamp_;
    region_.push_back(t);
    return true;
  }
  // Adds t; when t is non-positive in the target, also the stars of its vertices (clusters merge;
  // not in aimed growth, where the stars of a far-off vertex would bring in ∂M faces aim cannot see).
  std::size_t add_with_merge(std::uint32_t t) {
    if (!add_to_region(t)) return 0;
    std::size_t added = 1;
    if (!aimed_ && target_sign(t) <= 0) {
      std::vector<std::uint32_t> st;
      for (int i = 0; i < 4; ++i) {
        star(src_.tets[4 * std::size_t(t) + i], st);
        for (auto s : st) added += add_to_region(s);
      }
    }
    return added;
  }

  void region_boundary() {
    faces_.clear();
    for (std::uint32_t t : region_)
      for (int i = 0; i < 4; ++i) {
        const std::uint64_t o = nb_[4 * std::size_t(t) + i];
        if (o == kNoFace || in_region_[o / 4] != region_stamp_) faces_.push_back({face(t, i), o, t});
      }
  }

  // Checks that ∂R (faces_) is a closed 2-manifold sphere. Fills offending vertices/edges, the
  // component of each face and returns the Euler characteristic (V − E + F).
  long long ball_check(std::vector<std::uint32_t>& bad_vertices, std::vector<std::array<std::uint32_t, 2>>& bad_edges,
                       std::vector<std::uint32_t>& comp, std::size_t& ncomp) {
    bad_vertices.clear();
    bad_edges.clear();
    const std::size_t nf = faces_.size();
    // Directed edges (min, max, forward?, face).
    struct E {
      std::uint32_t a, b;
      std::uint8_t fwd;
      std::uint32_t f;
    };
    std::vector<E> edges;
    edges.reserve(3 * nf);
    for (std::size_t f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = faces_[f].v[k], b = faces_[f].v[(k + 1) % 3];
        edges.push_back({std::min(a, b), std::max(a, b), std::uint8_t(a < b), std::uint32_t(f)});
      }
    std::sort(edges.begin(), edges.end(), [](const E& x, const E& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
    std::vector<std::uint32_t> parent(nf);
    for (std::size_t f = 0; f < nf; ++f) parent[f] = std::uint32_t(f);
    auto find = [&](std::uint32_t x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    long long num_edges = 0;
    for (std::size_t k = 0; k < edges.size();) {
      std::size_t j = k;
      int fwd = 0, bwd = 0;
      while (j < edges.size() && edges[j].a == edges[k].a && edges[j].b == edges[k].b) {
        (edges[j].fwd ? fwd : bwd)++;
        parent[find(edges[j].f)] = find(edges[k].f);
        ++j;
      }
      ++num_edges;
      if (fwd != 1 || bwd != 1) bad_edges.push_back({edges[k].a, edges[k].b});
      k = j;
    }
    // Vertex fans: at corner v of (v, a, b) the fan steps a → b; one cycle per manifold vertex.
    struct C {
      std::uint32_t v, a, b;
    };
    std::vector<C> corners;
    corners.reserve(3 * nf);
    for (const auto& f : faces_)
      for (int k = 0; k < 3; ++k) corners.push_back({f.v[k], f.v[(k + 1) % 3], f.v[(k + 2) % 3]});
    std::sort(corners.begin(), corners.end(), [](const C& x, const C& y) { return x.v != y.v ? x.v < y.v : x.a < y.a; });
    long long num_vertices = 0;
    for (std::size_t k = 0; k < corners.size();) {
      std::size_t j = k;
      while (j < corners.size() && corners[j].v == corners[k].v) ++j;
      ++num_vertices;
      const std::size_t deg = j - k;
      std::uint32_t cur = corners[k].a;
      std::size_t steps = 0;
      bool ok = true;
      do {
        auto it = std::lower_bound(corners.begin() + long(k), corners.begin() + long(j), cur,
                                   [](const C& c, std::uint32_t a) { return c.a < a; });
        if (it == corners.begin() + long(j) || it->a != cur || (it + 1 != corners.begin() + long(j) && (it + 1)->a == cur)) {
          ok = false;
          break;
        }
        cur = it->b;
        ++steps;
      } while (cur != corners[k].a && steps <= deg);
      if (!ok || steps != deg) bad_vertices.push_back(corners[k].v);
      k = j;
    }
    comp.assign(nf, 0);
    ncomp = 0;
    std::vector<std::uint32_t> id(nf, kNoTet);
    for (std::size_t f = 0; f < nf; ++f) {
      const std::uint32_t r = find(std::uint32_t(f));
      if (id[r] == kNoTet) id[r] = std::uint32_t(ncomp++);
      comp[f] = id[r];
    }
    return num_vertices - num_edges + (long long)nf;
  }

  // The faces of ∂R as LP triangles (9 doubles each) in target and source coordinates.
  void face_triangles(std::vector<double>& tri_t, std::vector<double>& tri_s) const {
    tri_t.clear();
    tri_s.clear();
    for (const auto& f : faces_)
      for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 3; ++i) {
          tri_t.push_back(T(f.v[k])[i]);
          tri_s.push_back(S(f.v[k])[i]);
        }
  }

  // Kernel-LP progress of the current region (double only, for ranking growth candidates): the
  // target slack, or 2 + the source slack once the target LP has an interior point.
  double region_progress(std::vector<double>& tri_t, std::vector<double>& tri_s) {
    region_boundary();
    face_triangles(tri_t, tri_s);
    double x[3], slack = -1;
    ++res_.lp_solves;
    if (!chebyshev_point(tri_t, x, &slack)) return -1.0;
    if (!(slack > 0)) return slack;
    ++res_.lp_solves;
    return chebyshev_point(tri_s, x, &slack) ? 2.0 + slack : 1.0;
  }

  // Grows region_ from the cluster until it is a ball whose boundary has a strict kernel point in
  // both spaces; p (source) and q (target) receive them.
  // lookahead: growth candidates tried per step (<= 1: the most violated face only). A failure is
  // counted in res_.failures only when count_failure is set.
  // aim (optional): a fixed target point instead of the target kernel LP; each step then adds the
  // tets behind every face of ∂R that aim does not see strictly (exact orient3d), and the region is
  // accepted when aim sees all of ∂R (q = aim) and the source LP has a verified strict point.
  bool grow_region(const std::vector<std::uint32_t>& cluster, double* p, double* q, int lookahead, bool count_failure,
                   const double* aim = nullptr) {
    ++region_stamp_;
    region_.clear();
    aimed_ = aim != nullptr;
    std::vector<std::uint32_t> st;
    for (std::uint32_t t : cluster) add_with_merge(t);
    std::vector<std::uint32_t> bad_vertices, comp;
    std::vector<std::array<std::uint32_t, 2>> bad_edges;
    std::vector<double> tri_t, tri_s;
    std::vector<std::pair<double, std::uint32_t>> candidates;  // (violation, tet behind)
    auto& fail = res_.failures;
    int last_fail = 0;  // 1 target kernel empty, 2 source kernel empty
    double best_progress = -std::numeric_limits<double>::infinity();
    int best_step = 0;
    auto growth_failed = [&](std::size_t& counter) {
      if (!count_failure) return false;
      ++counter;
      if (last_fail == 1) ++fail.last_no_target;
      if (last_fail == 2) ++fail.last_no_source;
      return false;
    };
    for (int step = 0; step < opt_.max_growth_steps; ++step) {
      if (out_of_time()) return growth_failed(fail.time_limit);
      ++res_.growth_steps;
      if (opt_.max_region_tets > 0 && region_.size() > opt_.max_region_tets) return growth_failed(fail.region_limit);
      region_boundary();
      if (aim) {
        // Aimed growth: exact visibility from aim first (before the ball repairs, which add whole
        // stars); a face on ∂M that aim does not see ends it.
        std::size_t added = 0;
        for (const auto& f : faces_) {
          if (fp_.orient3d(T(f.v[0]), T(f.v[1]), T(f.v[2]), aim) > 0) continue;
          if (f.outside == kNoFace) return growth_failed(fail.no_growth_face);
          added += add_to_region(std::uint32_t(f.outside / 4));
        }
        if (added > 0) continue;
      }
      std::size_t ncomp = 0;
      const long long chi = ball_check(bad_vertices, bad_edges, comp, ncomp);
      if (!bad_vertices.empty() || !bad_edges.empty()) {
        std::size_t added = 0;
        for (auto v : bad_vertices) {
          star(v, st);
          for (auto t : st) added += add_with_merge(t);
        }
        for (const auto& e : bad_edges) {
          star(e[0], st);
          for (auto t : st) {
            const std::uint32_t* tv = &src_.tets[4 * std::size_t(t)];
            if (tv[0] == e[1] || tv[1] == e[1] || tv[2] == e[1] || tv[3] == e[1]) added += add_with_merge(t);
          }
        }
        if (added == 0) return growth_failed(fail.not_ball);
        continue;
      }
      if (ncomp > 1 || chi != 2) {
        // Cavities: fill from the faces of every component but the largest. Handles: fill pockets
        // (outside tets with two or more faces on ∂R).
        std::vector<std::size_t> size(ncomp, 0);
        for (auto c : comp) ++size[c];
        const std::size_t largest = std::size_t(std::max_element(size.begin(), size.end()) - size.begin());
        std::size_t added = 0;
        std::vector<std::uint32_t> behind;
        for (std::size_t f = 0; f < faces_.size(); ++f)
          if (faces_[f].outside != kNoFace) {
            if (ncomp > 1 && comp[f] != largest) added += add_with_merge(std::uint32_t(faces_[f].outside / 4));
            behind.push_back(std::uint32_t(faces_[f].outside / 4));
          }
        if (ncomp == 1) {
          std::sort(behind.begin(), behind.end());
          for (std::size_t k = 0; k + 1 < behind.size(); ++k)
            if (behind[k] == behind[k + 1]) added += add_with_merge(behind[k]);
        }
        if (added == 0) return growth_failed(fail.not_ball);
        continue;
      }
      if (aim) {
        // Aimed growth, ∂R a sphere seen from aim: the source kernel decides.
        last_fail = 2;
        for (int i = 0; i < 3; ++i) q[i] = aim[i];
        face_triangles(tri_t, tri_s);
        double slack_s = -1;
        ++res_.lp_solves;
        if (chebyshev_point(tri_s, p, &slack_s) && slack_s > 0 && verified_inside(fp_, tri_s, p)) return true;
        return growth_failed(fail.stalled);
      }
      face_triangles(tri_t, tri_s);
      double slack_t = -1, slack_s = -1;
      res_.lp_solves += 1;
      bool have_t = chebyshev_point(tri_t, q, &slack_t);
      const bool ok_t = have_t && slack_t > 0 && verified_inside(fp_, tri_t, q);
      bool ok_s = false, have_s = false;
      if (ok_t) {
        ++res_.lp_solves;
        have_s = chebyshev_point(tri_s, p, &slack_s);
        ok_s = have_s && slack_s > 0 && verified_inside(fp_, tri_s, p);
        if (ok_s) return true;
      }
      // Progress: the LP slack of the failing space (source phase ranked above the target phase).
      // Measured on stalled G1 star maps (gargoyle, camile_hand): failing regions wander for hundreds
      // of steps without improving it (the slack even gets worse); with plain growth a 128-step stall
      // limit kept every patch of the 400-step run (45 patches) and cut the time 5.7 s → 1.4 s
      // (gargoyle), 3.8 s → 1.6 s (camile_hand).
      const double progress = ok_t ? 2.0 + (have_s ? slack_s : -1.0) : (have_t ? slack_t : -1.0);
      if (progress > best_progress) {
        best_progress = progress;
        best_step = step;
      } else if (opt_.stall_growth_steps > 0 && step - best_step >= opt_.stall_growth_steps) {
        last_fail = ok_t ? 2 : 1;
        return growth_failed(fail.stalled);
      }
      // Grow behind the most violated constraint of the failing space (faces on ∂M cannot move).
      const bool target_fails = !ok_t;
      last_fail = target_fails ? 1 : 2;
      const std::vector<double>& tri = target_fails ? tri_t : tri_s;
      double pt[3];
      if (target_fails ? have_t : have_s) {
        for (int i = 0; i < 3; ++i) pt[i] = target_fails ? q[i] : p[i];
      } else {
        pt[0] = pt[1] = pt[2] = 0;
        for (std::size_t k = 0; k < tri.size() / 3; ++k)
          for (int i = 0; i < 3; ++i) pt[i] += tri[3 * k + i] / double(tri.size() / 3);
      }
      double worst = std::numeric_limits<double>::infinity();
      std::size_t worst_face = faces_.size();
      candidates.clear();
      for (std::size_t f = 0; f < faces_.size(); ++f) {
        if (faces_[f].outside == kNoFace) continue;
        const double* a = &tri[9 * f];
        const double* b = a + 3;
        const double* c = a + 6;
        double nn[3];
        const double len = inward_face_normal(a, b, c, 1.0, nn);
        double d = -std::numeric_limits<double>::max();
        if (len > 0) d = (nn[0] * (pt[0] - a[0]) + nn[1] * (pt[1] - a[1]) + nn[2] * (pt[2] - a[2])) / len;
        if (fp_.orient3d(a, b, c, pt) > 0 && d <= 0) d = std::numeric_limits<double>::min();
        if (d <= 0) candidates.push_back({d, std::uint32_t(faces_[f].outside / 4)});
        if (d < worst) {
          worst = d;
          worst_face = f;
        }
      }
      if (worst_face == faces_.size()) return growth_failed(fail.no_growth_face);
      std::uint32_t grow = std::uint32_t(faces_[worst_face].outside / 4);
      if (lookahead > 1 && candidates.size() > 1) {
        // Steepest ascent: try the tets behind the most violated faces, keep the one whose region
        // has the best kernel LP slack (the most violated one alone often makes it worse).
        std::sort(candidates.begin(), candidates.end());
        double best = -std::numeric_limits<double>::infinity();
        std::size_t tried = 0;
        for (std::size_t k = 0; k < candidates.size() && tried < std::size_t(lookahead); ++k) {
          const std::uint32_t t = candidates[k].second;
          if (k > 0 && std::any_of(candidates.begin(), candidates.begin() + long(k), [&](const auto& c) { return c.second == t; })) continue;
          ++tried;
          const std::size_t mark = region_.size();
          add_with_merge(t);
          const double pr = region_progress(tri_t, tri_s);
          for (std::size_t r = mark; r < region_.size(); ++r) in_region_[region_[r]] = 0;
          region_.resize(mark);
          if (pr > best) {
            best = pr;
            grow = t;
          }
        }
      }
      add_with_merge(grow);
    }
    return growth_failed(fail.growth_steps);
  }

  // Local complex of a patch.
  struct LocalTet {
    std::array<std::uint32_t, 4> v;
    std::int32_t label;
    bool dead;
  };

  // Splits the local tets whose closure contains u's source position (1→4, 2→6 or edge n→2n) and
  // gives u a target position making every new tet exactly positive.
  bool insert_vertex(std::uint32_t u, std::vector<LocalTet>& local) {
    const double* x = S(u);
    struct Hit {
      std::size_t k;
      int sign[4];
    };
    std::vector<Hit> hits;
    for (std::size_t k = 0; k < local.size(); ++k) {
      if (local[k].dead) continue;
      const auto& tv = local[k].v;
      Hit h{k, {0, 0, 0, 0}};
      int zeros = 0;
      bool outside = false;
      for (int i = 0; i < 4 && !outside; ++i) {
        const std::uint8_t* l = kTetFace[i];
        h.sign[i] = fp_.orient3d(S(tv[l[0]]), S(tv[l[1]]), S(tv[l[2]]), x);
        if (h.sign[i] < 0) outside = true;
        zeros += h.sign[i] == 0;
      }
      if (outside) continue;
      if (zeros >= 3) return false;  // coincides with a vertex
      hits.push_back(h);
    }
    if (hits.empty()) return false;
    std::size_t best = 0;
    auto nzero = [](const Hit& h) { return (h.sign[0] == 0) + (h.sign[1] == 0) + (h.sign[2] == 0) + (h.sign[3] == 0); };
    for (std::size_t h = 1; h < hits.size(); ++h)
      if (nzero(hits[h]) < nzero(hits[best])) best = h;
    const auto& t0 = local[hits[best].k].v;
    // Barycentric image in the matching target tet (double); carrier centroid for nudging.
    double y[3] = {0, 0, 0}, c[3] = {0, 0, 0};
    int carrier = 0;
    for (int i = 0; i < 4; ++i) {
      const std::uint8_t* l = kTetFace[i];
      const double den = signed_volume(S(t0[l[0]]), S(t0[l[1]]), S(t0[l[2]]), S(t0[i]));
      const double lam = hits[best].sign[i] > 0 ? signed_volume(S(t0[l[0]]), S(t0[l[1]]), S(t0[l[2]]), x) / den : 0.0;
      for (int d = 0; d < 3; ++d) y[d] += lam * T(t0[i])[d];
      if (hits[best].sign[i] > 0) {
        ++carrier;
        for (int d = 0; d < 3; ++d) c[d] += T(t0[i])[d];
      }
    }
    for (int d = 0; d < 3; ++d) c[d] /= carrier;
    std::vector<LocalTet> fresh;
    std::vector<double> tri;
    for (const Hit& h : hits)
      for (int i = 0; i < 4; ++i)
        if (h.sign[i] > 0) {
          const auto& tv = local[h.k].v;
          const std::uint8_t* l = kTetFace[i];
          fresh.push_back({{tv[l[0]], tv[l[1]], tv[l[2]], u}, local[h.k].label, false});
          for (int k = 0; k < 3; ++k)
            for (int d = 0; d < 3; ++d) tri.push_back(T(tv[l[k]])[d]);
        }
    double cand[3];
    bool placed = false;
    for (double t : {0.0, 1e-6, 1e-4, 1e-2, 0.1, 0.5, 1.0}) {
      for (int d = 0; d < 3; ++d) cand[d] = y[d] + t * (c[d] - y[d]);
      if (verified_inside(fp_, tri, cand)) {
        placed = true;
        break;
      }
    }
    if (!placed && !strict_kernel_point_in(fp_, tri, cand)) return false;
    for (int d = 0; d < 3; ++d) tx_[3 * std::size_t(u) + d] = cand[d];
    for (const Hit& h : hits) local[h.k].dead = true;
    local.insert(local.end(), fresh.begin(), fresh.end());
    return true;
  }

  // Unit normal of the ∂M face f pointing into M (target space) and the face's size sqrt(2 area).
  bool inward_unit_normal(const Tri& f, double* n, double* size) const {
    const double len = inward_face_normal(T(f[0]), T(f[1]), T(f[2]), 1.0, n);
    if (!(len > 0)) return false;
    for (int d = 0; d < 3; ++d) n[d] /= len;
    *size = std::sqrt(len);
    return true;
  }

  // The ∂M face containing edge (a, b) other than the face with sorted vertices skip; {kNoTet,..} if none.
  Tri boundary_face_across(std::uint32_t a, std::uint32_t b, const Tri& skip, std::vector<std::uint32_t>& st) {
    star(a, st);
    for (std::uint32_t t : st)
      for (int i = 0; i < 4; ++i) {
        if (nb_[4 * std::size_t(t) + i] != kNoFace) continue;
        const Tri g = face(t, i);
        const bool has_a = g[0] == a || g[1] == a || g[2] == a, has_b = g[0] == b || g[1] == b || g[2] == b;
        if (has_a && has_b && sorted(g) != skip) return g;
      }
    return {kNoTet, kNoTet, kNoTet};
  }

  bool repair_cluster(const std::vector<std::uint32_t>& cluster) {
    double p[3], q[3];
    const auto t_grow = std::chrono::steady_clock::now();
    // Steepest-ascent growth first, then the plain most-violated-face growth, then a 2-candidate
    // lookahead: each finds regions the others miss on G1 star maps (the greedy growth is path
    // dependent); a failure is counted once, for the last try.
    const int lookahead = opt_.growth_lookahead;
    int tries[3] = {std::max(1, lookahead), 1, 2};
    const int ntries = lookahead > 2 ? 3 : lookahead == 2 ? 2 : 1;
    if (lookahead == 2) tries[1] = 1;
    bool grown = false;
    for (int k = 0; k < ntries && !grown; ++k) grown = grow_region(cluster, p, q, tries[k], k + 1 == ntries);
    // Then aimed growth from points just inside the ∂M faces of the cluster's tets. G1 ramses star
    // (a frozen stalled state): a tet with a face on the concave valley between two spikes had its
    // free 4th vertex 33 units beyond that face's plane, inside the neighbouring spike; the LP
    // growth never found a target kernel (also not with 20000-tet regions), while aiming at the
    // face centroid moved 2 units inward gives a 42-tet ball with strict kernels in both spaces.
    // The aimed target point is checked exactly, like every patch.
    // Aim points: per ∂M face of the first cluster tets, the centroid moved inward by 1, 0.5, 2, 4
    // face sizes; then, per edge of such a face, the edge midpoint pushed inside both half-spaces
    // of the face and of the ∂M face across that edge (at a concave valley edge the first points may
    // not see the other valley face; these alone repair both frozen states with 25/27-tet balls).
    std::vector<std::array<double, 3>> aims;
    if (opt_.aimed_growth) {
      std::vector<std::array<double, 3>> valley;
      std::vector<std::uint32_t> st;
      // The ∂M faces of the first cluster tets, then the ∂M faces around their boundary vertices
      // (G1 ramses star: a stuck tet with only an edge on ∂M, two free vertices 30 units beyond it).
      std::vector<Tri> bfaces, around;
      for (std::size_t k = 0; k < cluster.size() && k < 8; ++k) {
        const std::uint32_t t = cluster[k];
        for (int i = 0; i < 4; ++i) {
          if (nb_[4 * std::size_t(t) + i] == kNoFace) bfaces.push_back(face(t, i));
          const std::uint32_t w = src_.tets[4 * std::size_t(t) + i];
          if (!onb_[w]) continue;
          star(w, st);
          for (std::uint32_t s : st)
            for (int j = 0; j < 4; ++j)
              if (nb_[4 * std::size_t(s) + j] == kNoFace && src_.tets[4 * std::size_t(s) + j] != w) around.push_back(face(s, j));
        }
      }
      for (const Tri& f : around) {
        bool known = false;
        for (const Tri& g : bfaces) known = known || sorted(g) == sorted(f);
        if (!known && bfaces.size() < 64) bfaces.push_back(f);
      }
      for (const Tri& f : bfaces) {
        {
          double nf[3], scale;
          if (!inward_unit_normal(f, nf, &scale)) continue;
          for (double k_dist : {1.0, 0.5, 2.0, 4.0}) {
            std::array<double, 3> aim;
            for (int d = 0; d < 3; ++d) aim[d] = (T(f[0])[d] + T(f[1])[d] + T(f[2])[d]) / 3.0 + k_dist * scale * nf[d];
            aims.push_back(aim);
          }
          for (int e = 0; e < 3; ++e) {
            const std::uint32_t a = f[e], b = f[(e + 1) % 3];
            const Tri g = boundary_face_across(a, b, sorted(f), st);
            double ng[3], scale_g;
            if (g[0] == kNoTet || !inward_unit_normal(g, ng, &scale_g)) continue;
            double m[3], len = 0;
            for (int d = 0; d < 3; ++d) {
              m[d] = nf[d] + ng[d];
              len += m[d] * m[d];
            }
            len = std::sqrt(len);
            if (!(len > 1e-12)) continue;
            const double size = std::min(scale, scale_g);
            for (double k_dist : {0.5, 1.0, 2.0, 4.0, 8.0}) {
              std::array<double, 3> aim;
              for (int d = 0; d < 3; ++d) aim[d] = 0.5 * (T(a)[d] + T(b)[d]) + k_dist * size * m[d] / len;
              valley.push_back(aim);
            }
          }
        }
      }
      aims.insert(aims.end(), valley.begin(), valley.end());
    }
    for (std::size_t k = 0; k < aims.size() && !grown; ++k) grown = grow_region(cluster, p, q, 1, false, aims[k].data());
    const auto t_patch = std::chrono::steady_clock::now();
    res_.seconds_growth += std::chrono::duration<double>(t_patch - t_grow).count();
    if (!grown) return false;
    struct PatchClock {
      ConeRepairResult& r;
      std::chrono::steady_clock::time_point t;
      ~PatchClock() { r.seconds_patch += std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count(); }
    } patch_clock{res_, t_patch};
    auto& fail = res_.failures;
    const std::size_t nv0 = src_.num_vertices();
    // Interior vertices of R: on R's tets but not on ∂R.
    ++vstamp_;
    for (const auto& f : faces_)
      for (auto v : f.v) vmark_[v] = vstamp_;
    std::vector<std::uint32_t> interior;
    for (std::uint32_t t : region_)
      for (int i = 0; i < 4; ++i) {
        const std::uint32_t v = src_.tets[4 * std::size_t(t) + i];
        if (vmark_[v] == vstamp_) continue;
        vmark_[v] = vstamp_;
        if (onb_[v]) {  // cannot happen for a ball R (∂M vertices lie on ∂R)
          ++fail.not_ball;
          return false;
        }
        interior.push_back(v);
      }
    // Apex: an interior vertex already in the strict source kernel (no new vertex), else w = p.
    std::uint32_t apex = kNoTet;
    for (std::uint32_t v : interior) {
      bool inside = true;
      for (const auto& f : faces_)
        if (fp_.orient3d(S(f.v[0]), S(f.v[1]), S(f.v[2]), S(v)) <= 0) {
          inside = false;
          break;
        }
      if (inside) {
        apex = v;
        break;
      }
    }
    std::vector<double> saved_target;
    for (std::uint32_t v : interior)
      for (int d = 0; d < 3; ++d) saved_target.push_back(T(v)[d]);
    auto restore = [&] {
      src_.xyz.resize(3 * nv0);
      tx_.resize(3 * nv0);
      for (std::size_t k = 0; k < interior.size(); ++k)
        for (int d = 0; d < 3; ++d) tx_[3 * std::size_t(interior[k]) + d] = saved_target[3 * k + d];
      return false;
    };
    const std::uint32_t w = apex != kNoTet ? apex : std::uint32_t(nv0);
    if (apex == kNoTet) {
      src_.xyz.insert(src_.xyz.end(), p, p + 3);
      tx_.insert(tx_.end(), q, q + 3);
    } else {
      for (int d = 0; d < 3; ++d) tx_[3 * std::size_t(w) + d] = q[d];
    }
    std::vector<LocalTet> local;
    local.reserve(faces_.size() + 8 * interior.size());
    for (const auto& f : faces_)
      local.push_back({{f.v[0], f.v[1], f.v[2], w}, has_labels_ ? src_.tet_labels[f.inner_tet] : 0, false});
    for (std::uint32_t v : interior)
      if (v != w && !insert_vertex(v, local)) {
        ++fail.reinsertion;
        return restore();
      }
    // Every new tet exactly positive in both spaces (by construction; checked).
    std::vector<LocalTet> live;
    for (const auto& lt : local)
      if (!lt.dead) {
        const auto& v = lt.v;
        if (fp_.orient3d(S(v[0]), S(v[1]), S(v[2]), S(v[3])) <= 0 || fp_.orient3d(T(v[0]), T(v[1]), T(v[2]), T(v[3])) <= 0) {
          ++fail.not_positive;
          return restore();
        }
        live.push_back(lt);
      }
    const long long net = (long long)live.size() - (long long)region_.size();
    if (opt_.max_added_tets > 0 && net_added_ + net > (long long)opt_.max_added_tets) {
      ++fail.budget;
      return restore();
    }
    // Face matching: interior faces pair up, the others must be exactly the faces of ∂R.
    struct Key {
      Tri f;
      std::uint64_t id;  // 4·local + i, or the ∂R face index with the top bit set
    };
    constexpr std::uint64_t kRegionBit = std::uint64_t(1) << 63;
    std::vector<Key> keys;
    keys.reserve(4 * live.size() + faces_.size());
    for (std::size_t k = 0; k < live.size(); ++k)
      for (int i = 0; i < 4; ++i) {
        const std::uint8_t* l = kTetFace[i];
        keys.push_back({sorted({live[k].v[l[0]], live[k].v[l[1]], live[k].v[l[2]]}), 4 * k + i});
      }
    for (std::size_t f = 0; f < faces_.size(); ++f) keys.push_back({sorted(faces_[f].v), kRegionBit | f});
    std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) { return a.f != b.f ? a.f < b.f : a.id < b.id; });
    std::vector<std::pair<std::uint64_t, std::uint64_t>> links;  // (local half-face, partner local half-face or region face)
    for (std::size_t k = 0; k < keys.size();) {
      std::size_t j = k;
      while (j < keys.size() && keys[j].f == keys[k].f) ++j;
      // Sorted by id, a region face sorts last: a region face first means two region faces or none local.
      if (j - k != 2 || (keys[k].id & kRegionBit)) {
        ++fail.face_mismatch;
        return restore();
      }
      links.push_back({keys[k].id, keys[k + 1].id});
      k = j;
    }
    // Commit: reuse R's slots, append the rest.
    std::vector<std::uint32_t> slot(live.size());
    for (std::size_t k = 0; k < live.size(); ++k) {
      if (k < region_.size()) {
        slot[k] = region_[k];
      } else {
        slot[k] = std::uint32_t(alive_.size());
        alive_.push_back(1);
        in_region_.push_back(0);
        seen_.push_back(0);
        nb_.resize(nb_.size() + 4, kNoFace);
        src_.tets.resize(src_.tets.size() + 4);
        if (has_labels_) src_.tet_labels.push_back(0);
      }
      for (int i = 0; i < 4; ++i) src_.tets[4 * std::size_t(slot[k]) + i] = live[k].v[i];
      if (has_labels_) src_.tet_labels[slot[k]] = live[k].label;
      alive_[slot[k]] = 1;
    }
    for (std::size_t k = live.size(); k < region_.size(); ++k) alive_[region_[k]] = 0;
    for (const auto& [a, b] : links) {
      const std::uint64_t ha = 4 * std::uint64_t(slot[a / 4]) + a % 4;
      if (b & kRegionBit) {
        const std::uint64_t o = faces_[b & ~kRegionBit].outside;
        nb_[ha] = o;
        if (o != kNoFace) nb_[o] = ha;
      } else {
        const std::uint64_t hb = 4 * std::uint64_t(slot[b / 4]) + b % 4;
        nb_[ha] = hb;
        nb_[hb] = ha;
      }
    }
    if (apex == kNoTet) {
      onb_.push_back(0);
      v2t_.push_back(kNoTet);
      vmark_.push_back(0);
      if (!src_.vertex_labels.empty()) src_.vertex_labels.push_back(0);
    }
    for (std::size_t k = 0; k < live.size(); ++k)
      for (auto v : live[k].v) v2t_[v] = slot[k];
    net_added_ += net;
    return true;
  }

  // Drops dead slots (tet order of the live ones kept).
  void finish() {
    std::size_t out = 0;
    for (std::size_t t = 0; t < alive_.size(); ++t) {
      if (!alive_[t]) continue;
      for (int i = 0; i < 4; ++i) src_.tets[4 * out + i] = src_.tets[4 * t + i];
      if (has_labels_) src_.tet_labels[out] = src_.tet_labels[t];
      ++out;
    }
    src_.tets.resize(4 * out);
    if (has_labels_) src_.tet_labels.resize(out);
  }
};

}  // namespace

ConeRepairResult cone_repair(TetMeshData& source, std::vector<std::uint8_t>& on_boundary, std::vector<double>& target_xyz,
                             const ConeRepairOptions& options) {
  if (source.tets.size() != 4 * source.num_tets() || on_boundary.size() != source.num_vertices() ||
      target_xyz.size() != source.xyz.size())
    throw Error(ErrorKind::BadInput, "", 0, "cone_repair: inconsistent array sizes");
  for (std::uint32_t v : source.tets)
    if (v >= source.num_vertices()) throw Error(ErrorKind::BadInput, "", 0, "cone_repair: tet vertex id out of range");
  const auto t0 = std::chrono::steady_clock::now();
  ConeRepairer repairer(source, on_boundary, target_xyz, options);
  const double setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ConeRepairResult res = repairer.run();
  res.seconds_setup = setup;
  return res;
}

RelocationResult relocate_into_link_kernels(const std::vector<std::uint32_t>& tets, const std::vector<std::uint8_t>& locked,
                                            std::vector<double>& X, int max_sweeps) {
  RelocationResult res;
  const std::size_t nv = X.size() / 3, nt = tets.size() / 4;
  std::vector<std::uint32_t> off(nv + 1, 0), slot(4 * nt);
  for (std::uint32_t v : tets) ++off[v + 1];
  for (std::size_t v = 0; v < nv; ++v) off[v + 1] += off[v];
  {
    std::vector<std::uint32_t> fill(off.begin(), off.end() - 1);
    for (std::size_t s = 0; s < 4 * nt; ++s) slot[fill[tets[s]]++] = std::uint32_t(s);
  }
  std::vector<std::int8_t> sign(nt);
  auto count_bad = [&] { return count_nonpositive(X.data(), nv, tets.data(), nt, sign.data()); };
  res.nonpositive_before = count_bad();
  std::size_t bad = res.nonpositive_before;
  std::vector<double> tri;
  std::vector<std::uint8_t> mark(nv, 0);
  const FpEnvironmentScope fp;  // one MXCSR check for all kernel verifications below
  for (int sweep = 0; sweep < max_sweeps && bad > 0; ++sweep) {
    res.sweeps = sweep + 1;
    std::vector<std::uint32_t> cand;
    for (std::size_t t = 0; t < nt; ++t)
      if (sign[t] <= 0)
        for (int i = 0; i < 4; ++i) {
          const std::uint32_t v = tets[4 * t + i];
          if (!locked[v] && !mark[v]) {
            mark[v] = 1;
            cand.push_back(v);
          }
        }
    for (auto v : cand) mark[v] = 0;
    std::size_t moved = 0;
    for (std::uint32_t v : cand) {
      tri.clear();
      for (std::uint32_t k = off[v]; k < off[v + 1]; ++k) {
        const std::uint32_t s = slot[k];
        const std::uint32_t* tv = &tets[4 * std::size_t(s / 4)];
        const std::uint8_t* fl = kTetFace[s % 4];
        for (int j = 0; j < 3; ++j)
          for (int i = 0; i < 3; ++i) tri.push_back(X[3 * std::size_t(tv[fl[j]]) + i]);
      }
      double q[3];
      if (!strict_kernel_point_in(fp, tri, q)) continue;
      for (int i = 0; i < 3; ++i) X[3 * std::size_t(v) + i] = q[i];
      ++moved;
    }
    res.moved += moved;
    const std::size_t now = count_bad();
    bad = now;
    if (moved == 0) break;
  }
  res.nonpositive_after = bad;
  return res;
}

}  // namespace volmap
