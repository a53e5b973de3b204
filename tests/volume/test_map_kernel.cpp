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
