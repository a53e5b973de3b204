// voxelize_star_polycube: a box mesh gives every cell of its grid, an L (star-shaped) every inside
// cell, a U (not star-shaped) a strictly star-shaped subset around the seed; counts known by
// construction, star-shapedness re-checked with polycube_kernel.
#include <doctest/doctest.h>
#include <volmap/core/error.hpp>
#include <volmap/surface/polycube_voxelize.hpp>
#include <volmap/testing/generate.hpp>

#include <algorithm>

using namespace volmap;

namespace {
// The Kuhn grid of nx × ny × 1 unit cubes without the tets whose centroid lies in a removed block.
TetMeshData grid_without(std::size_t nx, std::size_t ny, double x0, double x1, double y0, double y1) {
  const TetMeshData full = generate_kuhn_grid(nx, ny, 1);
  TetMeshData m = full;
  m.tets.clear();
  for (std::size_t t = 0; t < full.num_tets(); ++t) {
    double c[3] = {0, 0, 0};
    for (int k = 0; k < 4; ++k)
      for (int a = 0; a < 3; ++a) c[a] += 0.25 * full.xyz[3 * full.tets[4 * t + k] + a];
    if (c[0] > x0 && c[0] < x1 && c[1] > y0 && c[1] < y1) continue;
    m.tets.insert(m.tets.end(), &full.tets[4 * t], &full.tets[4 * t] + 4);
  }
  return m;
}
bool star_shaped(const std::vector<PolycubeCell>& cells) {
  try {
    polycube_kernel(cells, polycube_surface(cells, "test"), "test");
    return true;
  } catch (const Error&) {
    return false;
  }
}
}  // namespace

TEST_CASE("voxelize_star_polycube: a box gives its whole grid") {
  const auto cells = voxelize_star_polycube(generate_kuhn_grid(4, 2, 2), 4);  // h = 1: 4 x 2 x 2 cells
  CHECK(cells.size() == 16u);
  CHECK(star_shaped(cells));
  const auto fine = voxelize_star_polycube(generate_kuhn_unit_cube(3), 5);
  CHECK(fine.size() == 125u);
}

TEST_CASE("voxelize_star_polycube: an L keeps all its cells, a U only a star-shaped part") {
  const auto l = voxelize_star_polycube(grid_without(4, 4, 2, 4, 2, 4), 4);  // 16 - 4 = 12 cells
  CHECK(l.size() == 12u);
  CHECK(star_shaped(l));
  const auto u = voxelize_star_polycube(grid_without(6, 4, 2, 4, 2, 4), 6);  // 24 - 4 = 20 inside, not star-shaped
  CHECK(u.size() < 20u);
  CHECK(u.size() >= 12u);  // the bottom bar (12) and more are reachable from the seed
  CHECK(star_shaped(u));
  for (const auto& c : u) CHECK_FALSE((c[0] >= 2 && c[0] < 4 && c[1] >= 2));  // never a removed cell
}

TEST_CASE("voxelize_star_polycube refuses bad resolutions and empty meshes") {
  CHECK_THROWS_AS(voxelize_star_polycube(generate_kuhn_unit_cube(2), 0), Error);
  CHECK_THROWS_AS(voxelize_star_polycube(generate_kuhn_unit_cube(2), 65), Error);
  TetMeshData empty = generate_kuhn_unit_cube(1);
  empty.tets.clear();
  CHECK_THROWS_AS(voxelize_star_polycube(empty, 2), Error);
}
