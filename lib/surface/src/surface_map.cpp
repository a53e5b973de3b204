// Surface mapping onto a base domain (see surface_map.hpp for the algorithm).
// Conventions: boundary triangles are kept in the outward winding of their tet (kTetFace), so
// around a vertex v a triangle (v,x,y) turns counter-clockwise from x to y seen from outside, the same
// sense as the domain's rotation system. Vertex ids are those of the tet mesh; split vertices are
// appended. The working surface is a small flat structure (triangles + per-vertex triangle lists in
// one pool (VertexTriangleLists) + CSR adjacency rebuilt after each arc); the tet mesh is refined
// once at the end by replaying the recorded edge splits with TetMesh::split_edge (which appends the
// new vertices in the same order, so vertex ids agree).
#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>
#include <volmap/surface/surface_map.hpp>
#include <volmap/core/tet_mesh.hpp>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>
#include <unordered_map>

namespace volmap {
namespace {

using Tri = std::array<std::uint32_t, 3>;

[[noreturn]] void fail(const std::string& reason) { throw Error(ErrorKind::Failed, "", 0, reason); }

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | b;
}

// The triangles around every vertex, as lists in one flat pool (CSR with slack): list v occupies
// pool[first[v], first[v] + size[v]) with room for cap[v] ids. A full list moves to the end of the
// pool with twice the room, so pushes are amortised O(1) and no list owns a heap block. Lists keep
// their order (append at the end, erase shifts), hence stay sorted by triangle id here: new triangles
// always get the largest id.
class VertexTriangleLists {
 public:
  void build(std::size_t nv, const std::vector<Tri>& tris) {
    first_.assign(nv + 1, 0);
    for (const Tri& t : tris)
      for (auto v : t) ++first_[v + 1];
    for (std::size_t v = 0; v < nv; ++v) first_[v + 1] += first_[v];
    pool_.assign(first_[nv], 0);
    size_.assign(nv, 0);
    cap_.resize(nv);
    for (std::size_t v = 0; v < nv; ++v) cap_[v] = first_[v + 1] - first_[v];
    first_.pop_back();
    for (std::uint32_t t = 0; t < tris.size(); ++t)
      for (auto v : tris[t]) pool_[first_[v] + size_[v]++] = t;
  }
  void add_vertex() {
    first_.push_back(static_cast<std::uint32_t>(pool_.size()));
    size_.push_back(0);
    cap_.push_back(0);
  }
  std::size_t size(std::uint32_t v) const { return size_[v]; }
  bool empty(std::uint32_t v) const { return size_[v] == 0; }
  // Valid until the next push_back.
  Span<std::uint32_t> operator[](std::uint32_t v) const { return {pool_.data() + first_[v], size_[v]}; }
  void push_back(std::uint32_t v, std::uint32_t t) {
    if (size_[v] == cap_[v]) {
      const std::uint32_t cap = std::max<std::uint32_t>(4, 2 * cap_[v]);
      const auto at = static_cast<std::uint32_t>(pool_.size());
      pool_.resize(pool_.size() + cap);
      std::copy_n(pool_.begin() + first_[v], size_[v], pool_.begin() + at);
      first_[v] = at;
      cap_[v] = cap;
    }
    pool_[first_[v] + size_[v]++] = t;
  }
  void erase(std::uint32_t v, std::uint32_t t) {
    std::uint32_t* p = pool_.data() + first_[v];
    std::uint32_t* end = p + size_[v];
    std::uint32_t* it = std::find(p, end, t);
    if (it == end) return;
    std::copy(it + 1, end, it);
    --size_[v];
  }

 private:
  std::vector<std::uint32_t> pool_, first_, size_, cap_;
};

struct Surface {
  std::vector<double> xyz;                       // every mesh vertex (grows with splits)
  std::vector<Tri> tris;                         // boundary triangles, outward
  VertexTriangleLists vtris;                     // boundary triangles around each vertex
  std::vector<std::uint32_t> around_;            // split_edge scratch
  std::vector<std::uint32_t> adj_offset, adj;    // CSR neighbours (boundary edges)
  std::vector<std::array<std::uint32_t, 3>> splits;  // (a, b, new vertex) in order

  std::size_t num_vertices() const { return xyz.size() / 3; }

  void build_adjacency() {
    const std::size_t n = num_vertices();
    adj_offset.assign(n + 1, 0);
    for (const Tri& t : tris)
      for (int k = 0; k < 3; ++k) ++adj_offset[t[k] + 1];
    for (std::size_t v = 0; v < n; ++v) adj_offset[v + 1] += adj_offset[v];
    adj.resize(adj_offset[n]);
    std::vector<std::uint32_t> fill(adj_offset.begin(), adj_offset.end() - 1);
    // In a closed oriented manifold every edge u->v occurs once as a directed triangle edge.
    for (const Tri& t : tris)
      for (int k = 0; k < 3; ++k) adj[fill[t[k]]++] = t[(k + 1) % 3];
  }

