// self_intersection.cpp — exact triangle-surface self-intersection test (see self_intersection.hpp).
//
// Pipeline: validate ids/coordinates; flag degenerate triangles; find coincident vertices by sorting
// positions; build the flat bounding-volume hierarchy of box_tree.hpp over the triangle boxes;
// descend the tree against itself (split into tasks run in parallel) to every pair of triangles whose
// closed boxes overlap, once each, and run the exact pair test chosen by how many vertex ids the two
// share. Box tests compare doubles only (exact); every sign is an exact orient3d/orient2d, called unchecked
// inside one FpEnvironmentScope per block of work (one MXCSR check per block instead of per call;
// predicates.hpp).
//
// Adjacent pairs (most candidates on a mesh boundary: every triangle's boxes overlap its ~12
// neighbours') are first settled per vertex: a vertex whose triangles form one closed fan that an
// axis projection maps injectively (injective_fans) has no two triangles meeting beyond their
// shared vertex or edge, so pairs sharing such a vertex need no pair test.
//
// Why testing the six edges suffices for two closed triangles (non-adjacent case): their intersection
// is a compact convex set; an extreme point of it cannot lie in the relative interior of both
// triangles (a neighbourhood there would extend the intersection), so it lies on an edge of one
// triangle and in the other. Hence T1 ∩ T2 ≠ ∅ iff some edge of one meets the other triangle.
#include <volmap/check/self_intersection.hpp>

#include <volmap/check/box_tree.hpp>

#include <volmap/core/error.hpp>
#include <volmap/core/topology.hpp>
#include <volmap/predicates.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <string>

