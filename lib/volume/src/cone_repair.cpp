// cone_repair.cpp — B1 of docs/mapping.md §7: star-patch cone repair on TetMesh, original vertices
// kept (conventions in cone_repair.hpp). Orientation: a face (a,b,c) of ∂R is listed in the outward
// order of the R tet it bounds (kTetFace); a point q is on R's side iff orient3d(a,b,c,q) > 0.
// Rules of the region growth (§7 "Growing R"): steepest ascent on the kernel-LP slack over the tets
// behind the most violated ∂R faces, stopped after ConeRepairOptions::stall_growth_steps steps
// without progress; then plain and 2-candidate growth; then aimed growth towards fixed target points
// near the cluster's ∂M faces. A step that adds one tet along a disk of a ball skips the sphere check
// of ∂R (§7 "Shelling steps"); a round that repairs nothing is repeated with every growth limit
// widened (§7 "Widening the search"). A region whose patch would exceed max_added_tets absorbs free ∂R
// vertices (whole stars) while it stays a ball with both kernels, until the patch fits (§7 "Fitting
// the budget"). Every exact sign is fp_.orient3d (one environment scope per call).
#include <volmap/volume/cone_repair.hpp>

#include <volmap/core/error.hpp>
#include <volmap/core/shelling.hpp>
#include <volmap/core/time_budget.hpp>
#include <volmap/predicates.hpp>
#include <volmap/volume/kernel_lp.hpp>

#include "flat_array_edit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace volmap {

namespace {

constexpr std::uint32_t kNone = kInvalidIndex;
// The apex of a patch before it exists in the mesh (replace_cavity's name for its first new vertex).
constexpr std::uint32_t kPendingApex = CavityTet::kFirstNewVertex;
// Alternative positions tried for a new apex whose patch cannot be built (ConeRepairer::moved_apex).
constexpr int kApexRetries = 4;
// bulk_growth_divisor of a widened search (when the options leave it 0): its regions reach thousands
// of tets, one LP step per tet was most of its time (coarse spiky star -> cube: the patch that
// certifies it took 19.6 s one tet per step, 5.6 s with this divisor).
constexpr std::size_t kWidenedBulkGrowthDivisor = 64;

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

// A face of ∂R: outward vertex order, the half-face on the other side (invalid on ∂M), the R tet.
struct RegionFace {
  Tri v;
  HalfFaceId outside;
  std::uint32_t inner_pos;  // the R tet it bounds, as its index in the region's list
  int local;                // the face is that tet's face `local`
};

// A tet of a patch before it is committed: vertices (kPendingApex for a new apex) and the region tet
// whose label and properties it takes.
struct LocalTet {
  std::array<std::uint32_t, 4> v;
  std::uint32_t parent;
  bool dead;
};

// What became of a patch: applied, over the growth budget, or refused by a check (counted).
enum class PatchOutcome { applied, over_budget, refused };

// Kernel-LP outcome for the current ∂R: double LP found / exactly verified, per space.
struct Kernels {
  bool have_t = false, ok_t = false, have_s = false, ok_s = false;
  double slack_t = -1, slack_s = -1;
};

class ConeRepairer {
 public:
  ConeRepairer(TetMesh& mesh, PositionProperty& target, const VertexProperty<std::uint8_t>& locked, const ConeRepairOptions& options)
      : mesh_(mesh), tx_(target), locked_(locked), opt_(options), budget_(options.time_limit_seconds) {
    sync_slot_arrays();
    vertex_boxes();
  }

  ConeRepairResult run() {
    ConeRepairResult& res = res_;
    res.tets_before = mesh_.num_tets();
    const std::size_t nv0 = mesh_.num_vertices();
    const int rounds = std::max(1, opt_.max_rounds);
    for (int round = 0; round < rounds; ++round) {
      std::vector<std::vector<std::uint32_t>> clusters = find_clusters();
      if (round == 0) res.clusters = clusters.size();
      if (clusters.empty()) {
        res.failed_clusters = 0;
        break;
      }
      const std::size_t applied = repair_round(clusters);
      res.patches += applied;
      if (budget_.expired()) {
        res.failed_clusters = find_clusters().size();
        break;
      }
      if (applied == 0) {
        if (!widen_search()) break;
        --round;  // the same clusters again with the wider search (bounded: search_escalations)
        continue;
      }
      if (round + 1 == rounds) res.failed_clusters = find_clusters().size();
    }
    res.tets_after = mesh_.num_tets();
    res.vertices_added = mesh_.num_vertices() - nv0;
    return res;
  }

  // R = every live tet: its patch, when ∂M is a sphere with strict kernel points in both spaces
  // (whole_mesh_cone). Nothing is grown; the budget is unlimited.
  ConeRepairResult patch_whole_mesh() {
    res_.tets_before = mesh_.num_tets();
    const std::size_t nv0 = mesh_.num_vertices();
    clear_region();
    for (std::size_t t = 0; t < mesh_.num_tet_slots(); ++t)
      if (mesh_.tet_is_live(TetId(std::uint32_t(t)))) add_to_region(std::uint32_t(t));
    region_boundary();
    res_.attempts = 1;
    res_.failed_clusters = 1;
    if (!region_is_ball()) {
      ++res_.failures.not_ball;
    } else {
      std::vector<double> tri_t, tri_s;
      face_triangles(tri_t, tri_s);
      double p[3], q[3];
      const Kernels k = kernel_points(tri_t, tri_s, p, q);
      if (!k.ok_t) ++res_.failures.last_no_target;
      else if (!k.ok_s) ++res_.failures.last_no_source;
      else {
        const TimeBudget patch_clock;
        if (apply_patch(p, q) == PatchOutcome::applied) {
          res_.patches = 1;
          res_.failed_clusters = 0;
          res_.max_region = region_.size();
        }
        res_.seconds_patch = patch_clock.elapsed();
      }
    }
    res_.tets_after = mesh_.num_tets();
    res_.vertices_added = mesh_.num_vertices() - nv0;
    return res_;
  }

 private:
  // After a round that repaired nothing: every growth limit times search_widening (the growth is
  // deterministic, so a retry with the same limits fails the same way); false when no escalation is
  // left.
  bool widen_search() {
    if (res_.search_escalations >= std::size_t(std::max(0, opt_.search_escalations))) return false;
    ++res_.search_escalations;
    widen_growth_limits(opt_);
    return true;
  }