  double length(std::uint32_t a, std::uint32_t b) const {
    const double dx = xyz[3 * a] - xyz[3 * b], dy = xyz[3 * a + 1] - xyz[3 * b + 1], dz = xyz[3 * a + 2] - xyz[3 * b + 2];
    return std::sqrt(dx * dx + dy * dy + dz * dz);
  }

  // Neighbours of v in counter-clockwise order seen from outside.
  std::vector<std::uint32_t> ring(std::uint32_t v) const {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> next;  // x -> y for triangle (v,x,y)
    for (auto t : vtris[v]) {
      const Tri& tr = tris[t];
      const int k = tr[0] == v ? 0 : tr[1] == v ? 1 : 2;
      next.push_back({tr[(k + 1) % 3], tr[(k + 2) % 3]});
    }
    std::vector<std::uint32_t> out;
    if (next.empty()) return out;
    std::uint32_t x = next[0].first;
    for (std::size_t step = 0; step < next.size(); ++step) {
      out.push_back(x);
      auto it = std::find_if(next.begin(), next.end(), [&](auto& p) { return p.first == x; });
      if (it == next.end()) fail("boundary surface is not manifold at vertex " + std::to_string(v));
      x = it->second;
    }
    if (x != out[0]) fail("boundary surface is not manifold at vertex " + std::to_string(v));
    return out;
  }

  // Splits boundary edge (a,b) at its midpoint; returns the new vertex id.
  std::uint32_t split_edge(std::uint32_t a, std::uint32_t b) {
    const auto m = static_cast<std::uint32_t>(num_vertices());
    for (int k = 0; k < 3; ++k) xyz.push_back(0.5 * (xyz[3 * a + k] + xyz[3 * b + k]));
    vtris.add_vertex();
    const auto around_a = vtris[a];
    around_.assign(around_a.begin(), around_a.end());
    int found = 0;
    for (auto t : around_) {
      Tri tr = tris[t];
      int k = -1;
      for (int i = 0; i < 3; ++i)
        if ((tr[i] == a && tr[(i + 1) % 3] == b) || (tr[i] == b && tr[(i + 1) % 3] == a)) k = i;
      if (k < 0) continue;
      ++found;
      const std::uint32_t x = tr[k], y = tr[(k + 1) % 3], z = tr[(k + 2) % 3];
      // (x,y,z) -> (x,m,z) in place and (m,y,z) appended.
      tris[t] = {x, m, z};
      const auto t2 = static_cast<std::uint32_t>(tris.size());
      tris.push_back({m, y, z});
      vtris.erase(y, t);
      vtris.push_back(y, t2);
      vtris.push_back(z, t2);
      vtris.push_back(m, t);
      vtris.push_back(m, t2);
    }
    if (found != 2) fail("boundary edge " + std::to_string(a) + "-" + std::to_string(b) + " is not manifold");
    splits.push_back({a, b, m});
    return m;
  }
};

class Mapper {
 public:
  Mapper(const TetMeshData& mesh, const Domain& domain, std::vector<int> order, int subdivisions)
      : mesh_(mesh), domain_(domain), order_(std::move(order)), subdivisions_(subdivisions) {}

  SurfaceMapResult run();

 private:
  const TetMeshData& mesh_;
  const Domain& domain_;
  std::vector<int> order_;  // arcs in tracing order (a diagonal by its first arc)
  int subdivisions_ = 0;    // rounds of splitting every boundary edge before anything else
  Surface s_;
  std::vector<char> masked_;
  std::vector<std::uint32_t> node_vertex_;
  // Traced arcs, from -> to, in one pool: arc a is arc_pool_[arc_first_[a], + arc_size_[a]) (size 0:
  // not traced yet). Paths are appended in tracing order.
  std::vector<std::uint32_t> arc_pool_, arc_first_, arc_size_;
  Span<std::uint32_t> arc_path(int arc) const { return {arc_pool_.data() + arc_first_[arc], arc_size_[arc]}; }
  bool arc_traced(int arc) const { return arc_size_[arc] != 0; }
  std::unordered_map<std::uint64_t, std::int32_t> arc_edge_;  // key -> 2*arc + (path visits min first ? 1 : 0)
  // Dijkstra scratch.
  std::vector<double> dist_;
  std::vector<std::uint32_t> pred_;
  std::vector<std::uint32_t> touched_;
  std::vector<std::uint32_t> allow_stamp_a_, allow_stamp_b_;
  std::uint32_t stamp_ = 0;

