// B1 star-patch cone repair (docs/mapping.md §7, original vertices kept): hand-made Kuhn-grid cases
// with inverted vertex stars are repaired with every original vertex kept at its source position and
// the refined source a valid positive tetrahedralisation with the same boundary faces; impossible
// cases fail and leave everything unchanged; volmap-map never reports a false success; one small G1
// pair that fails at fixed connectivity is certified with refinement (data test).
#include <doctest/doctest.h>

#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/properties.hpp>
#include <volmap/core/tet_mesh.hpp>
#include <volmap/volume/cone_repair.hpp>
#include <volmap/io/io.hpp>
#include <volmap/predicates.hpp>
#include <volmap/check/tetmesh_checks.hpp>
#include <volmap/testing/generate.hpp>

#include "map_test_meshes.hpp"
#include "refinement_checks.hpp"
#include "mesh_test_util.hpp"
#include "test_support.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <utility>
#include <string>
#include <tuple>
#include <sys/wait.h>

namespace {

using refinement_checks::check_refinement;

int grid_id(int n, int i, int j, int k) { return (i * (n + 1) + j) * (n + 1) + k; }

// A Kuhn grid with its boundary flags and a target to displace (…0: the state before the repair),
// and a fresh copy repaired by repair() (m, bnd, target: the state after).
struct GridCase {
  explicit GridCase(int n) : GridCase(map_test::kuhn_grid(n), map_test::grid_boundary_flags(n)) {}
  GridCase(volmap::TetMeshData mesh, std::vector<std::uint8_t> boundary)
      : m0(std::move(mesh)), bnd0(std::move(boundary)), target0(m0.xyz) {}
  // Every shelling step is confirmed by the full sphere check (it throws on a disagreement).
  volmap::ConeRepairResult repair(volmap::ConeRepairOptions options = {}) {
    m = m0;
    bnd = bnd0;
    target = target0;
    options.verify_shelling = true;
    return volmap::cone_repair(m, bnd, target, options);
  }
  volmap::TetMeshData m0;
  std::vector<std::uint8_t> bnd0;
  std::vector<double> target0;
  volmap::TetMeshData m;
  std::vector<std::uint8_t> bnd;
  std::vector<double> target;
};

// A 12×3×3 Kuhn bar (boundary: its box faces) for scramble_bar.
GridCase scrambled_bar_case() {
  volmap::TetMeshData bar = volmap::generate_kuhn_grid(12, 3, 3);
  std::vector<std::uint8_t> boundary(bar.num_vertices(), 0);
  for (std::size_t v = 0; v < bar.num_vertices(); ++v) {
    const double* p = &bar.xyz[3 * v];
    boundary[v] = p[0] == 0 || p[0] == 12 || p[1] == 0 || p[1] == 3 || p[2] == 0 || p[2] == 3;
  }
  return GridCase(std::move(bar), std::move(boundary));
}

// The bar's target: the identity with every interior vertex moved at random (seeded), three times
// as far along the bar as across it.
void scramble_bar(GridCase& c, unsigned seed) {
  c.target0 = c.m0.xyz;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  for (std::size_t v = 0; v < c.m0.num_vertices(); ++v)
    if (!c.bnd0[v])
      for (int d = 0; d < 3; ++d) c.target0[3 * v + d] += u(rng) * (d == 0 ? 3 : 1);
}

}  // namespace

TEST_CASE("cone repair: one inverted vertex star in a Kuhn grid is repaired with original vertices kept") {
  const int n = 4;
  GridCase c(n);
  const auto& [m0, bnd0, target0] = std::tie(c.m0, c.bnd0, c.target0);
  const int v = grid_id(n, 2, 2, 2);
  for (int i = 0; i < 3; ++i) c.target0[3 * v + i] += 0.3;  // past its neighbours (spacing 0.25): star inverted
  const std::size_t bad0 = volmap::count_nonpositive(target0, m0.tets);
  REQUIRE(bad0 > 0);
  const auto r = c.repair();
  const auto& [m, bnd, target] = std::tie(c.m, c.bnd, c.target);
  CHECK(r.clusters >= 1);
  CHECK(r.patches >= 1);
  CHECK(r.failed_clusters == 0);
  CHECK(r.tets_before == m0.num_tets());
  CHECK(r.tets_after == m.num_tets());
  CHECK(r.vertices_added == m.num_vertices() - m0.num_vertices());
  CHECK(r.vertices_added <= r.patches);  // at most one apex per patch
  CHECK(r.max_region > 0);
  // Growth: each kept interior vertex of R costs a few tets (1→4 adds 3, 2→6 adds 4, n→2n adds n).
  // (the cones over ∂R may be fewer than R's tets, so the count can also shrink)
  CHECK(m.num_tets() <= m0.num_tets() + 8 * r.max_region);
  check_refinement(m0, target0, bnd0, m, target, bnd);
  MESSAGE("one star: " << bad0 << " inverted, region " << r.max_region << ", tets " << m0.num_tets() << " -> " << m.num_tets()
                       << ", vertices +" << r.vertices_added);
}

