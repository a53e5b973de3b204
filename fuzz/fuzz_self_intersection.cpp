// libFuzzer target: the self-intersection driver against brute force. The soup is a closed surface
// (the octahedron with each face split in four: 18 vertices, 32 triangles, every fan closed) whose
// vertices the input moves by small integers (many coplanar and collinear configurations, folds
// inside fans, coincident vertices), and whose triangles it may rewire. The driver (vertex fans,
// float pre-selection, tree) must report exactly the intersecting pairs and coincident vertices that
// the plain pair test over all pairs finds.
#include <volmap/check/self_intersection.hpp>
#include <volmap/predicates.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

namespace {

struct Surface {
  std::vector<double> xyz;
  std::vector<std::uint32_t> tris;
};

// The octahedron's six corners, then the midpoints of its twelve edges; each face in four.
Surface split_octahedron() {
  Surface s;
  const double corners[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const auto& c : corners) s.xyz.insert(s.xyz.end(), {c[0], c[1], c[2]});
  const std::uint32_t faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                     {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    const auto it = std::find(edges.begin(), edges.end(), key);
    if (it != edges.end()) return std::uint32_t(6 + (it - edges.begin()));
    edges.push_back(key);
    for (int k = 0; k < 3; ++k) s.xyz.push_back(0.5 * (s.xyz[3 * a + k] + s.xyz[3 * b + k]));
    return std::uint32_t(6 + edges.size() - 1);
  };
  for (const auto& f : faces) {
    const std::uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
    s.tris.insert(s.tris.end(), {f[0], ab, ca, ab, f[1], bc, ca, bc, f[2], ab, bc, ca});
  }
  return s;
}

bool degenerate(const Surface& s, std::size_t t) {
  const double* X = s.xyz.data();
  const std::uint32_t* v = &s.tris[3 * t];
  return volmap::triangle_is_degenerate(X + 3 * v[0], X + 3 * v[1], X + 3 * v[2]);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Surface s = split_octahedron();
  const std::size_t nv = s.xyz.size() / 3, nt = s.tris.size() / 3;
  if (size < 3 * nv) return 0;
  // Coordinates: the surface scaled by 4, each coordinate moved by an integer in [-3, 3] (one byte
  // each): mostly injective fans, with folds, contacts and coincidences where moves are large.
  for (std::size_t i = 0; i < 3 * nv; ++i) s.xyz[i] = 4.0 * s.xyz[i] + double(data[i] % 7) - 3.0;
  // Rewiring: each further triple of bytes (triangle, corner, vertex) replaces one corner.
  for (std::size_t i = 3 * nv; i + 2 < size; i += 3)
    s.tris[3 * (data[i] % nt) + data[i + 1] % 3] = std::uint32_t(data[i + 2] % nv);

  std::size_t pairs = 0, coincident = 0;
  for (std::size_t i = 0; i < nt; ++i)
    for (std::size_t j = i + 1; j < nt; ++j)
      if (!degenerate(s, i) && !degenerate(s, j) &&
          volmap::triangle_pair_intersects(s.xyz.data(), &s.tris[3 * i], &s.tris[3 * j]))
        ++pairs;
  // Coincident vertices (among those the triangles use): a point held by k vertices counts k − 1.
  std::vector<char> used(nv, 0);
  for (const std::uint32_t v : s.tris) used[v] = 1;
  for (std::size_t v = 0; v < nv; ++v) {
    if (!used[v]) continue;
    for (std::size_t w = 0; w < v; ++w)
      if (used[w] && volmap::points_equal(&s.xyz[3 * v], &s.xyz[3 * w])) {
        ++coincident;
        break;
      }
  }
  const volmap::SelfIntersectionResult r = volmap::find_self_intersections(s.xyz, s.tris);
  if (r.intersecting_pairs != pairs || r.coincident_vertices != coincident) __builtin_trap();
  return 0;
}
