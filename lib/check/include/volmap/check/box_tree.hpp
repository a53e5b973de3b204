// volmap/check/box_tree.hpp — a flat bounding-volume hierarchy over axis-aligned boxes (one per item,
// e.g. a triangle's bounding box), for "which items may touch this box?" queries.
// Conventions: boxes are closed (touching boxes overlap); comparisons are plain double comparisons,
// which are exact, so a query never misses an item whose box touches the query box. Items are ordered
// along a Morton (Z-order) curve of their box centres; the tree halves that order top-down (leaves of
// at most a leaf size of items), so `order` is the items' position along the curve and every node
// covers a contiguous range [begin, end) of positions. Nodes live in one array; a parent comes before
// its children, the children of an inner node are `left` and `left + 1`, and `left == 0` marks a leaf.
// kBoxTreeLeafSize is the default leaf size (build_box_tree can take another).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace volmap {

struct Box3 {
  double lo[3], hi[3];
};

inline bool boxes_overlap(const Box3& x, const Box3& y) {
  return x.lo[0] <= y.hi[0] && y.lo[0] <= x.hi[0] && x.lo[1] <= y.hi[1] && y.lo[1] <= x.hi[1] &&
         x.lo[2] <= y.hi[2] && y.lo[2] <= x.hi[2];
}

inline constexpr std::uint32_t kBoxTreeLeafSize = 8;

struct BoxTree {
  struct Node {
    Box3 box;
    std::uint32_t begin, end;  // the node's items are order[begin, end)
    std::uint32_t left;        // inner: left child (right = left + 1); leaf: 0
  };
  std::vector<Node> nodes;
  std::vector<std::uint32_t> order;  // item ids by position
  std::vector<Box3> leaf_boxes;      // the items' boxes by position (cache-friendly leaf scans)

  // Calls visit(item) for every item whose box overlaps `query` (in position order).
  template <class Visit>
  void for_each_overlapping(const Box3& query, Visit&& visit) const {
    if (nodes.empty()) return;
    std::uint32_t stack[96];  // the depth is about log2(items / leaf size): far below 96
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes[stack[--top]];
      if (!boxes_overlap(node.box, query)) continue;
      if (node.left != 0) {
        stack[top++] = node.left;
        stack[top++] = node.left + 1;
        continue;
      }
      for (std::uint32_t i = node.begin; i < node.end; ++i)
        if (boxes_overlap(leaf_boxes[i], query)) visit(order[i]);
    }
  }

  // Calls visit(item) for every item whose box, grown by `pad` on every side, meets the segment pq
  // (slab test in double: the padding absorbs its rounding, so an item whose box the segment
  // touches is never skipped when pad exceeds a few ulps of the coordinates).
  template <class Visit>
  void for_each_near_segment(const double* p, const double* q, double pad, Visit&& visit) const {
    if (nodes.empty()) return;
    const double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    auto meets = [&](const Box3& b) {
      double t0 = 0, t1 = 1;
      for (int k = 0; k < 3; ++k) {
        const double lo = b.lo[k] - pad, hi = b.hi[k] + pad;
        if (d[k] == 0) {
          if (p[k] < lo || p[k] > hi) return false;
          continue;
        }
        double a = (lo - p[k]) / d[k], c = (hi - p[k]) / d[k];
        if (a > c) std::swap(a, c);
        t0 = a > t0 ? a : t0;
        t1 = c < t1 ? c : t1;
        if (t0 > t1) return false;
      }
      return true;
    };
    std::uint32_t stack[96];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes[stack[--top]];
      if (!meets(node.box)) continue;
      if (node.left != 0) {
        stack[top++] = node.left;
        stack[top++] = node.left + 1;
        continue;
      }
      for (std::uint32_t i = node.begin; i < node.end; ++i)
        if (meets(leaf_boxes[i])) visit(order[i]);
    }
  }
};

// Builds the tree over boxes[0..n): O(n log n) (one sort of 64-bit Morton keys), the rest O(n).
// Leaves hold at most leaf_size items (0 counts as 1): small leaves suit single queries, larger ones
// a tree tested against itself leaf by leaf in vector lanes.
BoxTree build_box_tree(const std::vector<Box3>& boxes, std::uint32_t leaf_size = kBoxTreeLeafSize);

}  // namespace volmap