TEST_CASE("cone repair: a free vertex pushed across a concave boundary valley is repaired with and without aimed growth") {
  // Target: the unit-cube Kuhn grid with z scaled by 1 + 2|x − 0.5| (piecewise linear on the grid, so
  // positive): the top is a V-shaped valley along x = 0.5 (reflex edge, like the valleys between the
  // spikes of the star domain). The free vertex just below the valley is pushed up across the plane
  // of the valley's top faces. (This small case is solved by the LP growth already; the aimed growth
  // must leave it a valid refinement too. The LP-growth failure it was made for, G1 ramses star, is
  // described in cone_repair.cpp.)
  const int n = 6;
  const auto m0 = map_test::kuhn_grid(n);
  const auto bnd0 = map_test::grid_boundary_flags(n);
  auto target0 = m0.xyz;
  for (std::size_t u = 0; u < m0.num_vertices(); ++u) target0[3 * u + 2] *= 1 + 2 * std::abs(target0[3 * u] - 0.5);
  REQUIRE(volmap::count_nonpositive(target0, m0.tets) == 0);
  const int v = grid_id(n, 5, 3, 3);  // (0.5, 0.5, 5/6): the first index runs along z
  REQUIRE(m0.xyz[3 * v + 0] == doctest::Approx(0.5));
  REQUIRE(m0.xyz[3 * v + 1] == doctest::Approx(0.5));
  REQUIRE(m0.xyz[3 * v + 2] == doctest::Approx(5.0 / 6.0));
  target0[3 * v + 0] += 0.4;
  target0[3 * v + 2] += 1.0;
  REQUIRE(volmap::count_nonpositive(target0, m0.tets) > 0);
  for (bool aimed : {false, true}) {
    auto m = m0;
    auto bnd = bnd0;
    auto target = target0;
    volmap::ConeRepairOptions o;
    o.aimed_growth = aimed;
    const auto r = volmap::cone_repair(m, bnd, target, o);
    CHECK(r.failed_clusters == 0);
    CHECK(r.patches >= 1);
    check_refinement(m0, target0, bnd0, m, target, bnd);
  }
}

TEST_CASE("cone repair: the only interior vertex of a convex grid becomes the apex (no growth)") {
  const int n = 2;  // one interior vertex (1,1,1); every tet has a boundary face or touches ∂M
  const auto m0 = map_test::kuhn_grid(n);
  const auto bnd0 = map_test::grid_boundary_flags(n);
  auto target0 = m0.xyz;
  const int v = grid_id(n, 1, 1, 1);
  target0[3 * v + 0] = 0.95;  // near a corner: part of its star inverted
  target0[3 * v + 1] = 0.95;
  target0[3 * v + 2] = 0.05;
  REQUIRE(volmap::count_nonpositive(target0, m0.tets) > 0);
  auto m = m0;
  auto bnd = bnd0;
  auto target = target0;
  const auto r = volmap::cone_repair(m, bnd, target);
  CHECK(r.patches == 1);
  CHECK(r.failed_clusters == 0);
  // R is the whole cube (stars of boundary vertices); its only interior vertex is in the source kernel
  // (the cube is convex), so it is the apex: connectivity = the cones over the 48 boundary triangles.
  CHECK(r.vertices_added == 0);
  CHECK(m.num_tets() == 48);
  check_refinement(m0, target0, bnd0, m, target, bnd);
}