  const FpEnvironmentScope fp_;
  TetMesh& mesh_;
  PositionProperty& tx_;
  const VertexProperty<std::uint8_t>& locked_;
  ConeRepairOptions opt_;
  TimeBudget budget_;
  ConeRepairResult res_;
  std::vector<std::uint32_t> in_region_, vmark_;  // stamps per tet slot / vertex slot
  mutable std::vector<std::uint32_t> ball_vstamp_, ball_vindex_;  // ball_check's vertex numbering
  mutable std::uint32_t ball_stamp_ = 0;
  // ball_check's buffers, kept between calls (it runs at every growth step).
  struct BallEdge {
    std::uint32_t b;  // the larger end (the bucket is the smaller one)
    std::uint8_t fwd;
    std::uint32_t f;
  };
  struct BallCorner {
    std::uint32_t a, b;  // at the bucket's vertex v, face (v, a, b)
  };
  struct BallScratch {
    std::vector<std::uint32_t> verts, e_start, c_start, e_fill, c_fill, parent, id;
    std::vector<BallEdge> edges;
    std::vector<BallCorner> corners;
  };
  mutable BallScratch ball_;
  std::uint32_t region_stamp_ = 0, vstamp_ = 0;
  long long net_added_ = 0;
  std::vector<std::uint32_t> region_;
  // Per region_ entry: its open faces (bit i set iff face i is on ∂R; a byte array of their own,
  // scanned at every growth step), its vertices and face neighbours, kept by add_to_region and
  // truncate_region so that region_boundary reads the mesh nowhere (R's tets lie scattered in it).
  struct RegionTet {
    std::array<std::uint32_t, 4> v;
    std::array<HalfFaceId, 4> opposite;
    std::uint8_t aim_sees;  // aimed growth: bit i set once face i was found to see the aim strictly
  };
  std::vector<std::uint8_t> open_faces_;
  std::vector<RegionTet> region_tets_;
  std::vector<std::uint32_t> region_pos_;  // per tet slot: its index in region_ (while in R)
  std::vector<RegionFace> faces_;
  bool aimed_ = false;  // grow_region with a fixed target point
  // Bounding boxes of every vertex in the target and the source (lo, hi). A patch's new positions
  // lie in the hull of the old ones (the apex in a kernel of ∂R, re-inserted targets inside tets),
  // so the boxes computed once stay valid.
  double box_t_[6] = {0, 0, 0, 0, 0, 0}, box_s_[6] = {0, 0, 0, 0, 0, 0};
  // The apex of the patch being built, before it is committed.
  double pending_p_[3] = {0, 0, 0}, pending_q_[3] = {0, 0, 0};
  std::vector<TetId> star_;

  // ---- access -------------------------------------------------------------------------------
  void vertex_boxes() {
    for (int i = 0; i < 3; ++i) {
      box_t_[i] = box_s_[i] = std::numeric_limits<double>::infinity();
      box_t_[3 + i] = box_s_[3 + i] = -std::numeric_limits<double>::infinity();
    }
    for (std::size_t v = 0; v < mesh_.num_vertex_slots(); ++v) {
      if (!mesh_.vertex_is_live(VertexId(std::uint32_t(v)))) continue;
      const double* t = T(std::uint32_t(v));
      const double* x = S(std::uint32_t(v));
      for (int i = 0; i < 3; ++i) {
        box_t_[i] = std::min(box_t_[i], t[i]);
        box_t_[3 + i] = std::max(box_t_[3 + i], t[i]);
        box_s_[i] = std::min(box_s_[i], x[i]);
        box_s_[3 + i] = std::max(box_s_[3 + i], x[i]);
      }
    }
  }

  void sync_slot_arrays() {
    in_region_.resize(mesh_.num_tet_slots(), 0);
    region_pos_.resize(mesh_.num_tet_slots(), 0);
    vmark_.resize(mesh_.num_vertex_slots(), 0);
    ball_vstamp_.resize(mesh_.num_vertex_slots(), 0);
    ball_vindex_.resize(mesh_.num_vertex_slots(), 0);
  }
  Tri face(std::uint32_t t, int i) const {
    const auto f = mesh_.half_face_vertices(HalfFaceId(TetId(t), i));
    return {f[0].idx(), f[1].idx(), f[2].idx()};
  }
  std::uint32_t tet_vertex(std::uint32_t t, int i) const { return mesh_.tet_vertex(TetId(t), i).idx(); }
  bool on_mesh_boundary(std::uint32_t t, int i) const { return mesh_.half_face_is_boundary(HalfFaceId(TetId(t), i)); }
  const double* S(std::uint32_t v) const { return v == kPendingApex ? pending_p_ : mesh_.vertex_position(VertexId(v)); }
  const double* T(std::uint32_t v) const { return v == kPendingApex ? pending_q_ : tx_[VertexId(v)].data(); }
  int target_sign(std::uint32_t t) const {
    const auto v = mesh_.tet_vertices(TetId(t));
    return fp_.orient3d(T(v[0].idx()), T(v[1].idx()), T(v[2].idx()), T(v[3].idx()));
  }
  // Tets around vertex v (face-connected through faces containing v), into out.
  void star(std::uint32_t v, std::vector<std::uint32_t>& out) {
    mesh_.vertex_star(VertexId(v), star_);
    out.clear();
    for (TetId t : star_) out.push_back(t.idx());
  }

  // ---- clusters -----------------------------------------------------------------------------
  // Face-connected clusters of live tets with non-positive target.
  std::vector<std::vector<std::uint32_t>> find_clusters() const {
    const std::size_t ns = mesh_.num_tet_slots();
    std::vector<std::uint8_t> bad(ns, 0);
    for (std::size_t t = 0; t < ns; ++t)
      if (mesh_.tet_is_live(TetId(std::uint32_t(t))) && target_sign(std::uint32_t(t)) <= 0) bad[t] = 1;
    std::vector<std::vector<std::uint32_t>> out;
    for (std::size_t t0 = 0; t0 < ns; ++t0) {
      if (bad[t0] != 1) continue;
      std::vector<std::uint32_t> c{std::uint32_t(t0)};
      bad[t0] = 2;
      for (std::size_t k = 0; k < c.size(); ++k)
        for (int i = 0; i < 4; ++i) {
          const HalfFaceId o = mesh_.half_face_opposite(HalfFaceId(TetId(c[k]), i));
          if (o.is_valid() && bad[o.tet().idx()] == 1) {
            bad[o.tet().idx()] = 2;
            c.push_back(o.tet().idx());
          }
        }
      out.push_back(std::move(c));
    }
    return out;
  }

  // One round over the clusters, smallest first; returns the number of patches applied.
  std::size_t repair_round(std::vector<std::vector<std::uint32_t>>& clusters) {
    std::sort(clusters.begin(), clusters.end(), [](const auto& a, const auto& b) { return a.size() < b.size(); });
    std::size_t applied = 0, failed = 0;
    for (auto& cluster : clusters) {
      if (budget_.expired()) break;
      // Earlier patches of this round may have replaced some of these tets (their slots, if reused,
      // hold positive tets): keep the ones still non-positive.
      cluster.erase(std::remove_if(cluster.begin(), cluster.end(),
                                   [&](std::uint32_t t) { return !mesh_.tet_is_live(TetId(t)) || target_sign(t) > 0; }),
                    cluster.end());
      if (cluster.empty()) continue;
      ++res_.attempts;
      if (repair_cluster(cluster)) {
        ++applied;
        res_.max_region = std::max(res_.max_region, region_.size());
      } else {
        ++failed;
      }
    }
    res_.failed_clusters = failed;
    return applied;
  }