namespace volmap {
namespace {

// ---------------------------------------------------------------- 2D helpers on a projection ----
// A projection drops one coordinate: axes (kAxes[k][0], kAxes[k][1]).
constexpr int kAxes[3][2] = {{0, 1}, {1, 2}, {2, 0}};

struct P2 {
  double v[2];
};
inline P2 project(const double* p, int k) { return P2{{p[kAxes[k][0]], p[kAxes[k][1]]}}; }
inline int o2(const FpEnvironmentScope& fp, const P2& a, const P2& b, const P2& c) {
  return fp.orient2d(a.v, b.v, c.v);
}

// A projection under which triangle abc stays non-degenerate (so it is injective on abc's plane),
// or -1 when abc is degenerate. The candidate with the largest double normal component is tried
// first; the choice is then confirmed by the exact orient2d.
int projection_for(const FpEnvironmentScope& fp, const double* a, const double* b, const double* c,
                   int* orientation_out = nullptr) {
  const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
  const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
  const double n[3] = {std::fabs(uy * vz - uz * vy), std::fabs(uz * vx - ux * vz), std::fabs(ux * vy - uy * vx)};
  // Dropping coordinate 2 -> axes (0,1) = k 0; dropping 0 -> (1,2) = k 1; dropping 1 -> (2,0) = k 2.
  int order[3] = {0, 1, 2};
  const double weight[3] = {n[2], n[0], n[1]};
  std::sort(order, order + 3, [&](int x, int y) { return weight[x] > weight[y]; });
  for (int k : order) {
    const int o = o2(fp, project(a, k), project(b, k), project(c, k));
    if (o != 0) {
      if (orientation_out) *orientation_out = o;
      return k;
    }
  }
  return -1;
}

// x, known collinear with segment pq, lies on the closed segment pq.
inline bool on_segment_collinear(const P2& p, const P2& q, const P2& x) {
  for (int i = 0; i < 2; ++i) {
    if (x.v[i] < std::min(p.v[i], q.v[i]) || x.v[i] > std::max(p.v[i], q.v[i])) return false;
  }
  return true;
}

// Closed segments pq and ab share a point (both non-degenerate).
bool segments_intersect_2d(const FpEnvironmentScope& fp, const P2& p, const P2& q, const P2& a, const P2& b) {
  const int d1 = o2(fp, p, q, a), d2 = o2(fp, p, q, b);
  if ((d1 > 0 && d2 > 0) || (d1 < 0 && d2 < 0)) return false;
  const int d3 = o2(fp, a, b, p), d4 = o2(fp, a, b, q);
  if ((d3 > 0 && d4 > 0) || (d3 < 0 && d4 < 0)) return false;
  if (d1 != 0 || d2 != 0) return true;  // not all collinear: the straddles above imply a crossing
  // All four collinear: overlap iff an endpoint of one lies on the other.
  return on_segment_collinear(p, q, a) || on_segment_collinear(p, q, b) || on_segment_collinear(a, b, p) ||
         on_segment_collinear(a, b, q);
}

// x in the closed triangle abc of orientation o (!= 0).
inline bool point_in_triangle_2d(const FpEnvironmentScope& fp, const P2& a, const P2& b, const P2& c, int o,
                                 const P2& x) {
  return o * o2(fp, a, b, x) >= 0 && o * o2(fp, b, c, x) >= 0 && o * o2(fp, c, a, x) >= 0;
}

// x in the closed cone at apex a spanned by rays ab and ac (o = orient2d(a,b,c) != 0); x != a.
inline bool point_in_cone_2d(const FpEnvironmentScope& fp, const P2& a, const P2& b, const P2& c, int o, const P2& x) {
  return o * o2(fp, a, b, x) >= 0 && o * o2(fp, a, x, c) >= 0;
}

// Closed segment pq meets the closed triangle abc, all coplanar, in projection k where abc has
// orientation o.
bool coplanar_segment_triangle(const FpEnvironmentScope& fp, const double* p, const double* q, const double* a,
                               const double* b, const double* c, int k, int o) {
  const P2 P = project(p, k), Q = project(q, k), A = project(a, k), B = project(b, k), C = project(c, k);
  if (point_in_triangle_2d(fp, A, B, C, o, P) || point_in_triangle_2d(fp, A, B, C, o, Q)) return true;
  const bool pq_degenerate = P.v[0] == Q.v[0] && P.v[1] == Q.v[1];
  if (pq_degenerate) return false;  // a point outside the triangle
  return segments_intersect_2d(fp, P, Q, A, B) || segments_intersect_2d(fp, P, Q, B, C) ||
         segments_intersect_2d(fp, P, Q, C, A);
}

inline bool strictly_same_side(int s0, int s1, int s2) {
  return (s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0);
}

// Segment pq against non-degenerate triangle abc, given op = orient3d(a,b,c,p), oq = orient3d(a,b,c,q).
bool segment_triangle_with_signs(const FpEnvironmentScope& fp, const double* p, const double* q, const double* a,
                                 const double* b, const double* c, int op, int oq) {
  if ((op > 0 && oq > 0) || (op < 0 && oq < 0)) return false;
  if (op == 0 && oq == 0) {
    int o = 0;
    const int k = projection_for(fp, a, b, c, &o);
    if (k < 0) return false;  // caller guarantees non-degenerate; be safe
    return coplanar_segment_triangle(fp, p, q, a, b, c, k, o);
  }
  // The line pq is transversal to the plane and the segment reaches it: it meets the closed triangle
  // iff the crossing point is on the inner side (or on) of all three edge lines.
  const int s1 = fp.orient3d(p, q, a, b), s2 = fp.orient3d(p, q, b, c), s3 = fp.orient3d(p, q, c, a);
  const bool has_pos = s1 > 0 || s2 > 0 || s3 > 0;
  const bool has_neg = s1 < 0 || s2 < 0 || s3 < 0;
  return !(has_pos && has_neg);
}

// ---------------------------------------------------------------- pair tests by shared ids -----
// t = (a,b,c), u = (a,b,d): share edge ab.
bool shared_edge_pair(const FpEnvironmentScope& fp, const double* a, const double* b, const double* c,
                      const double* d) {
  if (fp.orient3d(a, b, c, d) != 0) return false;  // distinct planes meet in line ab only
  int o = 0;
  const int k = projection_for(fp, a, b, c, &o);
  if (k < 0) return false;
  const int od = o2(fp, project(a, k), project(b, k), project(d, k));
  return o * od > 0;  // d on c's side of ab: the triangles overlap (a fold)
}

// t = (a,b,c), u = (a,d,e): share vertex a only.
bool shared_vertex_pair(const FpEnvironmentScope& fp, const double* a, const double* b, const double* c,
                        const double* d, const double* e) {
  const int sd = fp.orient3d(a, b, c, d), se = fp.orient3d(a, b, c, e);
  if ((sd > 0 && se > 0) || (sd < 0 && se < 0)) return false;  // u touches t's plane only at a
  if (sd == 0 || se == 0) {
    int o = 0;
    const int k = projection_for(fp, a, b, c, &o);
    if (k < 0) return false;
    const P2 A = project(a, k), B = project(b, k), C = project(c, k), D = project(d, k), E = project(e, k);
    if (sd == 0 && se == 0) {
      // Coplanar: the corner cones at a overlap beyond a iff a bounding ray of one lies in the other.
      const int ou = o2(fp, A, D, E);
      if (ou == 0) return false;  // u degenerate: excluded by the caller
      return point_in_cone_2d(fp, A, B, C, o, D) || point_in_cone_2d(fp, A, B, C, o, E) ||
             point_in_cone_2d(fp, A, D, E, ou, B) || point_in_cone_2d(fp, A, D, E, ou, C);
    }
    // u meets t's plane in segment a-d (or a-e): it enters t iff that ray is in t's corner cone.
    return point_in_cone_2d(fp, A, B, C, o, sd == 0 ? D : E);
  }
  // d and e strictly on opposite sides: u meets t's plane in segment aX, X on de. aX enters t iff X
  // lies in t's corner cone at a, i.e. on the inner side (or on) both edge lines through a. For a
  // transversal line de, orient3d(d,e,p,q) has the sign of se times the side of X w.r.t. line pq
  // (identity: orient3d(d,e,a,b) + orient3d(d,e,b,c) + orient3d(d,e,c,a) = orient3d(a,b,c,e) -
  // orient3d(a,b,c,d)); testing both signs against se rules out the vertical angle.
  const int s1 = fp.orient3d(d, e, a, b), s2 = fp.orient3d(d, e, c, a);
  return s1 * se >= 0 && s2 * se >= 0;
}

// ---------------------------------------------------------------- injective vertex fans -------
// The fan of vertex a: its triangles chained into one closed cycle (VertexFan, topology.hpp), ring
// b_0 -> b_1 -> ... -> b_0, triangle i being (a, b_{i+1}, b_i). Projected along axis k, the fan is
// injective when every projected triangle has the same strict orientation s and the wedges at A wind
// once around A. Then two of its triangles meet only in their shared edge a-b_i or in a: their
// projections meet only there, and the projection is injective on each triangle. The winding number
// is the number of half-open wedges [B_i, B_{i+1}) that contain the direction of B_0 (each wedge is
// below a half turn, so the opposite direction is in none of them): exactly one, wedge 0, when it
// winds once.

// The fan's ring (b_0 .. b_{m−1}, triangles (a, b_{i+1}, b_i)) projected along axis k is injective
// (see above).
bool fan_injective_in(const FpEnvironmentScope& fp, const double* xyz, std::uint32_t a,
                      const std::vector<std::uint32_t>& ring, int k) {
  auto P = [&](std::uint32_t v) { return project(xyz + 3 * std::size_t(v), k); };
  const P2 A = P(a), B0 = P(ring[0]);
  const std::size_t m = ring.size();
  const int s = o2(fp, A, B0, P(ring[1]));
  if (s == 0) return false;
  // side[i] = s·orient2d(A, B_i, B_0); wedge i holds B_0's direction when side[i] ≥ 0 and
  // s·orient2d(A, B_0, B_{i+1}) = −side[i+1] > 0.
  int winding = 0, side_i = 0;  // side[0] = 0
  for (std::size_t i = 0; i < m; ++i) {
    const P2 Bi = P(ring[i]), Bn = P(ring[(i + 1) % m]);
    if (i > 0 && o2(fp, A, Bi, Bn) != s) return false;
    const int side_next = i + 1 < m ? s * o2(fp, A, Bn, B0) : 0;
    if (side_i >= 0 && side_next < 0) ++winding;
    side_i = side_next;
  }
  return winding == 1;
}

// Per vertex, 1 when its fan is injective under the axis projection closest to the fan's mean
// normal (doubles choose the axis; the exact test decides), else 0.
std::vector<std::uint8_t> injective_fans(const double* xyz, std::size_t num_vertices, const std::uint32_t* tris,
                                         std::size_t num_tris, bool parallel) {
  std::vector<std::uint32_t> offsets(num_vertices + 2, 0);
  for (std::size_t i = 0; i < 3 * num_tris; ++i) ++offsets[std::size_t(tris[i]) + 2];
  for (std::size_t v = 2; v < offsets.size(); ++v) offsets[v] += offsets[v - 1];
  std::vector<std::uint32_t> incident(3 * num_tris);
  for (std::size_t i = 0; i < 3 * num_tris; ++i) incident[offsets[std::size_t(tris[i]) + 1]++] = std::uint32_t(i / 3);
  std::vector<std::uint8_t> injective(num_vertices, 0);
  auto judge = [&](std::size_t begin, std::size_t end) {
    const FpEnvironmentScope fp;
    VertexFan fan;
    for (std::size_t v = begin; v < end; ++v) {
      const std::uint32_t a = std::uint32_t(v);
      if (!fan.close(tris, a, incident.data() + offsets[v], offsets[v + 1] - offsets[v])) continue;
      const std::vector<std::uint32_t>& ring = fan.ring();
      const double* pa = xyz + 3 * v;
      double normal[3] = {0, 0, 0};  // Σ (b_{i+1} − a) × (b_i − a): the fan's winding
      const std::size_t m = ring.size();
      for (std::size_t i = 0; i < m; ++i) {
        const double* p = xyz + 3 * std::size_t(ring[(i + 1) % m]);
        const double* q = xyz + 3 * std::size_t(ring[i]);
        const double u[3] = {p[0] - pa[0], p[1] - pa[1], p[2] - pa[2]};
        const double w[3] = {q[0] - pa[0], q[1] - pa[1], q[2] - pa[2]};
        normal[0] += u[1] * w[2] - u[2] * w[1];
        normal[1] += u[2] * w[0] - u[0] * w[2];
        normal[2] += u[0] * w[1] - u[1] * w[0];
      }
      // Dropping coordinate 2 is projection k 0, dropping 0 is k 1, dropping 1 is k 2 (kAxes).
      const double weight[3] = {std::fabs(normal[2]), std::fabs(normal[0]), std::fabs(normal[1])};
      const int k = weight[0] >= weight[1] ? (weight[0] >= weight[2] ? 0 : 2) : (weight[1] >= weight[2] ? 1 : 2);
      injective[v] = fan_injective_in(fp, xyz, a, ring, k) ? 1 : 0;
    }
  };
  if (parallel)
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_vertices, 1024),
                      [&](const tbb::blocked_range<std::size_t>& r) { judge(r.begin(), r.end()); });
  else
    judge(0, num_vertices);
  return injective;
}

