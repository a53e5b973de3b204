// Tracing the domain's graph on the working surface (see arc_tracing.hpp). Paths are shortest paths
// (edge length; A* with the straight-line distance as lower bound) that enter no graph vertex but
// their end; the sector rule at both ends keeps the arcs around every node in the domain's cyclic
// order.
#include "arc_tracing.hpp"

#include <volmap/core/error.hpp>

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
  ArcTracer(WorkingSurface& surface, const Domain& domain) : s_(surface), d_(domain) {
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
    return std::move(g_);
  }

 private:
  WorkingSurface& s_;
  const Domain& d_;
  EmbeddedGraph g_;
  // Dijkstra scratch, indexed by vertex index (grown after splits).
  std::vector<double> dist_;
  std::vector<HalfedgeHandle> pred_;  // last halfedge of the best path found to the vertex
  std::vector<std::uint32_t> touched_;
  std::vector<std::uint32_t> sector_a_, sector_b_;  // == stamp_: allowed first / last inner vertex
  std::uint32_t stamp_ = 0;
  std::vector<VertexHandle> ring_;

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
  std::vector<VertexHandle> shortest_path(int node_a, int arc_a, int node_b, int arc_b, const std::string& what);
  void commit(const std::vector<VertexHandle>& path, std::size_t first, std::size_t last, int arc);
  void split_chords(const std::vector<VertexHandle>& path);
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
  for (int k = 1; k < r; ++k) {
    const int q = (pp + k) % r;
    if (q == pn) break;
    stamps[ring_[q].idx()] = stamp_;
  }
  *between = "arcs " + std::to_string(prev) + " and " + std::to_string(next);
  return true;
}

// Dijkstra from node_a's vertex to node_b's vertex over free vertices, leaving node_a inside the
// sector of arc_a and entering node_b inside the sector of arc_b. Throws with the reason when the
// free vertices reachable from the first sector never touch the last one.
std::vector<VertexHandle> ArcTracer::shortest_path(int node_a, int arc_a, int node_b, int arc_b,
                                                   const std::string& what) {
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
    std::string why = "the free vertices reachable from " + node_name(node_a) +
                      (constrain_a ? " (between its " + between_a + ")" : "") + " never touch " + node_name(node_b) +
                      (constrain_b ? " between its " + between_b : "");
    fail("cannot trace " + what + ": " + why);
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

void ArcTracer::trace_arc(int arc) {
  const auto& da = d_.arcs[arc];
  const auto path =
      shortest_path(da.from, arc, da.to, arc, "arc " + std::to_string(da.from) + "->" + std::to_string(da.to));
  commit(path, 0, path.size() - 1, arc);
  split_chords(path);
}

// A star face diagonal: one path, cut in its middle, which becomes the face node.
void ArcTracer::trace_diagonal(const DomainDiagonal& dg) {
  auto path = shortest_path(dg.from, dg.first_arc, dg.to, dg.second_arc,
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
  split_chords(path);
}

}  // namespace

EmbeddedGraph embed_domain_graph(WorkingSurface& surface, const Domain& domain, const std::vector<int>& order,
                                 const Point3& bmin, const Point3& bmax) {
  return ArcTracer(surface, domain).run(order, bmin, bmax);
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
