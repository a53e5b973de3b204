// Tracing the domain's graph on the working surface (see arc_tracing.hpp). Paths are shortest paths
// (edge length; A* with the straight-line distance as lower bound) that enter no graph vertex but
// their end; the sector rule at both ends keeps the arcs around every node in the domain's cyclic
// order. Chords (edges off every arc joining two graph vertices) are split by the rule the caller
// picks: the reference's after every arc, or once at the end only those whose ends lie on one
// straight line of the domain (decided exactly on the domain's node targets).
#include "arc_tracing.hpp"

#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <string>
#include <utility>

namespace volmap::surface_detail {
namespace {

[[noreturn]] void fail(const std::string& reason) { throw Error(ErrorKind::Failed, "", 0, reason); }

constexpr double kInf = std::numeric_limits<double>::infinity();

class ArcTracer {
 public:
  ArcTracer(WorkingSurface& surface, const Domain& domain, ChordSplitRule rule)
      : s_(surface), d_(domain), rule_(rule) {
    g_.arc_path.resize(domain.arcs.size());
  }

  EmbeddedGraph run(const std::vector<int>& order, const Point3& bmin, const Point3& bmax) {
    grow_scratch();
    place_nodes(bmin, bmax);
    for (int arc : order) {
      const DomainDiagonal* diagonal = nullptr;
      for (const auto& dg : d_.diagonals)
        if (dg.first_arc == arc) diagonal = &dg;
      if (diagonal)
        trace_diagonal(*diagonal);
      else
        trace_arc(arc);
    }
    if (rule_ == ChordSplitRule::OnlyAlongOneLine) split_chords_along_one_line();
    return std::move(g_);
  }

 private:
  WorkingSurface& s_;
  const Domain& d_;
  ChordSplitRule rule_;
  EmbeddedGraph g_;
  // Dijkstra scratch, indexed by vertex index (grown after splits).
  std::vector<double> dist_;
  std::vector<HalfedgeHandle> pred_;  // last halfedge of the best path found to the vertex
  std::vector<std::uint32_t> touched_;
  std::vector<std::uint32_t> sector_a_, sector_b_;  // == stamp_: allowed first / last inner vertex
  std::uint32_t stamp_ = 0;
  std::vector<VertexHandle> ring_;
  VertexHandle sector_first_, sector_last_;  // mark_sector's bounding arc neighbours

  void grow_scratch() {
    const std::size_t n = s_.num_vertices();
    dist_.resize(n, kInf);
    pred_.resize(n);
    sector_a_.resize(n, 0);
    sector_b_.resize(n, 0);
  }
  bool traced(int arc) const { return !g_.arc_path[arc].empty(); }
  std::string node_name(int n) const { return "node " + std::to_string(n); }