// The triangles in the tree's position order (the order its leaves are scanned in), each with the
// bits of its corners whose fan is injective: the pair visits read them contiguously.
struct PositionedTriangles {
  std::vector<std::array<std::uint32_t, 3>> corners;
  std::vector<std::uint8_t> injective_corners;  // bit k: corner k's fan is injective
  PositionedTriangles(const std::uint32_t* tris, const std::vector<std::uint32_t>& order,
                      const std::vector<std::uint8_t>& injective_fan)
      : corners(order.size()), injective_corners(order.size(), 0) {
    for (std::size_t pos = 0; pos < order.size(); ++pos) {
      const std::uint32_t* t = tris + 3 * std::size_t(order[pos]);
      for (int k = 0; k < 3; ++k) {
        corners[pos][k] = t[k];
        injective_corners[pos] |= std::uint8_t(injective_fan[t[k]] << k);
      }
    }
  }
  // The triangles at positions i and j share a vertex whose fan is injective: they meet only where
  // they are adjacent.
  bool settled_by_fan(std::uint32_t i, std::uint32_t j) const {
    const std::array<std::uint32_t, 3>& t = corners[i];
    const std::array<std::uint32_t, 3>& u = corners[j];
    for (int k = 0; k < 3; ++k)
      if (((injective_corners[i] >> k) & 1) && (t[k] == u[0] || t[k] == u[1] || t[k] == u[2])) return true;
    return false;
  }
};

