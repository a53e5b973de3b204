// polygon_triangulation.hpp — the best triangulation of a polygon 0..n-1 (the ring of an edge to be
// removed) by dynamic programming over its sub-polygons i..j: the score of a triangulation is the
// minimum of its triangles' scores, and the best one maximises it. A triangle (i, k, j) scores
// `triangle(i, k, j)` (i < k < j; -infinity when not admissible); a diagonal (i, j) that is not a
// side of the polygon must pass `diagonal(i, j)`. O(n^3) calls of `triangle`. Internal header.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <vector>

namespace volmap::volume_detail {

inline constexpr double kNotAdmissible = -std::numeric_limits<double>::infinity();

// The triangles (i, k, j), i < k < j, of the best triangulation; empty when none is admissible.
template <class Triangle, class Diagonal>
std::vector<std::array<int, 3>> best_polygon_triangulation(int n, Triangle&& triangle, Diagonal&& diagonal) {
  std::vector<double> score(std::size_t(n * n), kNotAdmissible);
  std::vector<int> split(std::size_t(n * n), -1);
  const auto at = [n](int i, int j) { return std::size_t(i * n + j); };
  for (int i = 0; i + 1 < n; ++i) score[at(i, i + 1)] = std::numeric_limits<double>::infinity();
  for (int len = 2; len < n; ++len)
    for (int i = 0; i + len < n; ++i) {
      const int j = i + len;
      if (!(i == 0 && j == n - 1) && !diagonal(i, j)) continue;
      for (int k = i + 1; k < j; ++k) {
        const double s = std::min({score[at(i, k)], score[at(k, j)], triangle(i, k, j)});
        if (s > score[at(i, j)]) score[at(i, j)] = s, split[at(i, j)] = k;
      }
    }
  std::vector<std::array<int, 3>> out;
  if (n < 3 || score[at(0, n - 1)] == kNotAdmissible) return out;
  std::vector<std::array<int, 2>> todo = {{0, n - 1}};
  while (!todo.empty()) {
    const auto [i, j] = todo.back();
    todo.pop_back();
    if (j <= i + 1) continue;
    const int k = split[at(i, j)];
    out.push_back({i, k, j});
    todo.push_back({k, j});  // after the whole of (i, k): preorder, left first
    todo.push_back({i, k});
  }
  return out;
}

}  // namespace volmap::volume_detail
