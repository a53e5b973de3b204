// Strict-kernel LP (B1 of mapping.md §7), the link-kernel relocation pre-step and the kernel descent (§10).
#include <doctest/doctest.h>

#include <volmap/core/local_tables.hpp>
#include <volmap/core/tet_mesh.hpp>
#include <volmap/volume/kernel_descent.hpp>
#include <volmap/volume/kernel_lp.hpp>
#include <volmap/volume/link_kernel.hpp>
#include <volmap/volume/map_stages.hpp>
#include <volmap/predicates.hpp>

#include "map_test_meshes.hpp"

#include <algorithm>
#include <cmath>
#include <random>

TEST_CASE("strict kernel of a tet's outward faces is its interior; reversed faces have none") {
  // VOLMAP-positive tet: orient3d(v0,v1,v2,v3) > 0.
  double v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  if (volmap::orient3d(v[0], v[1], v[2], v[3]) < 0) std::swap(v[2], v[3]);
  const auto& F = volmap::kTetFace;
  std::vector<double> tri, rev;
  for (const auto& f : F) {
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) tri.push_back(v[f[j]][i]);
    for (int j = 2; j >= 0; --j)
      for (int i = 0; i < 3; ++i) rev.push_back(v[f[j]][i]);
  }
  double q[3];
  REQUIRE(volmap::strict_kernel_point(tri, q));
  for (const auto& f : F) CHECK(volmap::orient3d(v[f[0]], v[f[1]], v[f[2]], q) > 0);
  CHECK(!volmap::strict_kernel_point(rev, q));
}

// Triangles with corners on a 4×4×4 grid, a third of the coordinates moved by up to 1e-7, a third of
// the triangles repeated: rows (nearly) equal or parallel, as on the boundary of a tet region. The
// LP's point must attain the slack it reports (every face's signed distance, in the LP's frame, at
// least the slack): before Harris's ratio test about 0.3 % of such sets missed rows by up to 0.4.
TEST_CASE("kernel LP: the Chebyshev point attains its slack on repeated and nearly parallel faces") {
  std::mt19937_64 rng(20261207);
  auto unit = [&] { return double(rng() >> 11) * 0x1p-53; };  // [0, 1), the same on every platform
  int solved = 0, missed = 0;
  for (int it = 0; it < 20000; ++it) {
    std::vector<double> tri;
    const int nf = 4 + int(rng() % 30);
    for (int f = 0; f < nf; ++f) {
      double p[3][3];
      for (auto& corner : p)
        for (double& x : corner) x = double(rng() % 4) + (rng() % 3 == 0 ? 1e-7 * (2 * unit() - 1) : 0.0);
      double n[3];
      const double len = volmap::inward_face_normal(p[0], p[1], p[2], 1.0, n);
      if (len * len < 1e-2) continue;  // a well-defined normal only
      if (n[0] * (1.5 - p[0][0]) + n[1] * (1.5 - p[0][1]) + n[2] * (1.5 - p[0][2]) < 0) std::swap(p[1], p[2]);
      if (rng() % 8 == 0) std::swap(p[1], p[2]);  // some faces away from the centre: kernels may be empty
      for (int copy = rng() % 3 == 0 ? 2 : 1; copy > 0; --copy)
        for (const auto& corner : p) tri.insert(tri.end(), corner, corner + 3);
    }
    if (tri.empty()) continue;
    double q[3], slack = 0;
    if (!volmap::chebyshev_point(tri, q, &slack)) continue;
    ++solved;
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (std::size_t k = 0; k < tri.size(); ++k) {
      lo[k % 3] = std::min(lo[k % 3], tri[k]);
      hi[k % 3] = std::max(hi[k % 3], tri[k]);
    }
    const double diag = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
    double attained = 1e300;
    for (std::size_t f = 0; f < tri.size() / 9; ++f) {
      const double* a = &tri[9 * f];
      double n[3];
      const double len = volmap::inward_face_normal(a, a + 3, a + 6, 1.0, n);
      attained = std::min(attained, (n[0] * (q[0] - a[0]) + n[1] * (q[1] - a[1]) + n[2] * (q[2] - a[2])) / len / diag);
    }
    if (attained < slack - 1e-7) ++missed;
  }
  CHECK(solved > 19000);
  CHECK(missed == 0);
}