// Per-block findings, merged in block order so the reported lists are deterministic.
struct BlockResult {
  std::size_t pairs = 0;
  std::size_t candidates = 0;
  std::vector<TrianglePair> smallest;
};

inline bool pair_less(const TrianglePair& x, const TrianglePair& y) {
  return x.first != y.first ? x.first < y.first : x.second < y.second;
}

void keep_smallest(std::vector<TrianglePair>& list, std::size_t cap) {
  std::sort(list.begin(), list.end(), pair_less);
  if (list.size() > cap) list.resize(cap);
}


// ---------------------------------------------------------------- tree-against-itself traversal
// Every pair of items whose boxes overlap is found once by descending the tree against itself:
// a node's own pairs are its children's own pairs plus the pairs across them, and two nodes whose
// boxes are disjoint have no pair across them. A task is one such unit of work, `self` (pairs inside
// node a) or `across` (pairs with one item in a, one in b).
struct NodeTask {
  std::uint32_t a, b;
  bool self;
};

inline std::uint32_t node_size(const BoxTree::Node& n) { return n.end - n.begin; }

// How a task splits. kLeaves: both nodes are leaves, so its pairs are enumerated item by item;
// otherwise `count` subtasks cover its pairs (0 when the two nodes' boxes are disjoint): a self task
// splits into its children's own pairs and the pairs across them, an across task into the halves of
// its larger node.
struct TaskSplit {
  bool leaves = false;
  int count = 0;
  NodeTask parts[3];
};

