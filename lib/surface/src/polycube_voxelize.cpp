// polycube_voxelize.cpp — grid cells inside a tet mesh, grown into a strictly star-shaped polycube
// (see polycube_voxelize.hpp for the conventions).
#include <volmap/surface/polycube_voxelize.hpp>

#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>
#include <volmap/core/local_tables.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <queue>
#include <tuple>

namespace volmap {
namespace {

struct Grid {
  std::array<double, 3> min{};
  double h = 0;
  std::array<int, 3> n{};
  std::size_t index(const PolycubeCell& c) const { return std::size_t(c[0]) + std::size_t(n[0]) * (std::size_t(c[1]) + std::size_t(n[1]) * std::size_t(c[2])); }
  std::size_t size() const { return std::size_t(n[0]) * std::size_t(n[1]) * std::size_t(n[2]); }
  std::array<double, 3> centre(const PolycubeCell& c) const {
    return {min[0] + h * (c[0] + 0.5), min[1] + h * (c[1] + 0.5), min[2] + h * (c[2] + 0.5)};
  }
};

Grid make_grid(const TetMeshData& mesh, int resolution) {
  std::array<double, 3> lo = {mesh.xyz[0], mesh.xyz[1], mesh.xyz[2]}, hi = lo;
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], mesh.xyz[3 * v + a]);
      hi[a] = std::max(hi[a], mesh.xyz[3 * v + a]);
    }
  Grid g;
  g.min = lo;
  g.h = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}) / resolution;
  for (int a = 0; a < 3; ++a) g.n[a] = std::max(1, int(std::ceil((hi[a] - lo[a]) / g.h)));
  return g;
}

// inside[index(c)] for every cell whose centre lies in a (closed) tet: each tet tests the centres in
// its bounding box.
std::vector<char> inside_cells(const TetMeshData& mesh, const Grid& g) {
  std::vector<char> inside(g.size(), 0);
  for (std::size_t t = 0; t < mesh.num_tets(); ++t) {
    const double* p[4];
    for (int k = 0; k < 4; ++k) p[k] = &mesh.xyz[3 * std::size_t(mesh.tets[4 * t + k])];
    std::array<int, 3> from{}, to{};
    for (int a = 0; a < 3; ++a) {
      const double lo = std::min({p[0][a], p[1][a], p[2][a], p[3][a]}), hi = std::max({p[0][a], p[1][a], p[2][a], p[3][a]});
      from[a] = std::max(0, int(std::floor((lo - g.min[a]) / g.h - 0.5)));
      to[a] = std::min(g.n[a] - 1, int(std::ceil((hi - g.min[a]) / g.h - 0.5)));
    }
    for (int k = from[2]; k <= to[2]; ++k)
      for (int j = from[1]; j <= to[1]; ++j)
        for (int i = from[0]; i <= to[0]; ++i) {
          const PolycubeCell c = {i, j, k};
          if (inside[g.index(c)]) continue;
          const auto q = g.centre(c);
          bool in = true;
          for (int f = 0; f < 4 && in; ++f)
            in = orient3d(p[kTetFace[f][0]], p[kTetFace[f][1]], p[kTetFace[f][2]], q.data()) >= 0;
          if (in) inside[g.index(c)] = 1;
        }
  }
  return inside;
}

bool valid_star_polycube(const std::vector<PolycubeCell>& cells) {
  try {
    const PolycubeSurface s = polycube_surface(cells, "voxelization");
    polycube_kernel(cells, s, "voxelization");
    return true;
  } catch (const Error&) {
    return false;
  }
}

}  // namespace

std::vector<PolycubeCell> voxelize_star_polycube(const TetMeshData& mesh, int resolution) {
  if (resolution < 1 || resolution > 64)
    throw Error(ErrorKind::BadInput, "", 0, "voxelization resolution must be in [1, 64]");
  if (mesh.num_tets() == 0) throw Error(ErrorKind::BadInput, "", 0, "voxelization: the mesh has no tets");
  const Grid g = make_grid(mesh, resolution);
  const std::vector<char> inside = inside_cells(mesh, g);

  std::array<double, 3> centroid = {0, 0, 0};
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v)
    for (int a = 0; a < 3; ++a) centroid[a] += mesh.xyz[3 * v + a] / double(mesh.num_vertices());
  const auto distance2 = [&](const PolycubeCell& c, const std::array<double, 3>& to) {
    const auto q = g.centre(c);
    return (q[0] - to[0]) * (q[0] - to[0]) + (q[1] - to[1]) * (q[1] - to[1]) + (q[2] - to[2]) * (q[2] - to[2]);
  };
  bool found = false;
  PolycubeCell seed{};
  double best = 0;
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        const PolycubeCell c = {i, j, k};
        if (!inside[g.index(c)]) continue;
        const double d = distance2(c, centroid);
        if (!found || d < best) found = true, best = d, seed = c;
      }
  if (!found)
    throw Error(ErrorKind::BadInput, "", 0, "voxelization: no cell centre lies inside the mesh (raise the resolution)");

  // Grow by distance from the seed's centre.
  const auto seed_centre = g.centre(seed);
  using Candidate = std::tuple<double, PolycubeCell>;
  std::priority_queue<Candidate, std::vector<Candidate>, std::greater<Candidate>> frontier;
  std::vector<char> queued(g.size(), 0);
  std::vector<PolycubeCell> cells;
  frontier.push({0.0, seed});
  queued[g.index(seed)] = 1;
  static constexpr int kStep[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  while (!frontier.empty() && cells.size() < kMaxPolycubeCells) {
    const PolycubeCell c = std::get<1>(frontier.top());
    frontier.pop();
    cells.push_back(c);
    if (!valid_star_polycube(cells)) {
      cells.pop_back();
      continue;
    }
    for (const auto& s : kStep) {
      const PolycubeCell nb = {c[0] + s[0], c[1] + s[1], c[2] + s[2]};
      if (nb[0] < 0 || nb[1] < 0 || nb[2] < 0 || nb[0] >= g.n[0] || nb[1] >= g.n[1] || nb[2] >= g.n[2]) continue;
      if (!inside[g.index(nb)] || queued[g.index(nb)]) continue;
      queued[g.index(nb)] = 1;
      frontier.push({distance2(nb, seed_centre), nb});
    }
  }
  return cells;
}

}  // namespace volmap