TEST_CASE("cone repair: an exhausted time limit leaves the mesh and map exactly as they were") {
  const int n = 6;
  const auto m0 = map_test::kuhn_grid(n);
  const auto bnd0 = map_test::grid_boundary_flags(n);
  auto target0 = m0.xyz;
  for (int c : {grid_id(n, 1, 1, 1), grid_id(n, 4, 2, 3)})
    for (int i = 0; i < 3; ++i) target0[3 * c + i] += 0.3;
  REQUIRE(volmap::count_nonpositive(target0, m0.tets) > 0);
  auto m = m0;
  auto bnd = bnd0;
  auto target = target0;
  volmap::ConeRepairOptions o;
  o.time_limit_seconds = 1e-12;  // already over when the first cluster would start
  const auto r = volmap::cone_repair(m, bnd, target, o);
  CHECK(r.patches == 0);
  CHECK(r.failed_clusters == r.clusters);
  CHECK(r.clusters > 0);
  CHECK(m.tets == m0.tets);
  CHECK(m.xyz == m0.xyz);
  CHECK(target == target0);
  CHECK(bnd == bnd0);
  // The same state without the limit is repaired.
  const auto r2 = volmap::cone_repair(m, bnd, target);
  CHECK(r2.failed_clusters == 0);
  CHECK(volmap::count_nonpositive(target, m.tets) == 0);
}

TEST_CASE("cone repair: scattered scrambled interior vertices are all repaired") {
  const int n = 6;
  GridCase gc(n);
  const auto& [m0, bnd0, target0] = std::tie(gc.m0, gc.bnd0, gc.target0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.25, 0.25);
  for (int c : {grid_id(n, 1, 1, 1), grid_id(n, 4, 2, 3), grid_id(n, 2, 5, 4), grid_id(n, 3, 3, 1), grid_id(n, 5, 5, 5)})
    for (int i = 0; i < 3; ++i) gc.target0[3 * c + i] += u(rng);
  const std::size_t bad0 = volmap::count_nonpositive(target0, m0.tets);
  REQUIRE(bad0 > 0);
  const auto r = gc.repair();
  const auto& [m, bnd, target] = std::tie(gc.m, gc.bnd, gc.target);
  CHECK(r.failed_clusters == 0);
  CHECK(r.patches >= 1);
  CHECK(r.attempts >= r.patches);
  CHECK(r.growth_steps >= r.patches);
  CHECK(r.lp_solves >= 2 * r.patches);  // a patch needs a verified kernel point in both spaces
  check_refinement(m0, target0, bnd0, m, target, bnd);
  for (int variant = 0; variant < 2; ++variant) {
    auto m2 = m0;
    auto bnd2 = bnd0;
    auto target2 = target0;
    volmap::ConeRepairOptions o;
    o.verify_shelling = true;
    if (variant == 0) o.stall_growth_steps = 0;  // no stall limit
    if (variant == 1) o.growth_lookahead = 1;    // plain most-violated-face growth
    const auto r2 = volmap::cone_repair(m2, bnd2, target2, o);
    CHECK(r2.failed_clusters == 0);
    check_refinement(m0, target0, bnd0, m2, target2, bnd2);
    if (variant == 0) {  // the stall limit only cuts failing growth: the same patches are applied
      CHECK(r2.patches == r.patches);
      CHECK(m2.tets == m.tets);
      CHECK(target2 == target);
    } else {
      CHECK(r2.lp_solves <= r.lp_solves);  // the lookahead solves extra LPs per growth step
    }
  }
  MESSAGE("scrambled: " << bad0 << " inverted in " << r.clusters << " clusters, " << r.patches << " patches, tets " << m0.num_tets()
                        << " -> " << m.num_tets());
}

TEST_CASE("cone repair: along a scrambled bar the growth takes shelling steps, each confirmed by the full check") {
  // A 12×3×3 bar whose interior vertices are scrambled, most along the bar: regions grow along it
  // one tet at a time, the case the shelling steps are for. GridCase::repair sets verify_shelling,
  // so a step that left a non-ball would throw.
  GridCase c = scrambled_bar_case();
  for (unsigned seed : {0u, 3u, 5u}) {
    scramble_bar(c, seed);
    REQUIRE(volmap::count_nonpositive(c.target0, c.m0.tets) > 0);
    const auto r = c.repair();
    INFO("seed " << seed);
    CHECK(r.shelling_steps > 0);
    CHECK(r.failed_clusters == 0);
    check_refinement(c.m0, c.target0, c.bnd0, c.m, c.target, c.bnd);
  }
}