TaskSplit split_task(const BoxTree& tree, const NodeTask& task) {
  TaskSplit split;
  const BoxTree::Node& a = tree.nodes[task.a];
  if (task.self) {
    if (a.left == 0) {
      split.leaves = true;
    } else {
      split.count = 3;
      split.parts[0] = {a.left, a.left, true};
      split.parts[1] = {a.left + 1, a.left + 1, true};
      split.parts[2] = {a.left, a.left + 1, false};
    }
    return split;
  }
  const BoxTree::Node& b = tree.nodes[task.b];
  if (!boxes_overlap(a.box, b.box)) return split;
  if (a.left == 0 && b.left == 0) {
    split.leaves = true;
    return split;
  }
  split.count = 2;
  if (b.left == 0 || (a.left != 0 && node_size(a) >= node_size(b))) {
    split.parts[0] = {a.left, task.b, false};
    split.parts[1] = {a.left + 1, task.b, false};
  } else {
    split.parts[0] = {task.a, b.left, false};
    split.parts[1] = {task.a, b.left + 1, false};
  }
  return split;
}

// Expands the root's task breadth-first into at least `wanted` tasks (fewer when the tree runs out),
// in a fixed order, so the parallel drivers' results merge deterministically.
std::vector<NodeTask> split_traversal(const BoxTree& tree, std::size_t wanted) {
  std::vector<NodeTask> tasks;
  if (tree.nodes.empty()) return tasks;
  tasks.push_back({0, 0, true});
  bool expanded = true;
  while (expanded && tasks.size() < wanted) {
    std::vector<NodeTask> next;
    next.reserve(3 * tasks.size());
    expanded = false;
    for (const NodeTask& task : tasks) {
      const TaskSplit split = split_task(tree, task);
      if (split.leaves) next.push_back(task);
      next.insert(next.end(), split.parts, split.parts + split.count);
      expanded = expanded || split.count > 0;
    }
    tasks.swap(next);
  }
  return tasks;
}

// The tree's leaf size here: leaves are tested against each other in groups of four float lanes, so
// larger leaves than a query tree's pay: fewer node pairs for the same lanes (the whole test, serial,
// on the viewer bunny's boundary: leaves of 8 17.3 ms, 16 15.5, 24 14.3, 32 15.2).
constexpr std::uint32_t kLeafSize = 24;
static_assert(kLeafSize % 4 == 0 && kLeafSize <= 32, "leaf_hits tests a leaf in groups of four lanes");

// The leaf boxes by position again, as floats rounded outwards (lo down, hi up), one array per bound,
// padded by a leaf of empty boxes: a box is tested against a whole leaf at once (leaf_hits). Float
// boxes contain the double ones, so they only pre-select; each hit is confirmed by the exact double
// test, and the pairs found are exactly the double boxes' overlapping pairs. This holds in any
// floating-point mode: the conversion is monotone whatever the rounding or flushing, and each bound
// is moved outwards from the converted value: a lower bound ≤ an upper bound in doubles stays so in
// floats. Items marked `skip` (degenerate triangles, which pair with nothing) get empty boxes and are
// never visited.
struct FloatLeafBoxes {
  std::vector<float> bound[6];  // lo x, lo y, lo z, hi x, hi y, hi z
  FloatLeafBoxes(const std::vector<Box3>& boxes, const std::vector<std::uint8_t>& skip) {
    for (int k = 0; k < 6; ++k) bound[k].assign(boxes.size() + kLeafSize, k < 3 ? kInf : -kInf);
    for (std::size_t i = 0; i < boxes.size(); ++i)
      for (int k = 0; k < 3 && !skip[i]; ++k) {
        bound[k][i] = round_down(boxes[i].lo[k]);
        bound[k + 3][i] = round_up(boxes[i].hi[k]);
      }
  }
  static constexpr float kInf = std::numeric_limits<float>::infinity();
  static float round_down(double x) {
    const float f = static_cast<float>(x);
    return static_cast<double>(f) > x ? std::nextafter(f, -kInf) : f;
  }
  static float round_up(double x) {
    const float f = static_cast<float>(x);
    return static_cast<double>(f) < x ? std::nextafter(f, kInf) : f;
  }
};