  void grow_vertex_arrays() {
    const std::size_t n = s_.num_vertices();
    masked_.resize(n, 0);
    dist_.resize(n, std::numeric_limits<double>::infinity());
    pred_.resize(n, 0);
    allow_stamp_a_.resize(n, 0);
    allow_stamp_b_.resize(n, 0);
  }
  bool is_arc_edge(std::uint32_t a, std::uint32_t b) const { return arc_edge_.count(edge_key(a, b)) != 0; }
  // First vertex after node n along traced arc `arc`.
  std::uint32_t arc_neighbour(int node, int arc) const {
    const auto p = arc_path(arc);
    return domain_.arcs[arc].from == node ? p[1] : p[p.size() - 2];
  }
  bool sector(int node, int arc, std::vector<std::uint32_t>& stamps, std::uint32_t stamp) const;
  std::vector<std::uint32_t> trace(std::uint32_t a, std::uint32_t b, int node_a, int arc_a, int node_b, int arc_b,
                                   const std::string& what);
  void commit_path(const std::vector<std::uint32_t>& path, int arc);
  void split_chords(const std::vector<std::uint32_t>& path);
  void assign_nodes(SurfaceMapResult& result);
  void check_rotations() const;
  std::vector<double> embed_charts();
  void refine_tets(TetMeshData& out) const;
};

void Mapper::assign_nodes(SurfaceMapResult& result) {
  Point3 lo{mesh_.xyz[0], mesh_.xyz[1], mesh_.xyz[2]}, hi = lo;
  for (std::size_t v = 0; v < mesh_.num_vertices(); ++v)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], mesh_.xyz[3 * v + k]);
      hi[k] = std::max(hi[k], mesh_.xyz[3 * v + k]);
    }
  std::vector<std::uint32_t> bverts;
  for (std::uint32_t v = 0; v < s_.num_vertices(); ++v)
    if (!s_.vtris.empty(v)) bverts.push_back(v);
  node_vertex_.assign(domain_.num_nodes(), UINT32_MAX);
  for (int n = 0; n < static_cast<int>(domain_.num_nodes()); ++n) {
    if (!domain_.has_probe(n)) continue;
    const Point3 p = domain_.probe(n, lo, hi);
    double best = std::numeric_limits<double>::infinity(), best_free = best;
    std::uint32_t arg = UINT32_MAX, arg_free = UINT32_MAX;
    for (auto v : bverts) {  // sorted ids: strict < keeps the smallest vid on ties
      const double dx = s_.xyz[3 * v] - p[0], dy = s_.xyz[3 * v + 1] - p[1], dz = s_.xyz[3 * v + 2] - p[2];
      const double d2 = dx * dx + dy * dy + dz * dz;
      if (d2 < best) best = d2, arg = v;
      if (d2 < best_free && !masked_[v]) best_free = d2, arg_free = v;
    }
    if (arg_free == UINT32_MAX) fail("no free boundary vertex for domain node " + std::to_string(n));
    if (arg != arg_free) ++result.collided_nodes;
    node_vertex_[n] = arg_free;
    masked_[arg_free] = 1;
  }
}

// Marks (stamps[v] = stamp) the neighbours of node `node` through which arc `arc` may leave it so the
// cyclic order of arcs around the node follows the domain's rotation. Returns false when every
// direction is allowed (fewer than one traced arc around the node).
bool Mapper::sector(int node, int arc, std::vector<std::uint32_t>& stamps, std::uint32_t stamp) const {
  const auto& rot = domain_.rotation[node];
  const int deg = static_cast<int>(rot.size());
  const int i = static_cast<int>(std::find(rot.begin(), rot.end(), arc) - rot.begin());
  int prev = -1, next = -1;
  for (int k = 1; k < deg && prev < 0; ++k)
    if (arc_traced(rot[(i - k + deg) % deg])) prev = rot[(i - k + deg) % deg];
  for (int k = 1; k < deg && next < 0; ++k)
    if (arc_traced(rot[(i + k) % deg])) next = rot[(i + k) % deg];
  if (prev < 0) return false;
  const auto ring = s_.ring(node_vertex_[node]);
  const int r = static_cast<int>(ring.size());
  const auto pos = [&](std::uint32_t v) {
    const auto it = std::find(ring.begin(), ring.end(), v);
    if (it == ring.end()) fail("internal: arc does not start at a neighbour of its node");
    return static_cast<int>(it - ring.begin());
  };
  const int pp = pos(arc_neighbour(node, prev)), pn = pos(arc_neighbour(node, next));
  for (int k = 1; k < r; ++k) {
    const int q = (pp + k) % r;
    if (q == pn) break;
    stamps[ring[q]] = stamp;
  }
  return true;
}