TEST_CASE("cone repair: bulk growth repairs the scrambled bar in fewer growth steps, and a widened search grows in bulk") {
  // The bar of the shelling test: one tet per step against |R| / 8 more per step. Both must give a
  // valid refinement with no cluster left; bulk steps reach the same kernels in fewer LP steps.
  GridCase c = scrambled_bar_case();
  std::size_t steps_single = 0, steps_bulk = 0;
  for (unsigned seed : {0u, 3u, 5u}) {
    scramble_bar(c, seed);
    INFO("seed " << seed);
    const auto single = c.repair();
    CHECK(single.failed_clusters == 0);
    steps_single += single.growth_steps;
    volmap::ConeRepairOptions o;
    o.bulk_growth_divisor = 8;
    const auto bulk = c.repair(o);
    CHECK(bulk.failed_clusters == 0);
    check_refinement(c.m0, c.target0, c.bnd0, c.m, c.target, c.bnd);
    steps_bulk += bulk.growth_steps;
  }
  MESSAGE("growth steps: one tet per step " << steps_single << ", bulk " << steps_bulk);
  CHECK(steps_bulk < steps_single);
  volmap::ConeRepairOptions o;
  volmap::widen_growth_limits(o, 0);
  CHECK(o.bulk_growth_divisor == 0);
  volmap::widen_growth_limits(o, 1);
  CHECK(o.bulk_growth_divisor == 64);
  o.bulk_growth_divisor = 5;
  volmap::widen_growth_limits(o, 1);
  CHECK(o.bulk_growth_divisor == 5);
}

// Bars whose first unit of length is mirrored (x -> 1 − x for x <= 1: those tets and boundary faces
// inside out, the rest of the map the identity): a region with mirrored ∂M faces on two opposite
// sides has no target kernel point, and no larger region has one. The growth stops as soon as the
// ∂M faces of ∂R alone rule the kernel out; without that stop it runs on along the bar to its other
// limits. Both must end the same way, the stop with less work.
TEST_CASE("cone repair: the growth stops when the mesh boundary alone rules out a kernel, with the same outcome") {
  auto mirrored = [](const volmap::TetMeshData& m) {
    auto t = m.xyz;
    for (std::size_t v = 0; v < m.num_vertices(); ++v)
      if (m.xyz[3 * v] <= 1.0) t[3 * v] = 1.0 - m.xyz[3 * v];
    return t;
  };
  auto boundary_flags = [](const volmap::TetMeshData& m) {
    std::vector<std::uint8_t> flags(m.num_vertices(), 0);
    for (std::uint32_t v : volmap::boundary_vertex_ids(m)) flags[v] = 1;
    return flags;
  };
  auto all_cells = [](std::size_t, std::size_t, std::size_t) { return true; };
  for (std::size_t width : {2, 3}) {
    CAPTURE(width);
    const auto m0 = volmap::generate_kuhn_grid(12, width, width, all_cells, 0.5);  // x in [0, 6]
    const auto bnd0 = boundary_flags(m0);
    const auto target0 = mirrored(m0);
    REQUIRE(volmap::count_nonpositive(target0, m0.tets) > 0);
    volmap::ConeRepairResult result[2];
    volmap::TetMeshData mesh[2] = {m0, m0};
    std::vector<double> target[2] = {target0, target0};
    std::vector<std::uint8_t> bnd[2] = {bnd0, bnd0};
    for (int stop = 0; stop < 2; ++stop) {
      volmap::ConeRepairOptions o;
      o.stop_at_mesh_boundary = stop == 1;
      result[stop] = volmap::cone_repair(mesh[stop], bnd[stop], target[stop], o);
      refinement_checks::check_unchanged(m0, target0, bnd0, mesh[stop], target[stop], bnd[stop]);
      CHECK(result[stop].patches == 0);
    }
    CHECK(result[0].failed_clusters == result[1].failed_clusters);
    CHECK(result[0].failures.mesh_boundary == 0);
    CHECK(result[1].failures.mesh_boundary > 0);
    CHECK(result[1].growth_steps < result[0].growth_steps);
  }
}

