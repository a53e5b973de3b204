// box_tree.cpp — construction of the flat BVH of box_tree.hpp (conventions there).
#include <volmap/check/box_tree.hpp>

#include <algorithm>

namespace volmap {
namespace {

// Spreads the low 10 bits of x so that there are two zero bits between consecutive bits.
std::uint32_t spread_bits(std::uint32_t x) {
  x &= 0x3FFu;
  x = (x | (x << 16)) & 0x030000FFu;
  x = (x | (x << 8)) & 0x0300F00Fu;
  x = (x | (x << 4)) & 0x030C30C3u;
  x = (x | (x << 2)) & 0x09249249u;
  return x;
}

void grow(Box3& box, const Box3& other) {
  for (int k = 0; k < 3; ++k) {
    box.lo[k] = std::min(box.lo[k], other.lo[k]);
    box.hi[k] = std::max(box.hi[k], other.hi[k]);
  }
}

// Sorts keys (30-bit Morton code << 32 | item) by code, stably: three counting passes of 10 bits
// (the items arrive in increasing order, so ties stay in item order, as a full sort of the keys).
void sort_by_code(std::vector<std::uint64_t>& keys) {
  std::vector<std::uint64_t> scratch(keys.size());
  for (int shift = 32; shift < 62; shift += 10) {
    std::uint32_t count[1025] = {};
    for (const std::uint64_t key : keys) ++count[((key >> shift) & 0x3FFu) + 1];
    for (int b = 0; b < 1024; ++b) count[b + 1] += count[b];
    for (const std::uint64_t key : keys) scratch[count[(key >> shift) & 0x3FFu]++] = key;
    keys.swap(scratch);
  }
}

}  // namespace

// Morton order of the box centres, ranges halved top-down, boxes merged bottom-up. Children are
// created after their parent, so a reverse sweep over the node array sees every child before its
// parent.
BoxTree build_box_tree(const std::vector<Box3>& boxes, std::uint32_t leaf_size) {
  leaf_size = std::max<std::uint32_t>(leaf_size, 1);
  const std::size_t n = boxes.size();
  BoxTree tree;
  tree.order.resize(n);
  if (n == 0) return tree;
  Box3 all = boxes[0];
  for (const Box3& box : boxes) grow(all, box);
  double scale[3];
  for (int k = 0; k < 3; ++k) scale[k] = all.hi[k] > all.lo[k] ? 1023.0 / (all.hi[k] - all.lo[k]) : 0.0;
  std::vector<std::uint64_t> keys(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t code = 0;
    for (int k = 0; k < 3; ++k) {
      const double c = 0.5 * (boxes[i].lo[k] + boxes[i].hi[k]);
      const double q = std::min(1023.0, std::max(0.0, (c - all.lo[k]) * scale[k]));
      code |= spread_bits(std::uint32_t(q)) << k;
    }
    keys[i] = (std::uint64_t(code) << 32) | std::uint64_t(i);
  }
  sort_by_code(keys);
  tree.leaf_boxes.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    tree.order[i] = std::uint32_t(keys[i] & 0xFFFFFFFFu);
    tree.leaf_boxes[i] = boxes[tree.order[i]];
  }
  tree.nodes.reserve(2 * (n / leaf_size + 1));
  tree.nodes.push_back(BoxTree::Node{Box3{}, 0, std::uint32_t(n), 0});
  for (std::size_t at = 0; at < tree.nodes.size(); ++at) {  // top-down: split ranges in half
    const std::uint32_t begin = tree.nodes[at].begin, end = tree.nodes[at].end;
    if (end - begin <= leaf_size) continue;
    const std::uint32_t mid = begin + (end - begin) / 2;
    const std::uint32_t left = std::uint32_t(tree.nodes.size());
    tree.nodes[at].left = left;
    tree.nodes.push_back(BoxTree::Node{Box3{}, begin, mid, 0});
    tree.nodes.push_back(BoxTree::Node{Box3{}, mid, end, 0});
  }
  for (std::size_t at = tree.nodes.size(); at-- > 0;) {  // bottom-up boxes
    BoxTree::Node& node = tree.nodes[at];
    if (node.left == 0) {
      node.box = tree.leaf_boxes[node.begin];
      for (std::uint32_t i = node.begin + 1; i < node.end; ++i) grow(node.box, tree.leaf_boxes[i]);
    } else {
      node.box = tree.nodes[node.left].box;
      grow(node.box, tree.nodes[node.left + 1].box);
    }
  }
  return tree;
}

}  // namespace volmap