std::vector<std::uint32_t> Mapper::trace(std::uint32_t a, std::uint32_t b, int node_a, int arc_a, int node_b,
                                         int arc_b, const std::string& what) {
  ++stamp_;
  const bool constrain_a = sector(node_a, arc_a, allow_stamp_a_, stamp_);
  const bool constrain_b = sector(node_b, arc_b, allow_stamp_b_, stamp_);
  using Item = std::pair<double, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  for (auto v : touched_) dist_[v] = std::numeric_limits<double>::infinity();
  touched_.clear();
  dist_[a] = 0;
  touched_.push_back(a);
  heap.push({0.0, a});
  bool reached = false;
  while (!heap.empty()) {
    const auto [d, u] = heap.top();
    heap.pop();
    if (d > dist_[u]) continue;
    if (u == b) {
      reached = true;
      break;
    }
    for (std::uint32_t k = s_.adj_offset[u]; k < s_.adj_offset[u + 1]; ++k) {
      const std::uint32_t w = s_.adj[k];
      if (w != b && masked_[w]) continue;
      if (u == a && constrain_a && allow_stamp_a_[w] != stamp_) continue;
      if (w == b && constrain_b && allow_stamp_b_[u] != stamp_) continue;
      const double nd = d + s_.length(u, w);
      if (nd < dist_[w]) {
        if (dist_[w] == std::numeric_limits<double>::infinity()) touched_.push_back(w);
        dist_[w] = nd;
        pred_[w] = u;
        heap.push({nd, w});
      }
    }
  }
  if (!reached)
    fail("cannot trace " + what + ": no free boundary path in the sector the domain's arc order requires");
  std::vector<std::uint32_t> path{b};
  while (path.back() != a) path.push_back(pred_[path.back()]);
  std::reverse(path.begin(), path.end());
  return path;
}

void Mapper::commit_path(const std::vector<std::uint32_t>& path, int arc) {
  arc_first_[arc] = static_cast<std::uint32_t>(arc_pool_.size());
  arc_size_[arc] = static_cast<std::uint32_t>(path.size());
  arc_pool_.insert(arc_pool_.end(), path.begin(), path.end());
  for (auto v : path) masked_[v] = 1;
  for (std::size_t i = 0; i + 1 < path.size(); ++i)
    arc_edge_[edge_key(path[i], path[i + 1])] = 2 * arc + (path[i] < path[i + 1] ? 1 : 0);
}

void Mapper::split_chords(const std::vector<std::uint32_t>& path) {
  bool any = false;
  for (auto p : path) {
    for (bool again = true; again;) {
      again = false;
      const std::size_t deg = s_.vtris.size(p);
      for (std::size_t i = 0; i < deg; ++i) {  // by index: a split below ends this loop
        const Tri& tr = s_.tris[s_.vtris[p][i]];
        const int k = tr[0] == p ? 0 : tr[1] == p ? 1 : 2;
        const std::uint32_t q = tr[(k + 1) % 3];
        if (masked_[q] && !is_arc_edge(p, q)) {
          s_.split_edge(p, q);
          grow_vertex_arrays();
          any = again = true;
          break;
        }
      }
    }
  }
  if (any) s_.build_adjacency();
}

void Mapper::check_rotations() const {
  for (int n = 0; n < static_cast<int>(domain_.num_nodes()); ++n) {
    const auto ring = s_.ring(node_vertex_[n]);
    std::vector<int> pos;
    for (int arc : domain_.rotation[n])
      pos.push_back(static_cast<int>(std::find(ring.begin(), ring.end(), arc_neighbour(n, arc)) - ring.begin()));
    int descents = 0;
    for (std::size_t i = 0; i < pos.size(); ++i) descents += pos[(i + 1) % pos.size()] < pos[i];
    if (descents != 1)
      fail("the arcs around domain node " + std::to_string(n) + " are not in the domain's cyclic order");
  }
}