TEST_CASE("cone repair: an impossible region fails and leaves the mesh unchanged") {
  SUBCASE("a mirrored map: no region has a target kernel point") {
    // x -> 1 - x turns every tet inside out, boundary images included: each boundary face's inner
    // side is then outside the cube, so a region with faces on two opposite sides of the cube has
    // an empty target kernel, and the one cluster (every tet) must grow to those.
    const int n = 2;
    const auto m0 = map_test::kuhn_grid(n);
    auto bnd = map_test::grid_boundary_flags(n);
    auto target0 = m0.xyz;
    for (std::size_t v = 0; v < m0.num_vertices(); ++v) target0[3 * v] = 1.0 - m0.xyz[3 * v];
    REQUIRE(volmap::count_nonpositive(target0, m0.tets) == m0.num_tets());
    auto m = m0;
    auto target = target0;
    const auto bnd0 = bnd;
    const auto r = volmap::cone_repair(m, bnd, target);
    CHECK(r.failed_clusters > 0);
    CHECK(r.patches == 0);
    CHECK(r.failures.reinsertion + r.failures.not_positive + r.failures.face_mismatch == 0);
    refinement_checks::check_unchanged(m0, target0, bnd0, m, target, bnd);
  }
  SUBCASE("region limit too small; widened until the repair succeeds") {
    const int n = 4;
    GridCase c(n);
    const int v = grid_id(n, 2, 2, 2);
    for (int i = 0; i < 3; ++i) c.target0[3 * v + i] += 0.3;
    volmap::ConeRepairOptions o;
    o.max_region_tets = 4;
    o.search_escalations = 0;
    const auto r = c.repair(o);
    const auto& [m0, target0, m, target] = std::tie(c.m0, c.target0, c.m, c.target);
    CHECK(r.failed_clusters > 0);
    CHECK(r.patches == 0);
    CHECK(m.tets == m0.tets);
    CHECK(m.xyz == m0.xyz);
    CHECK(target == target0);
    // Diagnostics: every failed attempt has exactly one reason, here the region limit.
    CHECK(r.attempts == r.failures.region_limit);
    CHECK(r.failures.last_no_target + r.failures.last_no_source <= r.failures.region_limit);
    CHECK(r.failures.reinsertion + r.failures.not_positive + r.failures.face_mismatch + r.failures.budget == 0);

    // The same cluster: a round that repairs nothing is repeated with the limits ×4 (4, 16, 64 tets).
    o.search_escalations = 3;
    const auto w = c.repair(o);
    CHECK(w.search_escalations >= 1);
    CHECK(w.failed_clusters == 0);
    CHECK(w.patches >= 1);
    CHECK(w.max_region > 4);
    CHECK(w.failures.region_limit >= 1);  // the attempts before the widening
    check_refinement(m0, target0, c.bnd0, m, target, c.bnd);
  }
  SUBCASE("tet budget too small") {
    const int n = 4;
    GridCase gc(n);
    for (int c : {grid_id(n, 2, 2, 2), grid_id(n, 1, 2, 2)})
      for (int i = 0; i < 3; ++i) gc.target0[3 * c + i] += 0.3;
    volmap::ConeRepairOptions o;
    o.max_added_tets = 1;
    const auto r = gc.repair(o);
    const auto& [m0, m, target] = std::tie(gc.m0, gc.m, gc.target);
    // Whatever was applied stayed within the budget and valid; the rest is left as it was.
    CHECK(long(m.num_tets()) - long(m0.num_tets()) <= 1);
    CHECK(volmap::count_nonpositive(m.xyz, m.tets) == 0);
    if (r.failed_clusters == 0) CHECK(volmap::count_nonpositive(target, m.tets) == 0);
  }
}

TEST_CASE("cone repair: a region whose patch exceeds the tet budget absorbs boundary vertices until it fits") {
  // A free vertex next to the bottom face pushed 1.5 spacings through it: the first ball with both
  // kernels is thin (it hugs ∂M), so its patch adds tets. With a budget of 1 the repair must not give
  // up on that region (the growth is deterministic: every retry finds the same one) but grow it by
  // whole vertex stars, keeping both kernels, until the cones replace more tets than they add.
  const int n = 4;
  GridCase gc(n);
  const int v = grid_id(n, 1, 2, 2);  // the first index runs along z
  gc.target0[3 * v + 2] -= 1.5 / n;
  REQUIRE(volmap::count_nonpositive(gc.target0, gc.m0.tets) > 0);
  const auto unlimited = gc.repair();
  REQUIRE(unlimited.failed_clusters == 0);
  const long first_growth = long(gc.m.num_tets()) - long(gc.m0.num_tets());
  CHECK(unlimited.absorbed_vertices == 0);  // no budget: the first region is patched as it is
  CHECK(first_growth > 1);                  // the premise: that patch does not fit a budget of 1
  volmap::ConeRepairOptions o;
  o.max_added_tets = 1;
  const auto r = gc.repair(o);
  CHECK(r.failed_clusters == 0);
  CHECK(r.patches >= 1);
  CHECK(r.failures.budget == 0);
  CHECK(r.absorbed_vertices >= 1);
  CHECK(r.max_region > unlimited.max_region);
  CHECK(long(gc.m.num_tets()) - long(gc.m0.num_tets()) <= 1);
  check_refinement(gc.m0, gc.target0, gc.bnd0, gc.m, gc.target, gc.bnd);
  MESSAGE("budget 1: region " << unlimited.max_region << " -> " << r.max_region << " tets, growth " << first_growth << " -> "
                              << long(gc.m.num_tets()) - long(gc.m0.num_tets()) << ", " << r.absorbed_vertices << " vertices absorbed");
}