  // ---- the region R -------------------------------------------------------------------------
  bool in_region(HalfFaceId o) const { return o.is_valid() && in_region_[o.tet().idx()] == region_stamp_; }
  bool add_to_region(std::uint32_t t) {
    if (in_region_[t] == region_stamp_) return false;
    RegionTet r;
    std::uint8_t open = 0;
    r.aim_sees = 0;
    for (int i = 0; i < 4; ++i) {
      r.v[i] = tet_vertex(t, i);
      const HalfFaceId o = r.opposite[i] = mesh_.half_face_opposite(HalfFaceId(TetId(t), i));
      if (in_region(o))
        open_faces_[region_pos_[o.tet().idx()]] &= std::uint8_t(~(1u << o.local()));
      else
        open |= std::uint8_t(1u << i);
    }
    in_region_[t] = region_stamp_;
    region_pos_[t] = std::uint32_t(region_.size());
    region_.push_back(t);
    region_tets_.push_back(r);
    open_faces_.push_back(open);
    return true;
  }
  // R back to its first `mark` tets (the last added leave first).
  void truncate_region(std::size_t mark) {
    while (region_.size() > mark) {
      in_region_[region_.back()] = 0;
      region_.pop_back();
      for (const HalfFaceId o : region_tets_.back().opposite)
        if (in_region(o)) open_faces_[region_pos_[o.tet().idx()]] |= std::uint8_t(1u << o.local());
      region_tets_.pop_back();
      open_faces_.pop_back();
    }
  }
  void clear_region() {
    ++region_stamp_;
    region_.clear();
    region_tets_.clear();
    open_faces_.clear();
  }
  // Adds t; when t is non-positive in the target, also the stars of its vertices (clusters merge;
  // not in aimed growth, where the stars of a far-off vertex would bring in ∂M faces aim cannot see).
  std::size_t add_with_merge(std::uint32_t t) {
    if (!add_to_region(t)) return 0;
    std::size_t added = 1;
    if (!aimed_ && target_sign(t) <= 0) {
      std::vector<std::uint32_t> st;
      for (int i = 0; i < 4; ++i) {
        star(tet_vertex(t, i), st);
        for (auto s : st) added += add_to_region(s);
      }
    }
    return added;
  }

  // ∂R in faces_: the open faces of the tets of R, in the order of region_ and of the local faces.
  void region_boundary() {
    faces_.clear();
    for (std::size_t k = 0; k < region_.size(); ++k) {
      const std::uint8_t open = open_faces_[k];
      if (open == 0) continue;
      const RegionTet& r = region_tets_[k];
      for (int i = 0; i < 4; ++i) {
        if (!(open & (1u << i))) continue;
        const std::uint8_t* f = kTetFace[i];
        faces_.push_back({{r.v[f[0]], r.v[f[1]], r.v[f[2]]}, r.opposite[i], std::uint32_t(k), i});
      }
    }
  }