std::vector<double> Mapper::embed_charts() {
  const std::size_t nv = s_.num_vertices();
  const std::size_t nt = s_.tris.size();
  std::vector<double> img(3 * nv, std::numeric_limits<double>::quiet_NaN());
  // Nodes and arcs.
  for (std::size_t n = 0; n < domain_.num_nodes(); ++n)
    for (int k = 0; k < 3; ++k) img[3 * node_vertex_[n] + k] = domain_.targets[n][k];
  for (std::size_t a = 0; a < domain_.arcs.size(); ++a) {
    const auto p = arc_path(static_cast<int>(a));
    const Point3& ta = domain_.targets[domain_.arcs[a].from];
    const Point3& tb = domain_.targets[domain_.arcs[a].to];
    double total = 0;
    for (std::size_t i = 0; i + 1 < p.size(); ++i) total += s_.length(p[i], p[i + 1]);
    double acc = 0;
    for (std::size_t i = 1; i + 1 < p.size(); ++i) {
      acc += s_.length(p[i - 1], p[i]);
      const double t = acc / total;
      for (int k = 0; k < 3; ++k) img[3 * p[i] + k] = ta[k] + t * (tb[k] - ta[k]);
    }
  }
  // Face of each dart (2*arc + 0: from->to, +1: to->from), the face on its left.
  std::vector<int> face_of_dart(2 * domain_.arcs.size(), -1);
  for (std::size_t f = 0; f < domain_.faces.size(); ++f) {
    const auto& face = domain_.faces[f];
    for (std::size_t i = 0; i < face.arcs.size(); ++i) {
      const int arc = face.arcs[i];
      face_of_dart[2 * arc + (domain_.arcs[arc].from == face.nodes[i] ? 0 : 1)] = static_cast<int>(f);
    }
  }
  // Flood charts across non-arc edges.
  std::vector<std::int32_t> chart(nt, -1);
  std::vector<int> chart_face;
  std::vector<std::uint32_t> stack;
  for (std::uint32_t seed = 0; seed < nt; ++seed) {
    if (chart[seed] >= 0) continue;
    const int c = static_cast<int>(chart_face.size());
    chart_face.push_back(-1);
    chart[seed] = c;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const std::uint32_t t = stack.back();
      stack.pop_back();
      const Tri tr = s_.tris[t];
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t x = tr[k], y = tr[(k + 1) % 3];
        const auto it = arc_edge_.find(edge_key(x, y));
        if (it != arc_edge_.end()) {
          const int arc = it->second / 2;
          const bool min_first = it->second % 2 == 1;
          const bool forward = (x < y) == min_first;  // x -> y runs from -> to along the arc
          const int f = face_of_dart[2 * arc + (forward ? 0 : 1)];
          if (chart_face[c] >= 0 && chart_face[c] != f)
            fail("a chart touches two domain faces: the embedded arcs do not match the domain");
          chart_face[c] = f;
          continue;
        }
        for (auto t2 : s_.vtris[x]) {
          if (t2 == t || chart[t2] >= 0) continue;
          const Tri& o = s_.tris[t2];
          if (o[0] == y || o[1] == y || o[2] == y) {
            chart[t2] = c;
            stack.push_back(t2);
          }
        }
      }
    }
  }
  if (chart_face.size() != domain_.faces.size())
    fail("the arcs cut the surface into " + std::to_string(chart_face.size()) + " charts, the domain has " +
         std::to_string(domain_.faces.size()) + " faces");
  std::vector<int> seen_face(domain_.faces.size(), 0);
  for (int f : chart_face) {
    if (f < 0 || seen_face[f]++) fail("charts do not correspond one-to-one to domain faces");
  }
  // Tutte per chart in the face plane.
  std::vector<std::int32_t> local(nv, -1);
  std::vector<std::uint32_t> interior;
  // Triangles of each chart, CSR (sorted by triangle id).
  std::vector<std::uint32_t> chart_first(chart_face.size() + 1, 0), chart_tris(nt);
  for (std::uint32_t t = 0; t < nt; ++t) ++chart_first[chart[t] + 1];
  for (std::size_t c = 0; c < chart_face.size(); ++c) chart_first[c + 1] += chart_first[c];
  {
    std::vector<std::uint32_t> fill(chart_first.begin(), chart_first.end() - 1);
    for (std::uint32_t t = 0; t < nt; ++t) chart_tris[fill[chart[t]]++] = t;
  }
  for (std::size_t c = 0; c < chart_face.size(); ++c) {
    const auto& face = domain_.faces[chart_face[c]];
    interior.clear();
    for (std::uint32_t q = chart_first[c]; q < chart_first[c + 1]; ++q) {
      const std::uint32_t t = chart_tris[q];
      for (auto v : s_.tris[t])
        if (!masked_[v] && local[v] < 0) {
          local[v] = static_cast<std::int32_t>(interior.size());
          interior.push_back(v);
        }
    }
    if (interior.empty()) continue;
    // Face frame: origin, e1 along the first side, e2 = normal x e1 (Newell normal).
    const Point3 o = domain_.targets[face.nodes[0]];
    Point3 nrm{0, 0, 0};
    const std::size_t k = face.nodes.size();
    for (std::size_t i = 0; i < k; ++i) {
      const Point3& p = domain_.targets[face.nodes[i]];
      const Point3& q = domain_.targets[face.nodes[(i + 1) % k]];
      nrm[0] += (p[1] - q[1]) * (p[2] + q[2]);
      nrm[1] += (p[2] - q[2]) * (p[0] + q[0]);
      nrm[2] += (p[0] - q[0]) * (p[1] + q[1]);
    }
    const double nn = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    for (auto& x : nrm) x /= nn;
    Point3 e1;
    for (int j = 0; j < 3; ++j) e1[j] = domain_.targets[face.nodes[1]][j] - o[j];
    const double l1 = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (auto& x : e1) x /= l1;
    const Point3 e2{nrm[1] * e1[2] - nrm[2] * e1[1], nrm[2] * e1[0] - nrm[0] * e1[2], nrm[0] * e1[1] - nrm[1] * e1[0]};
    const std::size_t m = interior.size();
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(7 * m);
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(m), 2);
    for (std::size_t i = 0; i < m; ++i) {
      const std::uint32_t v = interior[i];
      const std::uint32_t deg = s_.adj_offset[v + 1] - s_.adj_offset[v];
      trip.emplace_back(static_cast<int>(i), static_cast<int>(i), static_cast<double>(deg));
      for (std::uint32_t q = s_.adj_offset[v]; q < s_.adj_offset[v + 1]; ++q) {
        const std::uint32_t w = s_.adj[q];
        if (masked_[w]) {
          double d[3];
          for (int j = 0; j < 3; ++j) d[j] = img[3 * w + j] - o[j];
          rhs(static_cast<Eigen::Index>(i), 0) += d[0] * e1[0] + d[1] * e1[1] + d[2] * e1[2];
          rhs(static_cast<Eigen::Index>(i), 1) += d[0] * e2[0] + d[1] * e2[1] + d[2] * e2[2];
        } else {
          if (local[w] < 0) fail("internal: interior vertex with a neighbour outside its chart");
          trip.emplace_back(static_cast<int>(i), local[w], -1.0);
        }
      }
    }
    Eigen::SparseMatrix<double> L(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(m));
    L.setFromTriplets(trip.begin(), trip.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(L);
    if (solver.info() != Eigen::Success) fail("Tutte system of a chart could not be factorised");
    const Eigen::MatrixXd uv = solver.solve(rhs);
    if (solver.info() != Eigen::Success) fail("Tutte system of a chart could not be solved");
    for (std::size_t i = 0; i < m; ++i) {
      const double u = uv(static_cast<Eigen::Index>(i), 0), w = uv(static_cast<Eigen::Index>(i), 1);
      for (int j = 0; j < 3; ++j) img[3 * interior[i] + j] = o[j] + u * e1[j] + w * e2[j];
    }
    for (auto v : interior) local[v] = -1;
  }
  return img;
}