TEST_CASE("cone repair on a TetMesh: every property follows the patches, the boundary and locked targets stay bit-identical") {
  // Oracles: a tet property and the tet labels are both copied from the same parent, so after the
  // repair label == 1000 + tag on every live tet; the oriented boundary triangles (brute force over
  // the live tets) and every original vertex (position, locked target, vertex property) unchanged.
  const int n = 6;
  volmap::TetMeshData data = map_test::kuhn_grid(n);
  for (std::size_t t = 0; t < data.num_tets(); ++t) data.tet_labels[t] = std::int32_t(1000 + t);
  const auto bnd = map_test::grid_boundary_flags(n);
  std::vector<double> target0 = data.xyz;
  for (int c : {grid_id(n, 1, 1, 1), grid_id(n, 4, 2, 3), grid_id(n, 3, 4, 4)})
    for (int i = 0; i < 3; ++i) target0[3 * c + i] += 0.3;
  REQUIRE(volmap::count_nonpositive(target0, data.tets) > 0);
  volmap::TetMesh mesh(data);
  volmap::PositionProperty target(mesh);
  volmap::VertexProperty<std::uint8_t> locked(mesh);
  volmap::TetProperty<int> tag(mesh, -1);
  volmap::VertexProperty<double> weight(mesh, -1.0);
  for (std::uint32_t v = 0; v < mesh.num_vertex_slots(); ++v) {
    for (int i = 0; i < 3; ++i) target[volmap::VertexId(v)][i] = target0[3 * v + i];
    locked[volmap::VertexId(v)] = bnd[v];
    weight[volmap::VertexId(v)] = 0.5 * v;
  }
  for (std::uint32_t t = 0; t < mesh.num_tet_slots(); ++t) tag[volmap::TetId(t)] = int(t);
  const auto boundary0 = mesh_test::oriented_boundary(mesh);
  const std::vector<double> positions0 = mesh.positions();
  const std::size_t nv0 = mesh.num_vertices();
  const auto r = volmap::cone_repair(mesh, target, locked);
  CHECK(r.patches >= 1);
  CHECK(r.failed_clusters == 0);
  CHECK(mesh.num_free_tet_slots() + mesh.num_tets() == mesh.num_tet_slots());
  const auto inv = mesh.check_invariants(true);  // source exactly positive, structure sound
  CHECK_MESSAGE(inv.ok, inv.problem);
  CHECK(mesh_test::oriented_boundary(mesh) == boundary0);
  CHECK(mesh.num_vertices() == nv0 + r.vertices_added);
  for (std::uint32_t v = 0; v < nv0; ++v) {
    const volmap::VertexId id(v);
    REQUIRE(mesh.vertex_is_live(id));
    for (int i = 0; i < 3; ++i) CHECK(mesh.vertex_position(id)[i] == positions0[3 * v + i]);
    CHECK(locked[id] == bnd[v]);
    CHECK(weight[id] == 0.5 * v);
    if (bnd[v])
      for (int i = 0; i < 3; ++i) CHECK(target[id][i] == target0[3 * v + i]);
  }
  for (std::uint32_t v = std::uint32_t(nv0); v < mesh.num_vertex_slots(); ++v) {
    CHECK(locked[volmap::VertexId(v)] == 0);
    CHECK(weight[volmap::VertexId(v)] == -1.0);
  }
  std::size_t replaced = 0;
  for (std::uint32_t t = 0; t < mesh.num_tet_slots(); ++t) {
    const volmap::TetId id(t);
    if (!mesh.tet_is_live(id)) continue;
    CHECK(tag[id] >= 0);
    CHECK(mesh.tet_labels()[t] == 1000 + tag[id]);
    const auto v = mesh.tet_vertices(id);
    CHECK(volmap::orient3d(target[v[0]].data(), target[v[1]].data(), target[v[2]].data(), target[v[3]].data()) > 0);
    bool same = t < data.num_tets();
    for (int i = 0; i < 4 && same; ++i) same = v[i].idx() == data.tets[4 * t + i];
    if (same) CHECK(tag[id] == int(t));  // untouched tets keep their slot, vertices and values
    replaced += !same;
  }
  CHECK(replaced > 0);
}

