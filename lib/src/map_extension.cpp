// Carrying a boundary map across midpoint edge splits (see map_extension.hpp). Parents are found from
// the refined boundary's edges as flat CSR adjacency: a new vertex v's parents are the pair (a,b) of
// older boundary vertices near v with fl(0.5*(x_a + x_b)) == x_v exactly in all three coordinates.
#include <volmap/boundary_faces.hpp>
#include <volmap/error.hpp>
#include <volmap/map_extension.hpp>

#include <algorithm>
#include <limits>

namespace volmap {

BoundaryMap extend_boundary_map_over_splits(const BoundaryMap& map, const TetMeshData& refined,
                                            std::size_t original_vertices) {
  const std::size_t nv = refined.num_vertices();
  constexpr double kUnset = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> image(3 * nv, kUnset);
  std::vector<char> has_image(nv, 0);
  for (std::size_t i = 0; i < map.size(); ++i) {
    const std::uint32_t v = map.vids[i];
    if (v >= original_vertices || v >= nv)
      throw Error(ErrorKind::BadInput, "", 0, "map vertex " + std::to_string(v) + " is not an original vertex");
    for (int k = 0; k < 3; ++k) image[3 * v + k] = map.xyz[3 * i + k];
    has_image[v] = 1;
  }

  // Boundary adjacency (CSR over directed boundary edges; each undirected edge appears twice).
  const auto faces = boundary_half_faces(refined);
  std::vector<std::uint32_t> offsets(nv + 1, 0);
  for (const auto hf : faces)
    for (const auto v : half_face_vertices(refined, hf)) offsets[v + 1] += 2;
  for (std::size_t v = 0; v < nv; ++v) offsets[v + 1] += offsets[v];
  std::vector<std::uint32_t> neighbours(offsets[nv]);
  std::vector<std::uint32_t> fill(offsets.begin(), offsets.end() - 1);
  for (const auto hf : faces) {
    const auto f = half_face_vertices(refined, hf);
    for (int k = 0; k < 3; ++k) {
      neighbours[fill[f[k]]++] = f[(k + 1) % 3];
      neighbours[fill[f[k]]++] = f[(k + 2) % 3];
    }
  }
  const auto boundary = boundary_vertex_ids(refined, faces);

  // New vertices in increasing id order: parents are older, so they have images already. A parent
  // need not be a neighbour any more: a later split of (a,v) puts a newer vertex between a and v.
  // So the candidates are the older vertices adjacent to v or to the newer vertices connected to v
  // through newer vertices (a small set, flat scratch arrays reused across vertices).
  std::vector<std::uint32_t> candidates, stack, visited;
  for (const std::uint32_t v : boundary) {
    if (has_image[v]) continue;
    if (v < original_vertices)
      throw Error(ErrorKind::Failed, "", 0, "original boundary vertex " + std::to_string(v) + " has no image in the map");
    candidates.clear();
    visited.assign(1, v);
    stack.assign(1, v);
    while (!stack.empty() && visited.size() < 256) {
      const std::uint32_t u = stack.back();
      stack.pop_back();
      for (std::uint32_t i = offsets[u]; i < offsets[u + 1]; ++i) {
        const std::uint32_t w = neighbours[i];
        if (w < v) {
          if (has_image[w] && std::find(candidates.begin(), candidates.end(), w) == candidates.end()) candidates.push_back(w);
        } else if (w > v && std::find(visited.begin(), visited.end(), w) == visited.end()) {
          visited.push_back(w);
          stack.push_back(w);
        }
      }
    }
    const double* x = &refined.xyz[3 * v];
    bool found = false;
    for (std::size_t i = 0; i < candidates.size() && !found; ++i)
      for (std::size_t j = i + 1; j < candidates.size() && !found; ++j) {
        const std::uint32_t a = candidates[i], b = candidates[j];
        const double* xa = &refined.xyz[3 * a];
        const double* xb = &refined.xyz[3 * b];
        if (0.5 * (xa[0] + xb[0]) != x[0] || 0.5 * (xa[1] + xb[1]) != x[1] || 0.5 * (xa[2] + xb[2]) != x[2]) continue;
        for (int k = 0; k < 3; ++k) image[3 * v + k] = 0.5 * (image[3 * a + k] + image[3 * b + k]);
        has_image[v] = 1;
        found = true;
      }
    if (!found)
      throw Error(ErrorKind::Failed, "", 0,
                  "new boundary vertex " + std::to_string(v) + " is not the midpoint of two older boundary vertices");
  }

  BoundaryMap extended;
  extended.vids = boundary;
  extended.xyz.reserve(3 * boundary.size());
  for (const std::uint32_t v : boundary) extended.xyz.insert(extended.xyz.end(), &image[3 * v], &image[3 * v] + 3);
  return extended;
}

}  // namespace volmap
