// face_grouping.hpp (internal) — groups the half-faces of a tet array by their vertex set in
// linear time: a counting sort by smallest vertex, then a small sort per bucket on the other two.
// Half-face h = 4t+i is the face opposite local vertex i; its outward winding is kTetFace[i].
// `parity` tells the winding: two half-faces with the same vertex set and opposite windings have
// different parities (the triple rotated to start at its smallest vertex is (m,p,q), parity = p>q).
#pragma once

#include <volmap/local_tables.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace volmap::detail {

struct FaceEntry {
  std::uint64_t key;     // (mid << 32) | max of the sorted triple
  std::uint32_t hf;      // 4t+i
  std::uint32_t parity;  // 0 or 1
};

// The smallest vertex of half-face i of tet p, the sort key of the other two and the parity.
inline void face_key(const std::uint32_t* p, int i, std::uint32_t& min_v, std::uint64_t& key, std::uint32_t& parity) {
  const std::uint32_t x = p[kTetFace[i][0]], y = p[kTetFace[i][1]], z = p[kTetFace[i][2]];
  std::uint32_t a, b;
  if (x < y && x < z) { min_v = x; a = y; b = z; }
  else if (y < z) { min_v = y; a = z; b = x; }
  else { min_v = z; a = x; b = y; }
  parity = a > b ? 1u : 0u;
  key = a < b ? (std::uint64_t(a) << 32) | b : (std::uint64_t(b) << 32) | a;
}

// Calls on_group(min_vertex, const FaceEntry* first, std::size_t n) once per distinct face, entries
// sorted by hf inside a group. Tets with skip(t) true are ignored. Vertex ids must be < num_vertices
// (checked by the caller). Work arrays are passed in so callers can reuse them.
template <class Skip, class OnGroup>
void group_faces(const std::uint32_t* tets, std::size_t num_tets, std::size_t num_vertices, Skip&& skip,
                 OnGroup&& on_group) {
  std::vector<std::uint32_t> offsets(num_vertices + 2, 0);
  for (std::size_t t = 0; t < num_tets; ++t) {
    if (skip(t)) continue;
    const std::uint32_t* p = tets + 4 * t;
    for (int i = 0; i < 4; ++i) {
      std::uint32_t m = 0xFFFFFFFFu;
      for (int k = 0; k < 3; ++k) m = std::min(m, p[kTetFace[i][k]]);
      ++offsets[std::size_t(m) + 2];
    }
  }
  for (std::size_t v = 2; v < offsets.size(); ++v) offsets[v] += offsets[v - 1];
  std::vector<std::uint32_t> order(offsets.back());
  for (std::size_t t = 0; t < num_tets; ++t) {
    if (skip(t)) continue;
    const std::uint32_t* p = tets + 4 * t;
    for (int i = 0; i < 4; ++i) {
      std::uint32_t m = 0xFFFFFFFFu;
      for (int k = 0; k < 3; ++k) m = std::min(m, p[kTetFace[i][k]]);
      order[offsets[std::size_t(m) + 1]++] = std::uint32_t(4 * t + i);
    }
  }
  std::vector<FaceEntry> bucket;
  for (std::size_t v = 0; v < num_vertices; ++v) {
    const std::uint32_t begin = offsets[v], end = offsets[v + 1];
    if (begin == end) continue;
    bucket.clear();
    for (std::uint32_t k = begin; k < end; ++k) {
      const std::uint32_t hf = order[k];
      FaceEntry e;
      std::uint32_t m;
      face_key(tets + 4 * std::size_t(hf >> 2), int(hf & 3), m, e.key, e.parity);
      e.hf = hf;
      bucket.push_back(e);
    }
    std::sort(bucket.begin(), bucket.end(), [](const FaceEntry& a, const FaceEntry& b) {
      return a.key < b.key || (a.key == b.key && a.hf < b.hf);
    });
    std::size_t g = 0;
    while (g < bucket.size()) {
      std::size_t e = g + 1;
      while (e < bucket.size() && bucket[e].key == bucket[g].key) ++e;
      on_group(std::uint32_t(v), bucket.data() + g, e - g);
      g = e;
    }
  }
}

}  // namespace volmap::detail