// An impossible case even with refinement: the boundary map mirrors the unit cube (x -> 1 - x).
// The image surface is embedded but reversed, so the signed volumes of any tetrahedralisation
// mapped with it sum to minus the cube's volume: no map with every tet positive exists, however
// the mesh is refined. The mapper must say so (exit 1, "certified": false) within its time limit.
TEST_CASE("volmap-map: no false success with refinement allowed when the boundary map is mirrored (exit 1)") {
  const auto tool = volmap_test::tool("volmap-map");
  if (!std::filesystem::exists(tool)) {
    MESSAGE("skipped: volmap-map not built");
    return;
  }
  const int n = 3;
  const auto m = map_test::kuhn_grid(n);
  const auto bnd = map_test::grid_boundary_flags(n);
  volmap::BoundaryMap map;
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    if (bnd[v]) {
      map.vids.push_back(std::uint32_t(v));
      map.xyz.push_back(1.0 - m.xyz[3 * v]);
      map.xyz.push_back(m.xyz[3 * v + 1]);
      map.xyz.push_back(m.xyz[3 * v + 2]);
    }
  const auto dir = volmap_test::scratch_dir("cone_repair_nfs");
  volmap::write_medit((dir / "in.mesh").string(), m);
  volmap::write_boundary_map((dir / "map.txt").string(), map);
  const std::string cmd = tool.string() + " " + (dir / "in.mesh").string() + " " + (dir / "map.txt").string() + " " +
                          (dir / "out.mesh").string() + " --refined-input " + (dir / "ref.mesh").string() +
                          " --time-limit 3 --threads 1 --json > " + (dir / "out.json").string() + " 2>/dev/null";
  const int rc = std::system(cmd.c_str());
  CHECK(WEXITSTATUS(rc) == 1);
  std::ifstream json_file(dir / "out.json");
  const std::string json((std::istreambuf_iterator<char>(json_file)), std::istreambuf_iterator<char>());
  CHECK(json.find("\"certified\":false") != std::string::npos);
  CHECK(json.find("\"certified\":true") == std::string::npos);
  CHECK(json.find("\"boundary_volume_sign\":-1") != std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST_CASE("volmap-map: G1 bone octa is certified with refinement within 5 % growth and map-check agrees") {
  VOLMAP_REQUIRE_DATA(mesh, "volmap/G1/bone.mesh");
  VOLMAP_REQUIRE_DATA(mp, "volmap/G1_octa/bone_octa.txt");
  const auto tool = volmap_test::tool("volmap-map"), check = volmap_test::tool("volmap-map-check");
  if (!std::filesystem::exists(tool) || !std::filesystem::exists(check)) {
    MESSAGE("skipped: volmap-map / volmap-map-check not built");
    return;
  }
  const auto dir = volmap_test::scratch_dir("cone_repair_bone");
  const std::string out = (dir / "out.mesh").string(), ref = (dir / "ref.mesh").string(), js = (dir / "r.json").string();
  const std::string cmd = tool.string() + " " + mesh.string() + " " + mp.string() + " " + out + " --refined-input " + ref +
                          " --threads 1 --time-limit 20 --no-quality --json > " + js + " 2>/dev/null";
  const int rc = std::system(cmd.c_str());
  const auto j = nlohmann::json::parse(volmap_test::read_bytes(js), nullptr, false);
  REQUIRE(!j.is_discarded());
  MESSAGE("bone octa: " << j.dump());
  CHECK(WEXITSTATUS(rc) == 0);
  CHECK(j.value("certified", false));
  CHECK(j.value("growth", 1.0) <= 0.05);
  const std::string src = j.value("refined", false) ? ref : mesh.string();
  const int rc2 = std::system((check.string() + " " + src + " " + out + " --boundary " + mp.string() + " --absolute > /dev/null 2>&1").c_str());
  CHECK(WEXITSTATUS(rc2) == 0);
  std::filesystem::remove_all(dir);
}