// Replays the surface's edge splits on the tets with TetMesh::split_edge (every tet around edge
// (a,b) becomes two; the new vertex is appended, so its id is the surface's). A child is positive
// iff the midpoint lies strictly on the replaced vertex's side; rounding can break that, so the
// children (the tets holding a new vertex) are checked exactly. TetMesh refuses vertices used by
// no tet: an input with such vertices is replayed on its used vertices (renumbered in order) and
// translated back, so they stay in the output where they were.
void Mapper::refine_tets(TetMeshData& out) const {
  if (s_.splits.empty()) {
    out = mesh_;
    return;
  }
  const std::size_t nv0 = mesh_.num_vertices();
  std::vector<std::uint32_t> compact_of(nv0, kInvalidIndex), original_of;  // used vertices only
  for (auto v : mesh_.tets) compact_of[v] = 0;
  const bool all_used = std::find(compact_of.begin(), compact_of.end(), kInvalidIndex) == compact_of.end();
  TetMeshData used;
  if (!all_used) {
    for (std::uint32_t v = 0; v < nv0; ++v)
      if (compact_of[v] != kInvalidIndex) {
        compact_of[v] = static_cast<std::uint32_t>(original_of.size());
        original_of.push_back(v);
        used.xyz.insert(used.xyz.end(), &mesh_.xyz[3 * std::size_t(v)], &mesh_.xyz[3 * std::size_t(v)] + 3);
      }
    used.tets = mesh_.tets;
    for (auto& v : used.tets) v = compact_of[v];
    used.tet_labels = mesh_.tet_labels;
  }
  const auto nu = static_cast<std::uint32_t>(all_used ? nv0 : original_of.size());
  const auto to_tm = [&](std::uint32_t v) {
    return all_used ? v : v < nv0 ? compact_of[v] : static_cast<std::uint32_t>(nu + (v - nv0));
  };
  TetMesh tm(all_used ? mesh_ : used);
  for (const auto& sp : s_.splits) {
    const VertexId m = tm.split_edge(VertexId(to_tm(sp[0])), VertexId(to_tm(sp[1])), &s_.xyz[3 * std::size_t(sp[2])]);
    if (m.idx() != to_tm(sp[2])) fail("internal: the tet mesh numbered split vertex " + std::to_string(sp[2]) + " differently");
  }
  TetMeshData refined = tm.to_data();
  out.xyz = s_.xyz;
  out.vertex_labels = mesh_.vertex_labels;
  out.vertex_labels.resize(s_.num_vertices(), 0);
  out.tets = std::move(refined.tets);
  out.tet_labels = std::move(refined.tet_labels);
  if (!all_used)
    for (auto& v : out.tets) v = v < nu ? original_of[v] : static_cast<std::uint32_t>(nv0 + (v - nu));
  for (std::size_t t = 0; t < out.num_tets(); ++t) {
    const std::uint32_t* q = &out.tets[4 * t];
    if (q[0] < nv0 && q[1] < nv0 && q[2] < nv0 && q[3] < nv0) continue;
    if (orient3d(&out.xyz[3 * q[0]], &out.xyz[3 * q[1]], &out.xyz[3 * q[2]], &out.xyz[3 * q[3]]) <= 0)
      fail("splitting a boundary edge produced a non-positive tet " + std::to_string(t) + " (midpoint rounding)");
  }
}