  void place_nodes(const Point3& bmin, const Point3& bmax);
  VertexHandle arc_neighbour(int node, int arc) const;
  bool mark_sector(int node, int arc, std::vector<std::uint32_t>& stamps, std::string* between);
  std::vector<VertexHandle> shortest_path(int node_a, int arc_a, int node_b, int arc_b, std::string* why);
  std::vector<VertexHandle> traced_path(int node_a, int arc_a, int node_b, int arc_b, const std::string& what);
  std::vector<VertexHandle> path_through_chords(int node_a, int arc_a, int node_b, int arc_b);
  struct Sector {
    bool constrained = false;
    std::vector<char> faces;         // per face
    std::vector<VertexHandle> ring;  // neighbours inside the sector
    bool has(VertexHandle v) const { return !constrained || std::find(ring.begin(), ring.end(), v) != ring.end(); }
  };
  Sector sector(int node, int arc);
  bool is_chord(EdgeHandle e) const;
  void commit(const std::vector<VertexHandle>& path, std::size_t first, std::size_t last, int arc);
  void split_chords(const std::vector<VertexHandle>& path);
  std::vector<std::vector<char>> arcs_on_one_line() const;
  void split_chords_along_one_line();
  void trace_arc(int arc);
  void trace_diagonal(const DomainDiagonal& diagonal);
};

// Step 1: nearest free vertex to every probe (vertex indices increase with vid: strict < keeps the
// smallest vid on ties).
void ArcTracer::place_nodes(const Point3& bmin, const Point3& bmax) {
  g_.node_vertex.assign(d_.num_nodes(), VertexHandle());
  for (int n = 0; n < static_cast<int>(d_.num_nodes()); ++n) {
    if (!d_.has_probe(n)) continue;
    const Point3 p = d_.probe(n, bmin, bmax);
    double best = kInf, best_free = kInf;
    VertexHandle arg, arg_free;
    for (auto v : s_.mesh.vertices()) {
      const double* x = s_.point(v);
      const double dx = x[0] - p[0], dy = x[1] - p[1], dz = x[2] - p[2];
      const double d2 = dx * dx + dy * dy + dz * dz;
      if (d2 < best) best = d2, arg = v;
      if (d2 < best_free && !s_.is_on_graph(v)) best_free = d2, arg_free = v;
    }
    if (!arg_free.is_valid()) fail("no free boundary vertex for domain " + node_name(n));
    if (arg != arg_free) ++g_.collided_nodes;
    g_.node_vertex[n] = arg_free;
    s_.mesh.property(s_.on_graph, arg_free) = 1;
  }
}

// First vertex after `node` along traced arc `arc`.
VertexHandle ArcTracer::arc_neighbour(int node, int arc) const {
  const auto& p = g_.arc_path[arc];
  return d_.arcs[arc].from == node ? p[1] : p[p.size() - 2];
}

// Stamps the neighbours of `node` through which arc `arc` may leave it so that the cyclic order of
// arcs around the node follows the domain's rotation. Returns false (nothing stamped) when the node
// has no traced arc yet; `between` names the two traced arcs that bound the sector.
bool ArcTracer::mark_sector(int node, int arc, std::vector<std::uint32_t>& stamps, std::string* between) {
  const auto& rot = d_.rotation[node];
  const int deg = static_cast<int>(rot.size());
  const int i = static_cast<int>(std::find(rot.begin(), rot.end(), arc) - rot.begin());
  int prev = -1, next = -1;
  for (int k = 1; k < deg && prev < 0; ++k)
    if (traced(rot[(i - k + deg) % deg])) prev = rot[(i - k + deg) % deg];
  for (int k = 1; k < deg && next < 0; ++k)
    if (traced(rot[(i + k) % deg])) next = rot[(i + k) % deg];
  if (prev < 0) return false;
  s_.ring(g_.node_vertex[node], ring_);
  const int r = static_cast<int>(ring_.size());
  const auto pos = [&](VertexHandle v) {
    const auto it = std::find(ring_.begin(), ring_.end(), v);
    if (it == ring_.end()) fail("internal: an arc does not start at a neighbour of its node");
    return static_cast<int>(it - ring_.begin());
  };
  const int pp = pos(arc_neighbour(node, prev)), pn = pos(arc_neighbour(node, next));
  sector_first_ = ring_[pp];
  sector_last_ = ring_[pn];
  for (int k = 1; k < r; ++k) {
    const int q = (pp + k) % r;
    if (q == pn) break;
    stamps[ring_[q].idx()] = stamp_;
  }
  *between = "arcs " + std::to_string(prev) + " and " + std::to_string(next);
  return true;
}

// Dijkstra from node_a's vertex to node_b's vertex over free vertices, leaving node_a inside the
// sector of arc_a and entering node_b inside the sector of arc_b. Returns no path, with the reason in
// *why, when the free vertices reachable from the first sector never touch the last one.
std::vector<VertexHandle> ArcTracer::shortest_path(int node_a, int arc_a, int node_b, int arc_b, std::string* why) {
  const VertexHandle a = g_.node_vertex[node_a], b = g_.node_vertex[node_b];
  ++stamp_;
  std::string between_a, between_b;
  const bool constrain_a = mark_sector(node_a, arc_a, sector_a_, &between_a);
  const bool constrain_b = mark_sector(node_b, arc_b, sector_b_, &between_b);
  // A* with the straight-line distance to b, scaled by (1 - 1e-6) so that it stays a consistent
  // lower bound despite rounding: the first time b is popped its distance is the shortest.
  const double* pb = s_.point(b);
  const auto lower_bound = [&](VertexHandle v) {
    const double* p = s_.point(v);
    const double dx = p[0] - pb[0], dy = p[1] - pb[1], dz = p[2] - pb[2];
    return (1 - 1e-6) * std::sqrt(dx * dx + dy * dy + dz * dz);
  };
  using Item = std::pair<double, std::uint32_t>;  // (distance + lower bound, vertex)
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  for (auto v : touched_) dist_[v] = kInf;
  touched_.clear();
  dist_[a.idx()] = 0;
  touched_.push_back(a.idx());
  heap.push({lower_bound(a), static_cast<std::uint32_t>(a.idx())});
  bool reached = false;
  while (!heap.empty()) {
    const std::uint32_t ui = heap.top().second;
    const VertexHandle u(static_cast<int>(ui));
    const double du = dist_[ui];
    if (heap.top().first > du + lower_bound(u)) {  // stale entry
      heap.pop();
      continue;
    }
    heap.pop();
    if (u == b) {
      reached = true;
      break;
    }
    s_.for_each_outgoing(u, [&](HalfedgeHandle h) {
      const VertexHandle w = s_.mesh.to_vertex_handle(h);
      if (w != b && s_.is_on_graph(w)) return;
      if (u == a && constrain_a && sector_a_[w.idx()] != stamp_) return;
      if (w == b && constrain_b && sector_b_[ui] != stamp_) return;
      const double nd = du + s_.length(u, w);
      double& dw = dist_[w.idx()];
      if (nd < dw) {
        if (dw == kInf) touched_.push_back(w.idx());
        dw = nd;
        pred_[w.idx()] = h;
        heap.push({nd + lower_bound(w), static_cast<std::uint32_t>(w.idx())});
      }
    });
  }
  if (!reached) {
    *why = "the free vertices reachable from " + node_name(node_a) + (constrain_a ? " (between its " + between_a + ")" : "") +
           " never touch " + node_name(node_b) + (constrain_b ? " between its " + between_b : "");
    return {};
  }
  std::vector<VertexHandle> path{b};
  while (path.back() != a) path.push_back(s_.mesh.from_vertex_handle(pred_[path.back().idx()]));
  std::reverse(path.begin(), path.end());
  return path;
}

// Labels path[first..last] as arc `arc` (vertices on the graph, edges with the arc and direction).
void ArcTracer::commit(const std::vector<VertexHandle>& path, std::size_t first, std::size_t last, int arc) {
  auto& stored = g_.arc_path[arc];
  stored.assign(path.begin() + static_cast<std::ptrdiff_t>(first), path.begin() + static_cast<std::ptrdiff_t>(last) + 1);
  for (auto v : stored) s_.mesh.property(s_.on_graph, v) = 1;
  for (std::size_t i = 0; i + 1 < stored.size(); ++i) {
    const HalfedgeHandle h = s_.mesh.find_halfedge(stored[i], stored[i + 1]);
    if (!h.is_valid()) fail("internal: a traced path is not connected");
    s_.mesh.property(s_.arc_label, s_.mesh.edge_handle(h)) = 1 + 2 * arc + (h.idx() & 1);
  }
}

// Step 3 (reference rule): every edge from a path vertex to another graph vertex that is not an arc
// edge is split at its midpoint. This keeps a free path between any two arcs of a face (paper Fig. 4)
// and leaves no chart edge joining two chart-boundary vertices, which Tutte's embedding needs.
void ArcTracer::split_chords(const std::vector<VertexHandle>& path) {
  bool any = false;
  for (auto p : path) {
    for (;;) {
      const HalfedgeHandle h = s_.find_outgoing(p, [&](HalfedgeHandle x) {
        return s_.is_on_graph(s_.mesh.to_vertex_handle(x)) && !s_.is_arc_edge(s_.mesh.edge_handle(x));
      });
      if (!h.is_valid()) break;
      s_.split_edge(s_.mesh.edge_handle(h));
      any = true;
    }
  }
  if (any) grow_scratch();
}

// same[a][b]: arcs a and b lie on one straight line of the domain (a == b, or the four node targets
// are collinear, exactly). A polycube face's side may consist of several arcs in a row, and a star
// face diagonal of two halves.
std::vector<std::vector<char>> ArcTracer::arcs_on_one_line() const {
  const std::size_t n = d_.arcs.size();
  std::vector<std::vector<char>> same(n, std::vector<char>(n, 0));
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a; b < n; ++b) {
      const double* p = d_.targets[d_.arcs[a].from].data();
      const double* q = d_.targets[d_.arcs[a].to].data();
      const bool one_line = a == b || (collinear(p, q, d_.targets[d_.arcs[b].from].data()) &&
                                       collinear(p, q, d_.targets[d_.arcs[b].to].data()));
      same[a][b] = same[b][a] = one_line ? 1 : 0;
    }
  return same;
}

// Lean rule, after the last arc: a chord is split only when its two ends lie on one straight line
// of the domain (a graph vertex lies on its own arc; a node on every arc at it). Such a chord would
// fall onto the polygon's side in the chart's Tutte embedding and flatten its triangles. Any other
// chord joins two different sides of the chart's convex polygon, so its image crosses the polygon's
// interior and Tutte's embedding stays injective (Floater 2003: a convex combination map onto a
// convex polygon is one-to-one when no dividing edge has both ends on one side). The exact check of
// the map still decides.
void ArcTracer::split_chords_along_one_line() {
  const std::vector<std::vector<char>> same = arcs_on_one_line();
  std::vector<int> arc_of(s_.num_vertices(), -1);  // path-interior vertices
  for (std::size_t a = 0; a < g_.arc_path.size(); ++a)
    for (std::size_t i = 1; i + 1 < g_.arc_path[a].size(); ++i) arc_of[g_.arc_path[a][i].idx()] = static_cast<int>(a);
  std::vector<int> node_of(s_.num_vertices(), -1);
  for (std::size_t n = 0; n < g_.node_vertex.size(); ++n) node_of[g_.node_vertex[n].idx()] = static_cast<int>(n);
  const auto arcs_at = [&](VertexHandle v) {
    if (node_of[v.idx()] >= 0) return d_.rotation[node_of[v.idx()]];
    return std::vector<int>{arc_of[v.idx()]};
  };
  std::vector<EdgeHandle> chords;
  for (auto e : s_.mesh.edges()) {
    if (s_.is_arc_edge(e)) continue;
    const HalfedgeHandle h = s_.mesh.halfedge_handle(e, 0);
    const VertexHandle u = s_.mesh.from_vertex_handle(h), w = s_.mesh.to_vertex_handle(h);
    if (!s_.is_on_graph(u) || !s_.is_on_graph(w)) continue;
    bool one_line = false;
    for (int a : arcs_at(u))
      for (int b : arcs_at(w)) one_line = one_line || (a >= 0 && b >= 0 && same[a][b]);
    if (one_line) chords.push_back(e);
  }
  for (auto e : chords) s_.split_edge(e);
  if (!chords.empty()) grow_scratch();
}

bool ArcTracer::is_chord(EdgeHandle e) const {
  const HalfedgeHandle h = s_.mesh.halfedge_handle(e, 0);
  return !s_.is_arc_edge(e) && s_.is_on_graph(s_.mesh.from_vertex_handle(h)) && s_.is_on_graph(s_.mesh.to_vertex_handle(h));
}

// The faces at `node`'s vertex that arc `arc` may use there (all of them while the node has no
// traced arc) and the neighbours it may leave through (mark_sector's stamps, copied).
ArcTracer::Sector ArcTracer::sector(int node, int arc) {
  Sector sec;
  sec.faces.assign(s_.mesh.n_faces(), 0);
  ++stamp_;
  std::string between;
  sec.constrained = mark_sector(node, arc, sector_a_, &between);
  s_.for_each_outgoing(g_.node_vertex[node], [&](HalfedgeHandle h) {
    // Face (v, x, y), y the ring successor of x: inside the sector when x is stamped or is the arc
    // neighbour the sector starts after, and y is stamped or is the neighbour it ends before.
    const VertexHandle x = s_.mesh.to_vertex_handle(h);
    const VertexHandle y = s_.mesh.to_vertex_handle(s_.mesh.next_halfedge_handle(h));
    const bool x_stamped = sector_a_[x.idx()] == stamp_, y_stamped = sector_a_[y.idx()] == stamp_;
    if (x_stamped) sec.ring.push_back(x);
    const bool inside = !sec.constrained || ((x_stamped || x == sector_first_) && (y_stamped || y == sector_last_));
    sec.faces[s_.mesh.face_handle(h).idx()] = inside ? 1 : 0;
  });
  return sec;
}

// A blocked arc (lean rule): the path from node_a to node_b that crosses the fewest chords, the
// shortest among those; each chord it crosses is split and its midpoint joins the path. The search
// runs over vertices (node_a, node_b, free vertices) and chord crossings. A crossing is a chord
// halfedge h: the path enters the chord from the face of opposite(h) and leaves into face(h) =
// (from(h), to(h), z). From a vertex u the path may cross the chord opposite u in a face of u; from
// a crossing it goes on to z, or crosses one of the two other edges of face(h) (after the split the
// midpoint sees z and both of them). Every step thus enters a new face, so the consecutive path
// elements stay adjacent after the splits (a shortest path never enters a face twice: it could cut
// across that face with fewer crossings). The sector rules hold through the faces at both nodes.
// Returns no path when even that fails.
std::vector<VertexHandle> ArcTracer::path_through_chords(int node_a, int arc_a, int node_b, int arc_b) {
  const VertexHandle a = g_.node_vertex[node_a], b = g_.node_vertex[node_b];
  const Sector at_a = sector(node_a, arc_a), at_b = sector(node_b, arc_b);
  const std::size_t nv = s_.mesh.n_vertices(), nh = s_.mesh.n_halfedges();
  const auto position = [&](std::size_t state, double out[3]) {  // a vertex, or a crossed chord's midpoint
    if (state < nv) {
      const double* p = s_.point(VertexHandle(static_cast<int>(state)));
      out[0] = p[0], out[1] = p[1], out[2] = p[2];
      return;
    }
    const HalfedgeHandle h(static_cast<int>(state - nv));
    const double* p = s_.point(s_.mesh.from_vertex_handle(h));
    const double* q = s_.point(s_.mesh.to_vertex_handle(h));
    for (int k = 0; k < 3; ++k) out[k] = 0.5 * (p[k] + q[k]);
  };
  const double* pb = s_.point(b);
  const auto distance = [](const double* p, const double* q) {
    const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
    return std::sqrt(dx * dx + dy * dy + dz * dz);
  };
  const auto lower_bound = [&](std::size_t state) {
    double p[3];
    position(state, p);
    return (1 - 1e-6) * distance(p, pb);
  };
  // Keys (crossings, length + lower bound), compared lexicographically: A* on the length stays exact
  // because the crossing count never falls along a path.
  using Key = std::pair<std::uint32_t, double>;
  std::vector<Key> best(nv + nh, Key{~0u, kInf});
  std::vector<std::uint32_t> pred(nv + nh, ~0u);
  using Item = std::pair<Key, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  const auto relax = [&](std::uint32_t from, std::size_t to) {
    double p[3], q[3];
    position(from, p);
    position(to, q);
    const Key key{best[from].first + (to >= nv ? 1u : 0u), best[from].second + distance(p, q)};
    if (key < best[to]) {
      best[to] = key;
      pred[to] = from;
      heap.push({Key{key.first, key.second + lower_bound(to)}, static_cast<std::uint32_t>(to)});
    }
  };
  const auto cross = [&](std::uint32_t from, HalfedgeHandle entered) {  // the chord of `entered`, into its other face
    if (is_chord(s_.mesh.edge_handle(entered))) relax(from, nv + s_.mesh.opposite_halfedge_handle(entered).idx());
  };
  best[a.idx()] = Key{0, 0};
  heap.push({Key{0, lower_bound(a.idx())}, static_cast<std::uint32_t>(a.idx())});
  bool reached = false;
  while (!heap.empty()) {
    const Key key = heap.top().first;
    const std::uint32_t state = heap.top().second;  // a plain local: lambdas below capture it
    heap.pop();
    if (key.first != best[state].first || key.second > best[state].second + lower_bound(state)) continue;  // stale
    if (state == static_cast<std::uint32_t>(b.idx())) {
      reached = true;
      break;
    }
    if (state < nv) {
      const VertexHandle u(static_cast<int>(state));
      s_.for_each_outgoing(u, [&](HalfedgeHandle h) {
        // along the edge u -> w, with shortest_path's rules
        const VertexHandle w = s_.mesh.to_vertex_handle(h);
        if ((w == b || !s_.is_on_graph(w)) && (u != a || at_a.has(w)) && (w != b || at_b.has(u))) relax(state, w.idx());
        // across the chord opposite u in the face of h
        if (u != a || at_a.faces[s_.mesh.face_handle(h).idx()]) cross(state, s_.mesh.next_halfedge_handle(h));
      });
      continue;
    }
    const HalfedgeHandle h(static_cast<int>(state - nv));  // leaving into face (from(h), to(h), z)
    const HalfedgeHandle n = s_.mesh.next_halfedge_handle(h);
    const VertexHandle z = s_.mesh.to_vertex_handle(n);
    if (z == b ? at_b.faces[s_.mesh.face_handle(h).idx()] != 0 : !s_.is_on_graph(z)) relax(state, z.idx());
    cross(state, n);
    cross(state, s_.mesh.next_halfedge_handle(n));
  }
  if (!reached) return {};
  std::vector<std::uint32_t> states{static_cast<std::uint32_t>(b.idx())};
  while (states.back() != static_cast<std::uint32_t>(a.idx())) states.push_back(pred[states.back()]);
  std::reverse(states.begin(), states.end());
  std::vector<VertexHandle> path;
  for (std::uint32_t st : states)
    path.push_back(st < nv ? VertexHandle(static_cast<int>(st))
                           : s_.split_edge(s_.mesh.edge_handle(HalfedgeHandle(static_cast<int>(st - nv)))));
  grow_scratch();
  return path;
}

// shortest_path, or Error(Failed) naming `what`. Under the lean rule a blocked arc takes the path
// through the fewest chords (path_through_chords), which are split.
std::vector<VertexHandle> ArcTracer::traced_path(int node_a, int arc_a, int node_b, int arc_b, const std::string& what) {
  std::string why;
  std::vector<VertexHandle> path = shortest_path(node_a, arc_a, node_b, arc_b, &why);
  if (path.empty() && rule_ == ChordSplitRule::OnlyAlongOneLine) path = path_through_chords(node_a, arc_a, node_b, arc_b);
  if (path.empty()) fail("cannot trace " + what + ": " + why);
  return path;
}

void ArcTracer::trace_arc(int arc) {
  const auto& da = d_.arcs[arc];
  const auto path =
      traced_path(da.from, arc, da.to, arc, "arc " + std::to_string(da.from) + "->" + std::to_string(da.to));
  commit(path, 0, path.size() - 1, arc);
  if (rule_ == ChordSplitRule::AfterEveryArc) split_chords(path);
}

// A star face diagonal: one path, cut in its middle, which becomes the face node.
void ArcTracer::trace_diagonal(const DomainDiagonal& dg) {
  auto path = traced_path(dg.from, dg.first_arc, dg.to, dg.second_arc,
                            "face diagonal " + std::to_string(dg.from) + "->" + std::to_string(dg.to));
  if (path.size() == 2) {  // a single edge: split it so the diagonal has a middle vertex
    const VertexHandle m = s_.split_edge(s_.mesh.edge_handle(s_.mesh.find_halfedge(path[0], path[1])));
    grow_scratch();
    path = {path[0], m, path[1]};
  }
  const std::size_t h = path.size() / 2;
  g_.node_vertex[dg.middle_node] = path[h];
  commit(path, 0, h, dg.first_arc);
  commit(path, h, path.size() - 1, dg.second_arc);
  if (rule_ == ChordSplitRule::AfterEveryArc) split_chords(path);
}

}  // namespace