// Bit j set: the float box at position i overlaps the float box at position first + j
// (j < kLeafSize).
inline std::uint32_t leaf_hits(const FloatLeafBoxes& f, std::uint32_t i, std::uint32_t first) {
  std::uint32_t hits = 0;
#if defined(__SSE2__)
  const __m128 own_lo[3] = {_mm_set1_ps(f.bound[0][i]), _mm_set1_ps(f.bound[1][i]), _mm_set1_ps(f.bound[2][i])};
  const __m128 own_hi[3] = {_mm_set1_ps(f.bound[3][i]), _mm_set1_ps(f.bound[4][i]), _mm_set1_ps(f.bound[5][i])};
  for (std::uint32_t group = 0; group < kLeafSize; group += 4) {
    __m128 inside = _mm_castsi128_ps(_mm_set1_epi32(-1));
    for (int k = 0; k < 3; ++k) {
      const __m128 lo = _mm_loadu_ps(f.bound[k].data() + first + group);
      const __m128 hi = _mm_loadu_ps(f.bound[k + 3].data() + first + group);
      inside = _mm_and_ps(inside, _mm_and_ps(_mm_cmple_ps(own_lo[k], hi), _mm_cmple_ps(lo, own_hi[k])));
    }
    hits |= std::uint32_t(_mm_movemask_ps(inside)) << group;
  }
#else
  for (std::uint32_t j = 0; j < kLeafSize; ++j) {
    bool inside = true;
    for (int k = 0; k < 3; ++k)
      inside = inside && f.bound[k][i] <= f.bound[k + 3][first + j] && f.bound[k][first + j] <= f.bound[k + 3][i];
    hits |= std::uint32_t(inside) << j;
  }
#endif
  return hits;
}

// Calls visit(position, position) for every pair of distinct items under the task whose leaf boxes
// overlap (items with empty float boxes never).
template <class Visit>
void run_traversal(const BoxTree& tree, const FloatLeafBoxes& float_boxes, const NodeTask& root, Visit&& visit) {
  NodeTask stack[192];  // each split adds at most 2 net entries per tree level, of depth below 32
  int top = 0;
  stack[top++] = root;
  while (top > 0) {
    const NodeTask task = stack[--top];
    const TaskSplit split = split_task(tree, task);
    for (int k = split.count; k-- > 0;) stack[top++] = split.parts[k];  // the first part on top
    if (!split.leaves) continue;
    const BoxTree::Node& a = tree.nodes[task.a];
    const BoxTree::Node& b = tree.nodes[task.b];  // the same node for a self task
    const std::uint32_t in_b = std::uint32_t((std::uint64_t(1) << (b.end - b.begin)) - 1);
    for (std::uint32_t i = a.begin; i < a.end; ++i) {
      // A self task pairs i with the later items only.
      std::uint32_t hits = leaf_hits(float_boxes, i, b.begin) & in_b;
      if (task.self) hits &= std::uint32_t(~std::uint64_t(0) << (i - a.begin + 1));
      while (hits != 0) {
        const std::uint32_t j = b.begin + std::uint32_t(__builtin_ctz(hits));
        hits &= hits - 1;
        if (boxes_overlap(tree.leaf_boxes[i], tree.leaf_boxes[j])) visit(i, j);
      }
    }
  }
}

constexpr std::size_t kParallelTasks = 64;
}  // namespace

// ------------------------------------------------------------------ public primitives ----------
// Each public primitive checks the floating-point environment once (FpEnvironmentScope) and runs
// the unchecked predicates; the driver below opens one scope per block of queries instead.
namespace {

bool triangles_intersect_in(const FpEnvironmentScope& fp, const double* a, const double* b, const double* c,
                            const double* d, const double* e, const double* f) {
  const int sd = fp.orient3d(a, b, c, d), se = fp.orient3d(a, b, c, e), sf = fp.orient3d(a, b, c, f);
  if (strictly_same_side(sd, se, sf)) return false;
  const int sa = fp.orient3d(d, e, f, a), sb = fp.orient3d(d, e, f, b), sc = fp.orient3d(d, e, f, c);
  if (strictly_same_side(sa, sb, sc)) return false;
  return segment_triangle_with_signs(fp, a, b, d, e, f, sa, sb) ||
         segment_triangle_with_signs(fp, b, c, d, e, f, sb, sc) ||
         segment_triangle_with_signs(fp, c, a, d, e, f, sc, sa) ||
         segment_triangle_with_signs(fp, d, e, a, b, c, sd, se) ||
         segment_triangle_with_signs(fp, e, f, a, b, c, se, sf) ||
         segment_triangle_with_signs(fp, f, d, a, b, c, sf, sd);
}

bool triangle_pair_intersects_in(const FpEnvironmentScope& fp, const double* xyz, const std::uint32_t* t,
                                 const std::uint32_t* u) {
  // Which corners of t appear in u.
  int in_u[3] = {-1, -1, -1};
  int shared = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (t[i] == u[j]) {
        in_u[i] = j;
        ++shared;
      }
  auto P = [&](std::uint32_t v) { return xyz + 3 * std::size_t(v); };
  if (shared >= 3) return true;  // the same triangle twice
  if (shared == 0) return triangles_intersect_in(fp, P(t[0]), P(t[1]), P(t[2]), P(u[0]), P(u[1]), P(u[2]));
  if (shared == 2) {
    int c = 0;
    while (in_u[c] >= 0) ++c;  // t's corner not in u
    int d = 0;
    while (u[d] == t[(c + 1) % 3] || u[d] == t[(c + 2) % 3]) ++d;
    return shared_edge_pair(fp, P(t[(c + 1) % 3]), P(t[(c + 2) % 3]), P(t[c]), P(u[d]));
  }
  int a = 0;
  while (in_u[a] < 0) ++a;
  const int j = in_u[a];
  return shared_vertex_pair(fp, P(t[a]), P(t[(a + 1) % 3]), P(t[(a + 2) % 3]), P(u[(j + 1) % 3]), P(u[(j + 2) % 3]));
}

}  // namespace

