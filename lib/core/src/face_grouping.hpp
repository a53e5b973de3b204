// face_grouping.hpp (internal) — groups the half-faces of a tet array by their vertex set in
// linear time: a counting sort by smallest vertex that already stores each face's sort key (sequential
// reads of the tets, scattered writes), then a small in-place sort per bucket on the other two ids.
// Half-face h = 4t+i is the face opposite local vertex i; its outward winding is kTetFace[i].
// The winding is kept as a parity bit: two half-faces with the same vertex set and opposite windings
// have different parities (the triple rotated to start at its smallest vertex is (m,p,q), parity =
// p>q). Requires num_tets <= kMaxGroupedTets (hf < 2^31, the parity lives in bit 31).
#pragma once

#include <volmap/core/huge_pages.hpp>
#include <volmap/core/local_tables.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

namespace volmap::detail {

inline constexpr std::size_t kMaxGroupedTets = std::size_t(1) << 29;
// A large bucket sorts its entries packed as (mid, max, position) in one 64-bit word when the ids
// fit 21 bits and the positions 22.
inline constexpr std::size_t kPackedIdLimit = std::size_t(1) << 21;
inline constexpr std::size_t kPackedPositionLimit = std::size_t(1) << 22;
inline constexpr std::uint32_t kParityBit = 0x80000000u;

inline std::uint32_t hf_of(std::uint32_t hf_parity) { return hf_parity & ~kParityBit; }
inline std::uint32_t parity_of(std::uint32_t hf_parity) { return hf_parity >> 31; }

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

// Calls on_group(min_vertex, const std::uint64_t* keys, const std::uint32_t* hf_parity, std::size_t n)
// once per distinct face, in increasing (min, mid, max) order; entries inside a group sorted by hf.
// keys[k] = (mid << 32) | max; hf_parity[k] = hf | parity << 31. Tets with skip(t) true are ignored.
// Vertex ids must be < num_vertices (checked by the caller).
// Parallel = true sorts and reports the buckets on several threads (TBB): on_group must then be
// safe to call concurrently for different min vertices (buckets are never split between threads,
// and one thread visits its buckets in increasing order).
template <bool Parallel = false, class Skip, class OnGroup>
void group_faces(const std::uint32_t* tets, std::size_t num_tets, std::size_t num_vertices, Skip&& skip,
                 OnGroup&& on_group) {
  std::vector<std::uint32_t> offsets(num_vertices + 2, 0);
  for (std::size_t t = 0; t < num_tets; ++t) {
    if (skip(t)) continue;
    const std::uint32_t* p = tets + 4 * t;
    // min over the face opposite i is the tet's min unless i is where the min sits.
    const std::uint32_t m01 = std::min(p[0], p[1]), m23 = std::min(p[2], p[3]);
    ++offsets[std::size_t(std::min(p[1], m23)) + 2];
    ++offsets[std::size_t(std::min(p[0], m23)) + 2];
    ++offsets[std::size_t(std::min(m01, p[3])) + 2];
    ++offsets[std::size_t(std::min(m01, p[2])) + 2];
  }
  for (std::size_t v = 2; v < offsets.size(); ++v) offsets[v] += offsets[v - 1];
  const std::size_t total = offsets.back();
  // Uninitialised (every slot is written below) and advised for huge pages.
  HugeBuffer<std::uint64_t> keys(total);
  HugeBuffer<std::uint32_t> hfp(total);
  for (std::size_t t = 0; t < num_tets; ++t) {
    if (skip(t)) continue;
    const std::uint32_t* p = tets + 4 * t;
    for (int i = 0; i < 4; ++i) {
      std::uint32_t m, parity;
      std::uint64_t key;
      face_key(p, i, m, key, parity);
      const std::uint32_t pos = offsets[std::size_t(m) + 1]++;
      keys[pos] = key;
      hfp[pos] = std::uint32_t(4 * t + i) | (parity << 31);
    }
  }
  auto process = [&](std::size_t first_vertex, std::size_t last_vertex) {
  std::vector<std::uint32_t> perm;
  std::vector<std::uint64_t> packed;
  std::vector<std::uint64_t> tmp_keys;
  std::vector<std::uint32_t> tmp_hfp;
  for (std::size_t v = first_vertex; v < last_vertex; ++v) {
    const std::size_t begin = offsets[v], end = offsets[v + 1];
    if (begin == end) continue;
    std::uint64_t* k = keys.data() + begin;
    std::uint32_t* h = hfp.data() + begin;
    const std::size_t n = end - begin;
    // A bucket's entries arrive in increasing hf (tets are scattered in order), so sorting by key
    // stably keeps each group sorted by hf.
    if (n <= 48) {  // insertion sort (stable) in place (typical buckets hold ~20 faces)
      for (std::size_t a = 1; a < n; ++a) {
        const std::uint64_t kk = k[a];
        const std::uint32_t hh = h[a];
        std::size_t b = a;
        while (b > 0 && kk < k[b - 1]) {
          k[b] = k[b - 1];
          h[b] = h[b - 1];
          --b;
        }
        k[b] = kk;
        h[b] = hh;
      }
    } else {  // large buckets (high-valence vertices): sort (key, position) and gather
      if (num_vertices <= kPackedIdLimit && n <= kPackedPositionLimit) {
        // (mid, max, position) packed in one word (21 + 21 + 22 bits): a plain integer sort.
        packed.resize(n);
        for (std::size_t a = 0; a < n; ++a)
          packed[a] = ((k[a] >> 32) << 43) | ((k[a] & 0xFFFFFFFFu) << 22) | std::uint64_t(a);
        std::sort(packed.begin(), packed.end());
        perm.resize(n);
        for (std::size_t a = 0; a < n; ++a) perm[a] = std::uint32_t(packed[a] & (kPackedPositionLimit - 1));
      } else {
        perm.resize(n);
        std::iota(perm.begin(), perm.end(), 0u);
        std::sort(perm.begin(), perm.end(),
                  [&](std::uint32_t x, std::uint32_t y) { return k[x] < k[y] || (k[x] == k[y] && x < y); });
      }
      tmp_keys.assign(k, k + n);
      tmp_hfp.assign(h, h + n);
      for (std::size_t a = 0; a < n; ++a) {
        k[a] = tmp_keys[perm[a]];
        h[a] = tmp_hfp[perm[a]];
      }
    }
    std::size_t g = 0;
    while (g < n) {
      std::size_t e = g + 1;
      while (e < n && k[e] == k[g]) ++e;
      on_group(std::uint32_t(v), k + g, h + g, e - g);
      g = e;
    }
  }
  };
  if constexpr (Parallel) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_vertices, 2048),
                      [&](const tbb::blocked_range<std::size_t>& r) { process(r.begin(), r.end()); });
  } else {
    process(0, num_vertices);
  }
}

}  // namespace volmap::detail