TEST_CASE("link-kernel relocation repairs a vertex pushed out of its star, never increases the bad count") {
  auto m = map_test::kuhn_grid(2);
  auto bnd = map_test::grid_boundary_flags(2);
  auto X = m.xyz;
  // The only interior vertex is (0.5,0.5,0.5) = id 13; push it outside the cube.
  REQUIRE(!bnd[13]);
  X[3 * 13] = 1.7;
  const auto before = volmap::count_nonpositive(X, m.tets);
  REQUIRE(before > 0);
  auto r = volmap::relocate_into_link_kernels(volmap::TetMesh(m), bnd, X, 5);
  CHECK(r.nonpositive_before == before);
  CHECK(r.nonpositive_after == 0);
  CHECK(volmap::count_nonpositive(X, m.tets) == 0);
  for (std::size_t v = 0; v < bnd.size(); ++v)
    if (bnd[v])
      for (int i = 0; i < 3; ++i) CHECK(X[3 * v + i] == m.xyz[3 * v + i]);
}

TEST_CASE("kernel descent: a vertex pushed out of its star comes back; bad tets with empty kernels never get worse") {
  auto m = map_test::kuhn_grid(3);
  auto bnd = map_test::grid_boundary_flags(3);
  std::size_t improved = 0;
  for (unsigned seed = 1; seed <= 20; ++seed) {
    auto X = map_test::scrambled_target(m, bnd, seed, 0.6);
    const auto X0 = X;
    const auto before = volmap::count_nonpositive(X, m.tets);
    auto r = volmap::descend_into_link_kernels(volmap::TetMesh(m), bnd, X);
    CHECK(r.nonpositive_before == before);
    CHECK(r.nonpositive_after == volmap::count_nonpositive(X, m.tets));
    CHECK(r.nonpositive_after <= before);
    improved += r.nonpositive_after < before;
    for (std::size_t v = 0; v < bnd.size(); ++v)
      if (bnd[v])
        for (int i = 0; i < 3; ++i) CHECK(X[3 * v + i] == X0[3 * v + i]);
  }
  CHECK(improved >= 10);
}

TEST_CASE("finish_by_link_kernels: a finished map or the given one, never a partial repair") {
  auto m = map_test::kuhn_grid(3);
  auto bnd = map_test::grid_boundary_flags(3);
  volmap::MapState state(m, map_test::boundary_map_of(bnd, m.xyz));
  SUBCASE("one interior vertex pushed out of its star: finished, exactly positive") {
    auto X = m.xyz;
    std::size_t v = 0;
    while (bnd[v]) ++v;
    X[3 * v] += 1.5;
    REQUIRE(volmap::count_nonpositive(X, m.tets) > 0);
    CHECK(volmap::finish_by_link_kernels(state, X));
    CHECK(volmap::count_nonpositive(X, m.tets) == 0);
  }
  SUBCASE("scrambled maps: true exactly when the result is positive; false leaves the map bit-identical") {
    std::size_t finished = 0, refused = 0;
    for (unsigned seed = 1; seed <= 20; ++seed) {
      auto X = map_test::scrambled_target(m, bnd, seed, 0.9);
      const auto X0 = X;
      if (volmap::finish_by_link_kernels(state, X)) {
        ++finished;
        CHECK(volmap::count_nonpositive(X, m.tets) == 0);
      } else {
        ++refused;
        CHECK(X == X0);
        // the same local moves in place leave bad tets (what the trial refused to keep)
        auto Y = X0;
        volmap::relocate_into_link_kernels(volmap::TetMesh(m), bnd, Y, 50);
        volmap::descend_into_link_kernels(volmap::TetMesh(m), bnd, Y);
        CHECK(volmap::count_nonpositive(Y, m.tets) > 0);
      }
    }
    CHECK(refused > 0);  // the scrambling is strong enough that some maps are not finished locally
    MESSAGE("finished " << finished << ", refused " << refused);
  }
}