bool triangle_is_degenerate(const double* a, const double* b, const double* c) {
  const FpEnvironmentScope fp;
  return projection_for(fp, a, b, c) < 0;
}

bool segment_intersects_triangle(const double* p, const double* q, const double* a, const double* b,
                                 const double* c) {
  const FpEnvironmentScope fp;
  return segment_triangle_with_signs(fp, p, q, a, b, c, fp.orient3d(a, b, c, p), fp.orient3d(a, b, c, q));
}

bool triangles_intersect(const double* a, const double* b, const double* c, const double* d, const double* e,
                         const double* f) {
  const FpEnvironmentScope fp;
  return triangles_intersect_in(fp, a, b, c, d, e, f);
}

bool triangle_pair_intersects(const double* xyz, const std::uint32_t* t, const std::uint32_t* u) {
  const FpEnvironmentScope fp;
  return triangle_pair_intersects_in(fp, xyz, t, u);
}

// ------------------------------------------------------------------ driver ---------------------
namespace {

// Whether two of the vertices sit at the same point (==, so −0 and +0 coincide): one pass over an
// open-addressing table of their positions (the report below sorts, which only a surface with such a
// pair pays).
bool any_coincident(const double* xyz, const std::vector<std::uint32_t>& vertices) {
  std::size_t size = 16;
  while (size < 2 * vertices.size()) size *= 2;
  constexpr std::uint32_t kEmpty = 0xFFFFFFFFu;
  std::vector<std::uint32_t> table(size, kEmpty);
  for (const std::uint32_t v : vertices) {
    const double* p = xyz + 3 * std::size_t(v);
    std::uint64_t h = 0x9E3779B97F4A7C15ull;
    for (int k = 0; k < 3; ++k) {
      const double c = p[k] + 0.0;  // −0 → +0: equal coordinates hash alike
      std::uint64_t bits;
      std::memcpy(&bits, &c, sizeof bits);
      h = (h ^ bits) * 0xFF51AFD7ED558CCDull;
      h ^= h >> 32;
    }
    for (std::size_t slot = h & (size - 1);; slot = (slot + 1) & (size - 1)) {
      if (table[slot] == kEmpty) {
        table[slot] = v;
        break;
      }
      if (points_equal(xyz + 3 * std::size_t(table[slot]), p)) return true;
    }
  }
  return false;
}

// Coincident vertices, reported in position order: sort the ids by position; equal neighbours
// coincide.
void report_coincident(const double* xyz, std::vector<std::uint32_t> vertices, std::size_t cap,
                       SelfIntersectionResult& result) {
  std::sort(vertices.begin(), vertices.end(), [&](std::uint32_t x, std::uint32_t y) {
    const double *p = xyz + 3 * std::size_t(x), *q = xyz + 3 * std::size_t(y);
    if (p[0] != q[0]) return p[0] < q[0];
    if (p[1] != q[1]) return p[1] < q[1];
    if (p[2] != q[2]) return p[2] < q[2];
    return x < y;
  });
  for (std::size_t i = 1; i < vertices.size(); ++i) {
    const double *p = xyz + 3 * std::size_t(vertices[i - 1]), *q = xyz + 3 * std::size_t(vertices[i]);
    if (points_equal(p, q)) {
      ++result.coincident_vertices;
      if (result.first_coincident.size() < cap) result.first_coincident.emplace_back(vertices[i - 1], vertices[i]);
    }
  }
}

}  // namespace