  // Checks that ∂R (faces_) is a closed 2-manifold sphere. Fills offending vertices/edges, the
  // component of each face and returns the Euler characteristic (V − E + F).
  long long ball_check(std::vector<std::uint32_t>& bad_vertices, std::vector<std::array<std::uint32_t, 2>>& bad_edges,
                       std::vector<std::uint32_t>& comp, std::size_t& ncomp) const {
    bad_vertices.clear();
    bad_edges.clear();
    const std::size_t nf = faces_.size();
    // ∂R's vertices, numbered in the order met (stamps per vertex slot: no sort, no map).
    if (++ball_stamp_ == 0) {
      std::fill(ball_vstamp_.begin(), ball_vstamp_.end(), 0u);
      ball_stamp_ = 1;
    }
    BallScratch& b = ball_;
    std::vector<std::uint32_t>& verts = b.verts;
    verts.clear();
    for (const auto& f : faces_)
      for (std::uint32_t v : f.v)
        if (ball_vstamp_[v] != ball_stamp_) {
          ball_vstamp_[v] = ball_stamp_;
          ball_vindex_[v] = std::uint32_t(verts.size());
          verts.push_back(v);
        }
    const std::size_t nv = verts.size();
    // Buckets by vertex (counting sort): the directed edges by their smaller end, the corners by
    // their vertex; each bucket is small (a vertex's degree on ∂R) and sorted on its own.
    using E = BallEdge;
    using C = BallCorner;
    std::vector<std::uint32_t>& e_start = b.e_start;
    std::vector<std::uint32_t>& c_start = b.c_start;
    e_start.assign(nv + 1, 0);
    c_start.assign(nv + 1, 0);
    for (const auto& f : faces_)
      for (int k = 0; k < 3; ++k) {
        ++e_start[ball_vindex_[std::min(f.v[k], f.v[(k + 1) % 3])] + 1];
        ++c_start[ball_vindex_[f.v[k]] + 1];
      }
    for (std::size_t i = 0; i < nv; ++i) {
      e_start[i + 1] += e_start[i];
      c_start[i + 1] += c_start[i];
    }
    std::vector<E>& edges = b.edges;
    std::vector<C>& corners = b.corners;
    edges.resize(3 * nf);
    corners.resize(3 * nf);
    b.e_fill.assign(e_start.begin(), e_start.end() - 1);
    b.c_fill.assign(c_start.begin(), c_start.end() - 1);
    for (std::size_t f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t u = faces_[f].v[k], w = faces_[f].v[(k + 1) % 3], x = faces_[f].v[(k + 2) % 3];
        edges[b.e_fill[ball_vindex_[std::min(u, w)]]++] = {std::max(u, w), std::uint8_t(u < w), std::uint32_t(f)};
        corners[b.c_fill[ball_vindex_[u]]++] = {w, x};
      }
    std::vector<std::uint32_t>& parent = b.parent;
    parent.resize(nf);
    for (std::size_t f = 0; f < nf; ++f) parent[f] = std::uint32_t(f);
    auto find = [&](std::uint32_t x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    // Edges: a manifold edge has one directed copy each way.
    long long num_edges = 0;
    for (std::size_t i = 0; i < nv; ++i) {
      const auto first = edges.begin() + long(e_start[i]), last = edges.begin() + long(e_start[i + 1]);
      std::sort(first, last, [](const E& x, const E& y) { return x.b < y.b; });
      for (auto k = first; k != last;) {
        auto j = k;
        int fwd = 0, bwd = 0;
        while (j != last && j->b == k->b) {
          (j->fwd ? fwd : bwd)++;
          parent[find(j->f)] = find(k->f);
          ++j;
        }
        ++num_edges;
        if (fwd != 1 || bwd != 1) bad_edges.push_back({verts[i], k->b});
        k = j;
      }
    }
    // Vertex fans: at corner v of (v, a, b) the fan steps a → b; one cycle per manifold vertex.
    for (std::size_t i = 0; i < nv; ++i) {
      const auto first = corners.begin() + long(c_start[i]), last = corners.begin() + long(c_start[i + 1]);
      std::sort(first, last, [](const C& x, const C& y) { return x.a < y.a; });
      const std::size_t deg = std::size_t(last - first);
      std::uint32_t cur = first->a;
      std::size_t steps = 0;
      bool ok = true;
      do {
        auto it = std::lower_bound(first, last, cur, [](const C& c, std::uint32_t a) { return c.a < a; });
        if (it == last || it->a != cur || (it + 1 != last && (it + 1)->a == cur)) {
          ok = false;
          break;
        }
        cur = it->b;
        ++steps;
      } while (cur != first->a && steps <= deg);
      if (!ok || steps != deg) bad_vertices.push_back(verts[i]);
    }
    // By vertex id and by (smaller, larger) end: the order grow_towards_ball adds their stars in.
    std::sort(bad_vertices.begin(), bad_vertices.end());
    std::sort(bad_edges.begin(), bad_edges.end());
    comp.assign(nf, 0);
    ncomp = 0;
    std::vector<std::uint32_t>& id = b.id;
    id.assign(nf, kNone);
    for (std::size_t f = 0; f < nf; ++f) {
      const std::uint32_t r = find(std::uint32_t(f));
      if (id[r] == kNone) id[r] = std::uint32_t(ncomp++);
      comp[f] = id[r];
    }
    return (long long)nv - num_edges + (long long)nf;
  }

  // Grows R towards a ball: stars around non-manifold vertices and edges of ∂R, then the faces of
  // every ∂R component but the largest (cavities) and the outside tets with two or more faces on ∂R
  // (handles). Returns the number of tets added; 0 with `*is_ball` set when ∂R is a sphere.
  std::size_t grow_towards_ball(bool* is_ball) {
    std::vector<std::uint32_t> bad_vertices, comp, st;
    std::vector<std::array<std::uint32_t, 2>> bad_edges;
    std::size_t ncomp = 0;
    const long long chi = ball_check(bad_vertices, bad_edges, comp, ncomp);
    *is_ball = false;
    std::size_t added = 0;
    if (!bad_vertices.empty() || !bad_edges.empty()) {
      for (auto v : bad_vertices) {
        star(v, st);
        for (auto t : st) added += add_with_merge(t);
      }
      for (const auto& e : bad_edges) {
        star(e[0], st);
        for (auto t : st)
          if (mesh_.tet_local_index(TetId(t), VertexId(e[1])) >= 0) added += add_with_merge(t);
      }
      return added;
    }
    if (ncomp == 1 && chi == 2) {
      *is_ball = true;
      return 0;
    }
    std::vector<std::size_t> size(ncomp, 0);
    for (auto c : comp) ++size[c];
    const std::size_t largest = std::size_t(std::max_element(size.begin(), size.end()) - size.begin());
    std::vector<std::uint32_t> behind;
    for (std::size_t f = 0; f < faces_.size(); ++f)
      if (faces_[f].outside.is_valid()) {
        if (ncomp > 1 && comp[f] != largest) added += add_with_merge(faces_[f].outside.tet().idx());
        behind.push_back(faces_[f].outside.tet().idx());
      }
    if (ncomp == 1) {
      std::sort(behind.begin(), behind.end());
      for (std::size_t k = 0; k + 1 < behind.size(); ++k)
        if (behind[k] == behind[k + 1]) added += add_with_merge(behind[k]);
    }
    return added;
  }

  // The faces of ∂R (with mesh_boundary_only: those on ∂M) as LP triangles (9 doubles each) in
  // target and source coordinates.
  void face_triangles(std::vector<double>& tri_t, std::vector<double>& tri_s, bool mesh_boundary_only = false) const {
    tri_t.clear();
    tri_s.clear();
    for (const auto& f : faces_)
      if (!mesh_boundary_only || !f.outside.is_valid())
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

  // Strict kernel points of ∂R: q in the target, then (only when q is verified) p in the source.
  Kernels kernel_points(const std::vector<double>& tri_t, const std::vector<double>& tri_s, double* p, double* q) {
    Kernels k;
    res_.lp_solves += 1;
    k.have_t = chebyshev_point(tri_t, q, &k.slack_t);
    k.ok_t = k.have_t && k.slack_t > 0 && verified_inside(fp_, tri_t, q);
    if (k.ok_t) {
      ++res_.lp_solves;
      k.have_s = chebyshev_point(tri_s, p, &k.slack_s);
      k.ok_s = k.have_s && k.slack_s > 0 && verified_inside(fp_, tri_s, p);
    }
    return k;
  }

  // The tet to add next: behind the most violated ∂R face of the failing space (faces on ∂M cannot
  // move), or with lookahead > 1 the candidate among the tets behind the most violated faces whose
  // region has the best kernel-LP slack. kNone when every violated face is on ∂M.
  // violated (when not null) receives every (violation, tet behind) of the failing space's violated
  // faces with a tet behind, unsorted.
  std::uint32_t choose_growth_tet(const Kernels& k, const double* p, const double* q, int lookahead, std::vector<double>& tri_t,
                                  std::vector<double>& tri_s, std::vector<std::pair<double, std::uint32_t>>* violated = nullptr) {
    const bool target_fails = !k.ok_t;
    const std::vector<double>& tri = target_fails ? tri_t : tri_s;
    double pt[3];
    if (target_fails ? k.have_t : k.have_s) {
      for (int i = 0; i < 3; ++i) pt[i] = target_fails ? q[i] : p[i];
    } else {
      pt[0] = pt[1] = pt[2] = 0;
      for (std::size_t j = 0; j < tri.size() / 3; ++j)
        for (int i = 0; i < 3; ++i) pt[i] += tri[3 * j + i] / double(tri.size() / 3);
    }
    std::vector<std::pair<double, std::uint32_t>> candidates;  // (violation, tet behind)
    double worst = std::numeric_limits<double>::infinity();
    std::size_t worst_face = faces_.size();
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      if (!faces_[f].outside.is_valid()) continue;
      const double* a = &tri[9 * f];
      const double* b = a + 3;
      const double* c = a + 6;
      double nn[3];
      const double len = inward_face_normal(a, b, c, 1.0, nn);
      double d = -std::numeric_limits<double>::max();
      if (len > 0) d = (nn[0] * (pt[0] - a[0]) + nn[1] * (pt[1] - a[1]) + nn[2] * (pt[2] - a[2])) / len;
      if (d <= 0 && fp_.orient3d(a, b, c, pt) > 0) d = std::numeric_limits<double>::min();  // exact sign wins
      if (d <= 0) candidates.push_back({d, faces_[f].outside.tet().idx()});
      if (d < worst) {
        worst = d;
        worst_face = f;
      }
    }
    if (worst_face == faces_.size()) return kNone;
    if (violated) *violated = candidates;
    std::uint32_t grow = faces_[worst_face].outside.tet().idx();
    if (lookahead <= 1 || candidates.size() <= 1) return grow;
    // Steepest ascent: the most violated face alone often makes the slack worse.
    std::sort(candidates.begin(), candidates.end());
    double best = -std::numeric_limits<double>::infinity();
    std::size_t tried = 0;
    for (std::size_t j = 0; j < candidates.size() && tried < std::size_t(lookahead); ++j) {
      const std::uint32_t t = candidates[j].second;
      if (j > 0 && std::any_of(candidates.begin(), candidates.begin() + long(j), [&](const auto& c) { return c.second == t; })) continue;
      ++tried;
      const std::size_t mark = region_.size();
      add_with_merge(t);
      const double pr = region_progress(tri_t, tri_s);
      truncate_region(mark);
      if (pr > best) {
        best = pr;
        grow = t;
      }
    }
    return grow;
  }

  // Aimed growth step: adds the tets behind every ∂R face that aim does not see strictly. Returns
  // false when such a face is on ∂M (aim cannot be reached); *added counts the tets added.
  // A face keeps its answer while it bounds R (aim, R's tets and their target positions are fixed
  // during one growth), so each face is tested once.
  bool grow_towards_aim(const double* aim, std::size_t* added) {
    *added = 0;
    for (const auto& f : faces_) {
      std::uint8_t& sees = region_tets_[f.inner_pos].aim_sees;
      const auto bit = std::uint8_t(1u << f.local);
      if (sees & bit) continue;
      if (fp_.orient3d(T(f.v[0]), T(f.v[1]), T(f.v[2]), aim) > 0) {
        sees |= bit;
        continue;
      }
      if (!f.outside.is_valid()) return false;
      *added += add_to_region(f.outside.tet().idx());
    }
    return true;
  }

  // Why a growth run stopped; counted only for the run that decides the cluster's failure.
  struct GrowthRun {
    bool count_failure;
    int last_fail = 0;  // 1 target kernel empty, 2 source kernel empty
    std::size_t mesh_faces_checked = 0;  // ∂M faces of ∂R at the last mesh_boundary_blocks check
  };

  // A face of ∂R on ∂M stays on ∂R however R grows (it has no tet behind it). When those faces
  // alone have no common strict kernel point in the target or the source (the double LP's slack
  // clearly negative, over the box of all vertices, which holds the kernel of any region), no region
  // grown from R has one either: the growth stops. Checked each time their number has grown by a
  // quarter (at least one) since the last check, so a growth run solves O(log) of these LPs.
  bool mesh_boundary_blocks(GrowthRun& run) {
    static constexpr double kClearlyNegative = -1e-9;
    if (!opt_.stop_at_mesh_boundary) return false;
    std::size_t on_mesh = 0;
    for (const auto& f : faces_) on_mesh += !f.outside.is_valid();
    if (on_mesh == 0 || on_mesh < run.mesh_faces_checked + std::max<std::size_t>(1, run.mesh_faces_checked / 4)) return false;
    run.mesh_faces_checked = on_mesh;
    std::vector<double> tri_t, tri_s;
    face_triangles(tri_t, tri_s, true);
    double x[3], slack = 0;
    res_.lp_solves += 2;
    if (chebyshev_point_in_box(tri_t, box_t_, box_t_ + 3, x, &slack) && slack < kClearlyNegative) return true;
    return chebyshev_point_in_box(tri_s, box_s_, box_s_ + 3, x, &slack) && slack < kClearlyNegative;
  }
  bool growth_failed(const GrowthRun& run, std::size_t& counter) {
    if (!run.count_failure) return false;
    ++counter;
    if (run.last_fail == 1) ++res_.failures.last_no_target;
    if (run.last_fail == 2) ++res_.failures.last_no_source;
    return false;
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
    clear_region();
    aimed_ = aim != nullptr;
    for (std::uint32_t t : cluster) add_with_merge(t);
    std::vector<double> tri_t, tri_s;
    std::vector<std::pair<double, std::uint32_t>> violated;
    auto& fail = res_.failures;
    GrowthRun run{count_failure};
    double best_progress = -std::numeric_limits<double>::infinity();
    int best_step = 0;
    bool shelled = false;  // the last step added one tet along a disk of a ball: still a ball
    for (int step = 0; step < opt_.max_growth_steps; ++step) {
      if (budget_.expired()) return growth_failed(run, fail.time_limit);
      ++res_.growth_steps;
      if (opt_.max_region_tets > 0 && region_.size() > opt_.max_region_tets) return growth_failed(run, fail.region_limit);
      region_boundary();
      if (mesh_boundary_blocks(run)) return growth_failed(run, fail.mesh_boundary);
      if (aim) {  // exact visibility from aim first (before the ball repairs, which add whole stars)
        std::size_t added = 0;
        if (!grow_towards_aim(aim, &added)) return growth_failed(run, fail.no_growth_face);
        if (added > 0) continue;
      }
      bool is_ball = shelled && !aim;
      shelled = false;
      if (is_ball) {
        ++res_.shelling_steps;
        assert_still_ball();
      } else {
        if (grow_towards_ball(&is_ball) > 0) continue;
        if (!is_ball) return growth_failed(run, fail.not_ball);
      }
      face_triangles(tri_t, tri_s);
      if (aim) {  // ∂R a sphere seen from aim: the source kernel decides
        run.last_fail = 2;
        for (int i = 0; i < 3; ++i) q[i] = aim[i];
        double slack_s = -1;
        ++res_.lp_solves;
        if (chebyshev_point(tri_s, p, &slack_s) && slack_s > 0 && verified_inside(fp_, tri_s, p)) return true;
        return growth_failed(run, fail.stalled);
      }
      const Kernels k = kernel_points(tri_t, tri_s, p, q);
      if (k.ok_s) return true;
      // Progress: the LP slack of the failing space (source phase ranked above the target phase).
      const double progress = k.ok_t ? 2.0 + (k.have_s ? k.slack_s : -1.0) : (k.have_t ? k.slack_t : -1.0);
      if (progress > best_progress) {
        best_progress = progress;
        best_step = step;
      } else if (opt_.stall_growth_steps > 0 && step - best_step >= opt_.stall_growth_steps) {
        run.last_fail = k.ok_t ? 2 : 1;
        return growth_failed(run, fail.stalled);
      }
      run.last_fail = k.ok_t ? 2 : 1;
      const std::uint32_t grow = choose_growth_tet(k, p, q, lookahead, tri_t, tri_s, &violated);
      if (grow == kNone) return growth_failed(run, fail.no_growth_face);
      const bool along_disk = attaches_along_disk(
          mesh_, TetId(grow), [&](TetId u) { return in_region_[u.idx()] == region_stamp_; }, star_);
      shelled = add_with_merge(grow) == 1 && along_disk;
      if (add_most_violated(violated, opt_.bulk_growth_divisor > 0 ? region_.size() / opt_.bulk_growth_divisor : 0) > 0)
        shelled = false;
    }
    return growth_failed(run, fail.growth_steps);
  }

  // Bulk growth: the tets behind the `count` most violated faces (violation, tet) join R. Returns the
  // number of tets added.
  std::size_t add_most_violated(std::vector<std::pair<double, std::uint32_t>>& violated, std::size_t count) {
    if (count == 0 || violated.empty()) return 0;
    count = std::min(count, violated.size());
    std::partial_sort(violated.begin(), violated.begin() + long(count), violated.end());
    std::size_t added = 0;
    for (std::size_t j = 0; j < count; ++j) added += add_with_merge(violated[j].second);
    return added;
  }

  // ---- aim points ---------------------------------------------------------------------------
  // Unit normal of the ∂M face f pointing into M (target space) and the face's size sqrt(2 area).
  bool inward_unit_normal(const Tri& f, double* n, double* size) const {
    const double len = inward_face_normal(T(f[0]), T(f[1]), T(f[2]), 1.0, n);
    if (!(len > 0)) return false;
    for (int d = 0; d < 3; ++d) n[d] /= len;
    *size = std::sqrt(len);
    return true;
  }

  // The ∂M face containing edge (a, b) other than the face with sorted vertices skip; {kNone,..} if none.
  Tri boundary_face_across(std::uint32_t a, std::uint32_t b, const Tri& skip, std::vector<std::uint32_t>& st) {
    star(a, st);
    for (std::uint32_t t : st)
      for (int i = 0; i < 4; ++i) {
        if (!on_mesh_boundary(t, i)) continue;
        const Tri g = face(t, i);
        const bool has_a = g[0] == a || g[1] == a || g[2] == a, has_b = g[0] == b || g[1] == b || g[2] == b;
        if (has_a && has_b && sorted(g) != skip) return g;
      }
    return {kNone, kNone, kNone};
  }

  // The ∂M faces of the first cluster tets, then (up to 64 in all) the ∂M faces around their
  // locked vertices: a stuck tet may touch ∂M only along an edge.
  std::vector<Tri> cluster_mesh_boundary_faces(const std::vector<std::uint32_t>& cluster) {
    std::vector<std::uint32_t> st;
    std::vector<Tri> bfaces, around;
    for (std::size_t k = 0; k < cluster.size() && k < 8; ++k) {
      const std::uint32_t t = cluster[k];
      for (int i = 0; i < 4; ++i) {
        if (on_mesh_boundary(t, i)) bfaces.push_back(face(t, i));
        const std::uint32_t w = tet_vertex(t, i);
        if (!locked_[VertexId(w)]) continue;
        star(w, st);
        for (std::uint32_t s : st)
          for (int j = 0; j < 4; ++j)
            if (on_mesh_boundary(s, j) && tet_vertex(s, j) != w) around.push_back(face(s, j));
      }
    }
    for (const Tri& f : around) {
      bool known = false;
      for (const Tri& g : bfaces) known = known || sorted(g) == sorted(f);
      if (!known && bfaces.size() < 64) bfaces.push_back(f);
    }
    return bfaces;
  }

  // Aim points of a cluster: per ∂M face, its centroid moved inward by 1, 0.5, 2, 4 face sizes;
  // then, per edge of such a face, the edge midpoint pushed inside both half-spaces of the face and
  // of the ∂M face across the edge by 0.5 .. 8 sizes (at a concave valley edge the first points may
  // not see the other valley face).
  std::vector<std::array<double, 3>> aim_points(const std::vector<std::uint32_t>& cluster) {
    std::vector<std::array<double, 3>> aims, valley;
    std::vector<std::uint32_t> st;
    for (const Tri& f : cluster_mesh_boundary_faces(cluster)) {
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
        if (g[0] == kNone || !inward_unit_normal(g, ng, &scale_g)) continue;
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
    aims.insert(aims.end(), valley.begin(), valley.end());
    return aims;
  }

  // Growth strategies in turn until one gives a region with kernel points p, q: steepest ascent,
  // plain most-violated-face growth, a 2-candidate lookahead (a failure is counted once, for the
  // last of them), then aimed growth.
  bool grow_with_strategies(const std::vector<std::uint32_t>& cluster, double* p, double* q) {
    const int lookahead = opt_.growth_lookahead;
    int tries[3] = {std::max(1, lookahead), 1, 2};
    const int ntries = lookahead > 2 ? 3 : lookahead == 2 ? 2 : 1;
    if (lookahead == 2) tries[1] = 1;
    bool grown = false;
    for (int k = 0; k < ntries && !grown; ++k) grown = grow_region(cluster, p, q, tries[k], k + 1 == ntries);
    if (grown || !opt_.aimed_growth) return grown;
    const std::vector<std::array<double, 3>> aims = aim_points(cluster);
    for (std::size_t k = 0; k < aims.size() && !grown; ++k) grown = grow_region(cluster, p, q, 1, false, aims[k].data());
    return grown;
  }

  // ---- fitting the budget -------------------------------------------------------------------
  // Net tet growth still allowed (max_added_tets minus the growth of the patches applied so far).
  long long budget_left() const {
    if (opt_.max_added_tets == 0) return std::numeric_limits<long long>::max();
    return (long long)opt_.max_added_tets - net_added_;
  }

  // What R's interior means for its patch: a lower bound on the patch's net tet growth (the cones
  // over ∂R, plus 3 per re-inserted interior vertex, the 1→4 split; one interior vertex may be the
  // apex), and whether a locked vertex would be inside (no patch then).
  struct RegionInterior {
    long long growth_bound = 0;
    bool locked_inside = false;
  };
  RegionInterior region_interior() {
    RegionInterior r;
    const std::vector<std::uint32_t> interior = region_interior_vertices();
    for (std::uint32_t v : interior) r.locked_inside = r.locked_inside || locked_[VertexId(v)];
    const long long reinserted = std::max(0LL, (long long)interior.size() - 1);
    r.growth_bound = (long long)faces_.size() + 3 * reinserted - (long long)region_.size();
    return r;
  }

  // With ConeRepairOptions::verify_shelling, each shelling step is confirmed by the full check.
  void assert_still_ball() const {
    if (opt_.verify_shelling && !region_is_ball())
      throw Error(ErrorKind::Failed, "cone repair: a shelling step left a region that is not a ball");
  }

  // ∂R (faces_) is a closed 2-manifold sphere (a pure check; grow_towards_ball repairs).
  bool region_is_ball() const {
    std::vector<std::uint32_t> bad_vertices, comp;
    std::vector<std::array<std::uint32_t, 2>> bad_edges;
    std::size_t ncomp = 0;
    const long long chi = ball_check(bad_vertices, bad_edges, comp, ncomp);
    return bad_vertices.empty() && bad_edges.empty() && ncomp == 1 && chi == 2;
  }

  // Strict kernel points of the current ∂R in both spaces: p and q stay when they still see every
  // face exactly, otherwise the LPs decide; p and q are left as they were when a kernel is empty.
  bool keep_kernel_points(double* p, double* q) {
    std::vector<double> tri_t, tri_s;
    face_triangles(tri_t, tri_s);
    if (verified_inside(fp_, tri_t, q) && verified_inside(fp_, tri_s, p)) return true;
    double p2[3], q2[3];
    if (!kernel_points(tri_t, tri_s, p2, q2).ok_s) return false;
    std::copy(p2, p2 + 3, p);
    std::copy(q2, q2 + 3, q);
    return true;
  }

  // The free (unlocked) vertices of ∂R, the ones on most ∂R faces first (then by id). Absorbing a
  // vertex on m faces of ∂R whose outside star meets ∂R only along its link cycle replaces those m
  // faces by the k outside link triangles while R gains k tets and one interior vertex: the bound
  // changes by 3 − m.
  std::vector<std::uint32_t> absorption_candidates() const {
    std::vector<std::uint32_t> corners;
    for (const auto& f : faces_)
      for (std::uint32_t v : f.v)
        if (!locked_[VertexId(v)]) corners.push_back(v);
    std::sort(corners.begin(), corners.end());
    std::vector<std::pair<long, std::uint32_t>> by_faces;  // (−faces, v)
    for (std::size_t k = 0; k < corners.size();) {
      std::size_t j = k;
      while (j < corners.size() && corners[j] == corners[k]) ++j;
      by_faces.push_back({-long(j - k), corners[k]});
      k = j;
    }
    std::sort(by_faces.begin(), by_faces.end());
    std::vector<std::uint32_t> out;
    for (const auto& c : by_faces) out.push_back(c.second);
    return out;
  }

  // Adds the whole star of one free ∂R vertex to R when R stays a ball within max_region_tets, with
  // strict kernel points in both spaces (p, q updated) and no locked vertex inside, and the patch
  // growth bound drops below `bound`. Each candidate tried costs one of `tries`; false (R as it was)
  // when no candidate qualifies, the tries or the time are used up.
  bool absorb_boundary_vertex(long long bound, double* p, double* q, int& tries) {
    std::vector<std::uint32_t> st;
    for (std::uint32_t v : absorption_candidates()) {
      if (tries <= 0 || budget_.expired()) break;
      --tries;
      const std::size_t mark = region_.size();
      star(v, st);
      for (std::uint32_t t : st) add_to_region(t);
      if (opt_.max_region_tets == 0 || region_.size() <= opt_.max_region_tets) {
        region_boundary();
        if (region_is_ball()) {
          const RegionInterior inside = region_interior();
          if (!inside.locked_inside && inside.growth_bound < bound && keep_kernel_points(p, q)) {
            ++res_.absorbed_vertices;
            return true;
          }
        }
      }
      truncate_region(mark);
      region_boundary();
    }
    return false;
  }

  // ---- the patch ----------------------------------------------------------------------------
  // x lies outside the axis-aligned bounding box of a, b, c, d (exact: comparisons only).
  static bool outside_box(const double* x, const double* a, const double* b, const double* c, const double* d) {
    for (int k = 0; k < 3; ++k)
      if (x[k] < std::min(std::min(a[k], b[k]), std::min(c[k], d[k])) || x[k] > std::max(std::max(a[k], b[k]), std::max(c[k], d[k])))
        return true;
    return false;
  }
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
      // Every local tet is strictly positive (a cone over ∂R from a strict kernel point, or a split
      // of one at a point strictly inside a face's side), so x outside its bounding box is outside
      // it: some exact sign would be negative.
      if (outside_box(x, S(tv[0]), S(tv[1]), S(tv[2]), S(tv[3]))) continue;
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
          fresh.push_back({{tv[l[0]], tv[l[1]], tv[l[2]], u}, local[h.k].parent, false});
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
    if (!placed && !strict_kernel_point(fp_, tri, cand)) return false;
    for (int d = 0; d < 3; ++d) tx_[VertexId(u)][d] = cand[d];
    for (const Hit& h : hits) local[h.k].dead = true;
    local.insert(local.end(), fresh.begin(), fresh.end());
    return true;
  }

  // The vertices of R's tets not on ∂R (never locked for a ball R: ∂M vertices lie on ∂R).
  std::vector<std::uint32_t> region_interior_vertices() {
    ++vstamp_;
    for (const auto& f : faces_)
      for (auto v : f.v) vmark_[v] = vstamp_;
    std::vector<std::uint32_t> interior;
    for (std::uint32_t t : region_)
      for (int i = 0; i < 4; ++i) {
        const std::uint32_t v = tet_vertex(t, i);
        if (vmark_[v] == vstamp_) continue;
        vmark_[v] = vstamp_;
        interior.push_back(v);
      }
    return interior;
  }

  // An interior vertex already strictly inside the source kernel of ∂R, or kNone.
  std::uint32_t existing_apex(const std::vector<std::uint32_t>& interior) const {
    for (std::uint32_t v : interior) {
      bool inside = true;
      for (const auto& f : faces_)
        if (fp_.orient3d(S(f.v[0]), S(f.v[1]), S(f.v[2]), S(v)) <= 0) {
          inside = false;
          break;
        }
      if (inside) return v;
    }
    return kNone;
  }

  // The cones (F, w) over ∂R with R's other interior vertices re-inserted into `live`.
  enum class PatchBuild { ok, reinsertion, not_positive, time_limit };
  PatchBuild build_patch(std::uint32_t w, const std::vector<std::uint32_t>& interior, std::vector<LocalTet>& live) {
    std::vector<LocalTet> local;
    local.reserve(faces_.size() + 8 * interior.size());
    for (const auto& f : faces_) local.push_back({{f.v[0], f.v[1], f.v[2], w}, region_[f.inner_pos], false});
    for (std::uint32_t v : interior) {
      if (budget_.expired()) return PatchBuild::time_limit;
      if (v != w && !insert_vertex(v, local)) return PatchBuild::reinsertion;
    }
    live.clear();
    for (const auto& lt : local) {
      if (lt.dead) continue;
      const auto& v = lt.v;
      if (fp_.orient3d(S(v[0]), S(v[1]), S(v[2]), S(v[3])) <= 0 || fp_.orient3d(T(v[0]), T(v[1]), T(v[2]), T(v[3])) <= 0)
        return PatchBuild::not_positive;
      live.push_back(lt);
    }
    return PatchBuild::ok;
  }

  // The k-th alternative source position of a new apex: p moved by a fraction of ∂R's source extent
  // along a fixed generic direction, kept only when it still sees every ∂R face strictly (exact).
  // An LP kernel point of a region cut from a regular grid tends to lie on a grid plane through
  // interior vertices of R: their re-insertion then meets cone tets that are flat to rounding.
  bool moved_apex(const double* p, int k, double* out) const {
    static constexpr double kDirections[kApexRetries][3] = {
        {0.5377, -0.2311, 0.8103}, {-0.6923, 0.4512, 0.5633}, {0.3190, 0.8837, -0.3425}, {-0.4469, -0.7146, -0.5383}};
    double lo[3] = {S(faces_[0].v[0])[0], S(faces_[0].v[0])[1], S(faces_[0].v[0])[2]}, hi[3] = {lo[0], lo[1], lo[2]};
    for (const auto& f : faces_)
      for (std::uint32_t v : f.v)
        for (int d = 0; d < 3; ++d) {
          lo[d] = std::min(lo[d], S(v)[d]);
          hi[d] = std::max(hi[d], S(v)[d]);
        }
    const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    std::vector<double> tri_t, tri_s;
    face_triangles(tri_t, tri_s);
    for (double step : {1e-2, 1e-3, 1e-4}) {
      double moved[3];
      for (int d = 0; d < 3; ++d) moved[d] = p[d] + step * extent * kDirections[k][d];
      if (verified_inside(fp_, tri_s, moved)) {
        std::copy(moved, moved + 3, out);
        return true;
      }
    }
    return false;
  }

  // Replaces R (region_, its ∂R in faces_) by the cone patch from a strict kernel point (source p,
  // target q). Leaves everything as it was when the patch fails a check (counted) or would exceed
  // the budget (not counted: the caller may still absorb vertices, see repair_cluster).
  PatchOutcome apply_patch(const double* p, const double* q) {
    const std::vector<std::uint32_t> interior = region_interior_vertices();
    for (std::uint32_t v : interior)
      if (locked_[VertexId(v)]) {  // cannot happen for a ball R
        ++res_.failures.not_ball;
        return PatchOutcome::refused;
      }
    const std::uint32_t apex = existing_apex(interior);
    const std::uint32_t w = apex != kNone ? apex : kPendingApex;
    std::vector<double> saved_target;
    for (std::uint32_t v : interior)
      for (int d = 0; d < 3; ++d) saved_target.push_back(T(v)[d]);
    auto restore = [&](PatchOutcome outcome) {
      for (std::size_t k = 0; k < interior.size(); ++k)
        for (int d = 0; d < 3; ++d) tx_[VertexId(interior[k])][d] = saved_target[3 * k + d];
      return outcome;
    };
    for (int d = 0; d < 3; ++d) {
      pending_p_[d] = p[d];
      pending_q_[d] = q[d];
    }
    if (apex != kNone)
      for (int d = 0; d < 3; ++d) tx_[VertexId(w)][d] = q[d];
    std::vector<LocalTet> live;
    PatchBuild built = build_patch(w, interior, live);
    // A new apex in a degenerate spot (see moved_apex) is moved and the patch built again.
    for (int k = 0; built != PatchBuild::ok && built != PatchBuild::time_limit && apex == kNone && k < kApexRetries; ++k) {
      if (!moved_apex(p, k, pending_p_)) continue;
      restore(PatchOutcome::refused);
      built = build_patch(w, interior, live);
    }
    if (built != PatchBuild::ok) {
      ++(built == PatchBuild::reinsertion  ? res_.failures.reinsertion
         : built == PatchBuild::time_limit ? res_.failures.time_limit
                                           : res_.failures.not_positive);
      return restore(PatchOutcome::refused);
    }
    const long long net = (long long)live.size() - (long long)region_.size();
    if (net > budget_left()) return restore(PatchOutcome::over_budget);
    std::vector<TetId> cavity;
    cavity.reserve(region_.size());
    for (std::uint32_t t : region_) cavity.push_back(TetId(t));
    std::vector<CavityTet> fill;
    fill.reserve(live.size());
    for (const LocalTet& lt : live)
      fill.push_back({{VertexId(lt.v[0]), VertexId(lt.v[1]), VertexId(lt.v[2]), VertexId(lt.v[3])}, TetId(lt.parent)});
    const std::vector<double> new_positions = apex == kNone ? std::vector<double>(pending_p_, pending_p_ + 3) : std::vector<double>();
    CavityReplacement made;
    try {
      made = mesh_.replace_cavity(cavity, fill, new_positions);
    } catch (const Error&) {
      ++res_.failures.face_mismatch;
      return restore(PatchOutcome::refused);
    }
    if (apex == kNone)
      for (int d = 0; d < 3; ++d) tx_[made.vertices[0]][d] = q[d];
    sync_slot_arrays();
    net_added_ += net;
    return PatchOutcome::applied;
  }

  // Grows R for the cluster, then applies its patch; while the patch would exceed the budget, R
  // absorbs free ∂R vertices (a larger ball's cones replace more tets than they add).
  bool repair_cluster(const std::vector<std::uint32_t>& cluster) {
    double p[3], q[3];
    const TimeBudget growth_clock;
    const bool grown = grow_with_strategies(cluster, p, q);
    res_.seconds_growth += growth_clock.elapsed();
    if (!grown) return false;
    int tries = opt_.max_growth_steps;
    for (;;) {
      const RegionInterior inside = region_interior();
      if (inside.growth_bound <= budget_left()) {
        const TimeBudget patch_clock;
        const PatchOutcome outcome = apply_patch(p, q);
        res_.seconds_patch += patch_clock.elapsed();
        if (outcome != PatchOutcome::over_budget) return outcome == PatchOutcome::applied;
      }
      const TimeBudget absorb_clock;
      const bool absorbed = absorb_boundary_vertex(inside.growth_bound, p, q, tries);
      res_.seconds_growth += absorb_clock.elapsed();
      if (!absorbed) {
        ++res_.failures.budget;
        return false;
      }
    }
  }
};

}  // namespace

void widen_growth_limits(ConeRepairOptions& options, int times) {
  const int f = std::max(2, options.search_widening);
  if (times > 0 && options.bulk_growth_divisor == 0) options.bulk_growth_divisor = kWidenedBulkGrowthDivisor;
  for (int k = 0; k < times; ++k) {
    options.stall_growth_steps *= f;
    options.max_growth_steps *= f;
    options.max_region_tets *= std::size_t(f);
  }
}

ConeRepairResult whole_mesh_cone(TetMesh& source, PositionProperty& target, const VertexProperty<std::uint8_t>& locked,
                                 double time_limit_seconds) {
  const TimeBudget setup_clock;
  ConeRepairOptions options;
  options.time_limit_seconds = time_limit_seconds;
  ConeRepairer repairer(source, target, locked, options);
  const double setup = setup_clock.elapsed();
  ConeRepairResult res = repairer.patch_whole_mesh();
  res.seconds_setup = setup;
  return res;
}

ConeRepairResult cone_repair(TetMesh& source, PositionProperty& target, const VertexProperty<std::uint8_t>& locked,
                             const ConeRepairOptions& options) {
  const TimeBudget setup_clock;
  ConeRepairer repairer(source, target, locked, options);
  const double setup = setup_clock.elapsed();
  ConeRepairResult res = repairer.run();
  res.seconds_setup = setup;
  return res;
}

namespace {

// The flat-array forms: patches delete no vertex, so compaction keeps every vertex id.
bool patched(const ConeRepairResult& r) { return r.patches > 0; }

}  // namespace

ConeRepairResult cone_repair(TetMeshData& source, std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                             const ConeRepairOptions& options) {
  return edit_on_flat_arrays(
      source, locked, target_xyz, "cone_repair",
      [&](TetMesh& mesh, PositionProperty& target, const VertexProperty<std::uint8_t>& lock) { return cone_repair(mesh, target, lock, options); },
      patched);
}

ConeRepairResult whole_mesh_cone(TetMeshData& source, std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                                 double time_limit_seconds) {
  return edit_on_flat_arrays(
      source, locked, target_xyz, "whole_mesh_cone",
      [&](TetMesh& mesh, PositionProperty& target, const VertexProperty<std::uint8_t>& lock) {
        return whole_mesh_cone(mesh, target, lock, time_limit_seconds);
      },
      patched);
}

}  // namespace volmap