SurfaceMapResult Mapper::run() {
  SurfaceMapResult result;
  const std::size_t nv0 = mesh_.num_vertices();
  // Input must be VOLMAP-positive: the outward windings depend on it.
  for (std::size_t t = 0; t < mesh_.num_tets(); ++t) {
    const std::uint32_t* q = &mesh_.tets[4 * t];
    for (int k = 0; k < 4; ++k)
      if (q[k] >= nv0) throw Error(ErrorKind::BadInput, "", 0, "tet " + std::to_string(t) + " has an out-of-range vertex id");
    if (orient3d(&mesh_.xyz[3 * q[0]], &mesh_.xyz[3 * q[1]], &mesh_.xyz[3 * q[2]], &mesh_.xyz[3 * q[3]]) <= 0)
      throw Error(ErrorKind::BadInput, "", 0,
                  "tet " + std::to_string(t) + " is not VOLMAP-positive (orient3d <= 0): flip or repair the mesh first");
  }
  s_.xyz = mesh_.xyz;
  for (auto hf : boundary_half_faces(mesh_)) {
    const auto f = half_face_vertices(mesh_, hf);
    s_.tris.push_back({f[0], f[1], f[2]});
  }
  if (s_.tris.empty()) throw Error(ErrorKind::BadInput, "", 0, "the mesh has no boundary");
  s_.vtris.build(nv0, s_.tris);
  {
    std::size_t nb = 0;
    for (std::uint32_t v = 0; v < nv0; ++v) nb += !s_.vtris.empty(v);
    // Euler characteristic of the boundary: a closed genus-0 surface has V - E + F = 2 with E = 3F/2.
    const long long chi = static_cast<long long>(nb) - static_cast<long long>(3 * s_.tris.size() / 2) +
                          static_cast<long long>(s_.tris.size());
    if (chi != 2)
      throw Error(ErrorKind::BadInput, "", 0,
                  "the boundary surface is not a genus-0 sphere (Euler characteristic " + std::to_string(chi) + ")");
  }
  s_.build_adjacency();
  for (std::uint32_t v = 0; v < nv0; ++v)
    if (!s_.vtris.empty(v)) s_.ring(v);  // throws when not manifold
  for (int round = 0; round < subdivisions_; ++round) {  // coarse surfaces: split every boundary edge
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (const Tri& t : s_.tris)
      for (int k = 0; k < 3; ++k)
        if (t[k] < t[(k + 1) % 3]) edges.push_back({t[k], t[(k + 1) % 3]});
    for (auto& e : edges) s_.split_edge(e.first, e.second);
    s_.build_adjacency();
  }
  grow_vertex_arrays();
  arc_pool_.clear();
  arc_first_.assign(domain_.arcs.size(), 0);
  arc_size_.assign(domain_.arcs.size(), 0);
  assign_nodes(result);

  for (int arc : order_) {
    const DomainDiagonal* diag = nullptr;
    for (auto& g : domain_.diagonals)
      if (g.first_arc == arc) diag = &g;
    if (!diag) {
      const auto& da = domain_.arcs[arc];
      const auto path = trace(node_vertex_[da.from], node_vertex_[da.to], da.from, arc, da.to, arc,
                              "arc " + std::to_string(da.from) + "->" + std::to_string(da.to));
      commit_path(path, arc);
      split_chords(path);
      continue;
    }
    auto path = trace(node_vertex_[diag->from], node_vertex_[diag->to], diag->from, diag->first_arc, diag->to,
                      diag->second_arc,
                      "face diagonal " + std::to_string(diag->from) + "->" + std::to_string(diag->to));
    if (path.size() == 2) {  // a single edge: split it so the diagonal has a middle vertex
      const std::uint32_t m = s_.split_edge(path[0], path[1]);
      grow_vertex_arrays();
      s_.build_adjacency();
      path = {path[0], m, path[1]};
    }
    const std::size_t h = path.size() / 2;
    node_vertex_[diag->middle_node] = path[h];
    commit_path(std::vector<std::uint32_t>(path.begin(), path.begin() + h + 1), diag->first_arc);
    commit_path(std::vector<std::uint32_t>(path.begin() + h, path.end()), diag->second_arc);
    split_chords(path);
  }
  check_rotations();
  const std::vector<double> img = embed_charts();

  refine_tets(result.mesh);
  result.added_vertices = result.mesh.num_vertices() - nv0;
  result.node_vertices = node_vertex_;
  for (std::uint32_t v = 0; v < s_.num_vertices(); ++v) {
    if (s_.vtris.empty(v)) continue;
    result.map.vids.push_back(v);
    for (int k = 0; k < 3; ++k) result.map.xyz.push_back(img[3 * v + k]);
  }
  result.check = check_surface_map(result.mesh, result.map, &domain_);
  if (!result.check.ok) fail("the computed map fails the exact check: " + result.check.reason);
  return result;
}

}  // namespace