EmbeddedGraph embed_domain_graph(WorkingSurface& surface, const Domain& domain, const std::vector<int>& order,
                                 ChordSplitRule rule, const Point3& bmin, const Point3& bmax) {
  return ArcTracer(surface, domain, rule).run(order, bmin, bmax);
}

void check_rotations(const WorkingSurface& s, const Domain& d, const EmbeddedGraph& g) {
  std::vector<VertexHandle> ring;
  std::vector<int> pos;
  for (int n = 0; n < static_cast<int>(d.num_nodes()); ++n) {
    s.ring(g.node_vertex[n], ring);
    pos.clear();
    for (int arc : d.rotation[n]) {
      const auto& p = g.arc_path[arc];
      const VertexHandle next = d.arcs[arc].from == n ? p[1] : p[p.size() - 2];
      pos.push_back(static_cast<int>(std::find(ring.begin(), ring.end(), next) - ring.begin()));
    }
    int descents = 0;
    for (std::size_t i = 0; i < pos.size(); ++i) descents += pos[(i + 1) % pos.size()] < pos[i];
    if (descents != 1) fail("the arcs around domain node " + std::to_string(n) + " are not in the domain's cyclic order");
  }
}

std::vector<int> spanning_tree_first_order(const Domain& d) {
  const std::vector<int> base = d.trace_order();
  std::vector<char> in_diagonal(d.arcs.size(), 0);
  for (const auto& g : d.diagonals) in_diagonal[g.first_arc] = in_diagonal[g.second_arc] = 1;
  std::vector<char> reached(d.num_nodes(), 0), taken(d.arcs.size(), 0);
  std::vector<int> order, queue{0};
  reached[0] = 1;
  for (std::size_t q = 0; q < queue.size(); ++q)
    for (int a : base) {
      if (in_diagonal[a] || taken[a]) continue;
      const int u = d.arcs[a].from, v = d.arcs[a].to;
      if (!d.has_probe(u) || !d.has_probe(v)) continue;
      const int w = u == queue[q] ? v : v == queue[q] ? u : -1;
      if (w < 0 || reached[w]) continue;
      reached[w] = 1;
      taken[a] = 1;
      order.push_back(a);
      queue.push_back(w);
    }
  for (int a : base)
    if (!taken[a]) order.push_back(a);
  return order;
}

}  // namespace volmap::surface_detail