SelfIntersectionResult find_self_intersections(const double* xyz, std::size_t num_vertices,
                                               const std::uint32_t* tris, std::size_t num_tris,
                                               const SelfIntersectionOptions& options) {
  SelfIntersectionResult result;
  if (num_tris >= (std::size_t(1) << 32))
    throw Error(ErrorKind::Unsupported, "self-intersection test: more than 2^32 triangles");
  // Validate ids and referenced coordinates.
  std::vector<std::uint8_t> referenced(num_vertices, 0);
  for (std::size_t i = 0; i < 3 * num_tris; ++i) {
    if (tris[i] >= num_vertices)
      throw Error(ErrorKind::BadInput, "triangle " + std::to_string(i / 3) + " refers to vertex " + std::to_string(tris[i]) +
                      " but there are " + std::to_string(num_vertices) + " vertices");
    referenced[tris[i]] = 1;
  }
  std::vector<std::uint32_t> used;
  used.reserve(num_vertices);
  for (std::size_t v = 0; v < num_vertices; ++v) {
    if (!referenced[v]) continue;
    const double* p = xyz + 3 * v;
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw Error(ErrorKind::BadInput, "vertex " + std::to_string(v) + " has a non-finite coordinate");
    used.push_back(std::uint32_t(v));
  }
  const std::size_t cap = options.max_reported;
  const bool parallel = options.parallel && num_tris >= 2048;

  if (any_coincident(xyz, used)) report_coincident(xyz, used, cap, result);

  // Boxes and degenerate triangles.
  std::vector<Box3> boxes(num_tris);
  std::vector<std::uint8_t> degenerate(num_tris, 0);
  auto prepare = [&](std::size_t begin, std::size_t end) {
    const FpEnvironmentScope fp;  // per block: MXCSR is per thread
    for (std::size_t t = begin; t < end; ++t) {
      const std::uint32_t* tri = tris + 3 * t;
      const double *a = xyz + 3 * std::size_t(tri[0]), *b = xyz + 3 * std::size_t(tri[1]), *c = xyz + 3 * std::size_t(tri[2]);
      Box3& box = boxes[t];
      for (int k = 0; k < 3; ++k) {
        box.lo[k] = std::min({a[k], b[k], c[k]});
        box.hi[k] = std::max({a[k], b[k], c[k]});
      }
      degenerate[t] = (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] || projection_for(fp, a, b, c) < 0) ? 1 : 0;
    }
  };
  if (parallel)
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_tris, 2048),
                      [&](const tbb::blocked_range<std::size_t>& r) { prepare(r.begin(), r.end()); });
  else
    prepare(0, num_tris);
  for (std::size_t t = 0; t < num_tris; ++t) {
    if (!degenerate[t]) continue;
    ++result.degenerate_triangles;
    if (result.first_degenerate.size() < cap) result.first_degenerate.push_back(std::uint32_t(t));
  }

  const std::vector<std::uint8_t> injective_fan = injective_fans(xyz, num_vertices, tris, num_tris, parallel);
  const BoxTree bvh = build_box_tree(boxes, kLeafSize);
  std::vector<std::uint8_t> degenerate_at(num_tris);  // by position
  for (std::size_t pos = 0; pos < num_tris; ++pos) degenerate_at[pos] = degenerate[bvh.order[pos]];
  const FloatLeafBoxes float_boxes(bvh.leaf_boxes, degenerate_at);
  const PositionedTriangles positioned(tris, bvh.order, injective_fan);
  const std::vector<NodeTask> tasks = split_traversal(bvh, parallel ? kParallelTasks : 1);
  std::vector<BlockResult> blocks(tasks.size());
  auto run_task = [&](std::size_t k) {
    const FpEnvironmentScope fp;  // one MXCSR check per task (per thread)
    BlockResult& out = blocks[k];
    auto visit_pair = [&](std::uint32_t i, std::uint32_t j) {  // positions; degenerate ones never come
      ++out.candidates;
      if (positioned.settled_by_fan(i, j)) return;
      const std::uint32_t t = bvh.order[i], u = bvh.order[j];
      const std::uint32_t lo = std::min(t, u), hi = std::max(t, u);
      if (!triangle_pair_intersects_in(fp, xyz, tris + 3 * std::size_t(lo), tris + 3 * std::size_t(hi))) return;
      ++out.pairs;
      if (cap > 0) {
        out.smallest.push_back(TrianglePair{lo, hi});
        if (out.smallest.size() >= 2 * cap) keep_smallest(out.smallest, cap);
      }
    };
    run_traversal(bvh, float_boxes, tasks[k], visit_pair);
    keep_smallest(out.smallest, cap);
  };
  if (parallel)
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tasks.size(), 1),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t k = r.begin(); k < r.end(); ++k) run_task(k);
                      });
  else
    for (std::size_t k = 0; k < tasks.size(); ++k) run_task(k);

  for (const BlockResult& block : blocks) {
    result.intersecting_pairs += block.pairs;
    result.candidate_pairs += block.candidates;
    result.first_pairs.insert(result.first_pairs.end(), block.smallest.begin(), block.smallest.end());
  }
  keep_smallest(result.first_pairs, cap);  // each block kept its smallest, so the union holds the global ones
  return result;
}

}  // namespace volmap