// Fallback tracing order: first a spanning tree of the nodes that have probes (BFS from node 0 over
// the arcs joining two such nodes, in domain order), then every other arc in the domain's order.
// With the traced graph connected and containing every node from the start, a correct rotation at
// every node makes the partial embedding equivalent to the domain's, so no later arc can find its
// face cut off (the reference order can trace a cycle, e.g. the octahedron's equator, with two
// still isolated nodes on the same side).
std::vector<int> spanning_tree_first_order(const Domain& d) {
  const std::vector<int> base = d.trace_order();
  std::vector<char> in_diag(d.arcs.size(), 0);
  for (auto& g : d.diagonals) in_diag[g.first_arc] = in_diag[g.second_arc] = 1;
  std::vector<char> reached(d.num_nodes(), 0), taken(d.arcs.size(), 0);
  std::vector<int> order, queue{0};
  reached[0] = 1;
  for (std::size_t q = 0; q < queue.size(); ++q)
    for (int a : base) {
      if (in_diag[a] || taken[a]) continue;
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

SurfaceMapResult map_surface_to_domain(const TetMeshData& mesh, const Domain& domain) {
  if (mesh.num_tets() == 0) throw Error(ErrorKind::BadInput, "", 0, "the mesh has no tets");
  // Attempts: the reference order; a spanning tree first; then, for surfaces too coarse for the
  // domain (fewer free vertices than nodes, no room between arcs), 1 and 2 rounds of splitting every
  // boundary edge first (spanning tree order).
  const std::vector<int> reference = domain.trace_order();
  const std::vector<int> tree = spanning_tree_first_order(domain);
  struct Attempt { const std::vector<int>* order; int subdivisions; };
  const Attempt attempts[] = {{&reference, 0}, {&tree, 0}, {&tree, 1}, {&tree, 2}};
  std::string errors;
  for (const auto& a : attempts) {
    if (a.order == &tree && a.subdivisions == 0 && tree == reference) continue;
    try {
      return Mapper(mesh, domain, *a.order, a.subdivisions).run();
    } catch (const Error& e) {
      if (e.kind() != ErrorKind::Failed) throw;
      if (errors.empty()) errors = e.what();
    }
  }
  fail(errors + " (also failed with a spanning tree traced first and after 1 and 2 rounds of boundary subdivision)");
}

SurfaceMapResult project_to_sphere(const SurfaceMapResult& in, const Point3& centre, double radius) {
  SurfaceMapResult out = in;
  for (std::size_t i = 0; i < out.map.size(); ++i) {
    double d[3], n2 = 0;
    for (int k = 0; k < 3; ++k) {
      d[k] = in.map.xyz[3 * i + k] - centre[k];
      n2 += d[k] * d[k];
    }
    const double n = std::sqrt(n2);
    if (!(n > 0)) fail("a map point coincides with the sphere centre");
    for (int k = 0; k < 3; ++k) out.map.xyz[3 * i + k] = centre[k] + radius * (d[k] / n);
  }
  // Exact re-check around the centre; where rounding made a cone non-positive, nudge the vertices
  // of the offending triangles by a few ulps (each coordinate) until all their triangles are positive.
  const auto faces = boundary_half_faces(out.mesh);
  std::vector<std::int32_t> slot(out.mesh.num_vertices(), -1);
  for (std::size_t i = 0; i < out.map.size(); ++i) slot[out.map.vids[i]] = static_cast<std::int32_t>(i);
  std::vector<Tri> tris;
  for (auto hf : faces) {
    const auto f = half_face_vertices(out.mesh, hf);
    tris.push_back({f[0], f[1], f[2]});
  }
  auto cone = [&](const Tri& t) {
    return orient3d(&out.map.xyz[3 * slot[t[0]]], &out.map.xyz[3 * slot[t[1]]], &out.map.xyz[3 * slot[t[2]]],
                    centre.data());
  };
  VertexTriangleLists vtris;  // built on the first non-positive cone
  bool have_vtris = false;
  for (std::uint32_t t = 0; t < tris.size(); ++t)
    if (cone(tris[t]) <= 0) {
      if (!have_vtris) {
        vtris.build(out.mesh.num_vertices(), tris);
        have_vtris = true;
      }
      for (auto v : tris[t]) {
        double* p = &out.map.xyz[3 * slot[v]];
        const Point3 orig{p[0], p[1], p[2]};
        auto all_positive = [&] {
          for (auto u : vtris[v])
            if (cone(tris[u]) <= 0) return false;
          return true;
        };
        bool fixed = all_positive();
        for (int step = 1; step <= 4 && !fixed; ++step)
          for (int dx = -1; dx <= 1 && !fixed; ++dx)
            for (int dy = -1; dy <= 1 && !fixed; ++dy)
              for (int dz = -1; dz <= 1 && !fixed; ++dz) {
                const int dir[3] = {dx, dy, dz};
                for (int k = 0; k < 3; ++k) {
                  p[k] = orig[k];
                  for (int r = 0; r < step; ++r)
                    if (dir[k]) p[k] = std::nextafter(p[k], dir[k] > 0 ? 1e300 : -1e300);
                }
                fixed = all_positive();
              }
        if (!fixed)
          for (int k = 0; k < 3; ++k) p[k] = orig[k];
        if (fixed) break;
      }
    }
  SurfaceMapCheckOptions opt;
  opt.override_kernel = true;
  opt.kernel = centre;
  opt.sphere_radius = radius;
  out.check = check_surface_map(out.mesh, out.map, nullptr, opt);
  if (!out.check.ok) fail("the projected sphere map fails the exact check: " + out.check.reason);
  return out;
}

}  // namespace volmap
