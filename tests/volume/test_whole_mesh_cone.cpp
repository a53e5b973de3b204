// The last resort of the mapper (docs/mapping.md §8 step 12): when ∂M is star-shaped in the source
// and in the map's image, the whole mesh becomes one cone patch from a kernel point. Oracles: a
// convex grid under an affine boundary map is star-shaped in both spaces (every interior point is a
// kernel point); a U-shaped grid is not (the inner walls of its two arms face each other, so a kernel
// point would need x < 1 and x > 2). The mapper with a time limit too short for the cascade is
// certified by the cone and not without it.
#include <doctest/doctest.h>

#include <volmap/core/boundary_faces.hpp>
#include <volmap/predicates.hpp>
#include <volmap/testing/generate.hpp>
#include <volmap/volume/cone_repair.hpp>
#include <volmap/volume/star_shaped_boundary.hpp>
#include <volmap/volume/volume_map.hpp>

#include "map_test_meshes.hpp"
#include "refinement_checks.hpp"

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace {

// A 6×4×2 Kuhn grid (spacing 0.5, so it has interior vertices) without the cells x ∈ [1, 2],
// y ∈ [1, 2]: a U whose arms' inner walls lie on x = 1 (facing +x) and x = 2 (facing −x).
volmap::TetMeshData u_shaped_grid() {
  return volmap::generate_kuhn_grid(
      6, 4, 2, [](std::size_t i, std::size_t j, std::size_t) { return !(i >= 2 && i < 4 && j >= 2); }, 0.5);
}

std::vector<std::uint8_t> boundary_flags(const volmap::TetMeshData& m) {
  std::vector<std::uint8_t> flags(m.num_vertices(), 0);
  for (std::uint32_t v : volmap::boundary_vertex_ids(m)) flags[v] = 1;
  return flags;
}

// A source, its boundary flags and a target (…0: before), and a copy the cone works on.
struct ConeCase {
  ConeCase(volmap::TetMeshData mesh, std::vector<std::uint8_t> boundary, std::vector<double> target)
      : m0(std::move(mesh)), bnd0(std::move(boundary)), target0(std::move(target)), m(m0), bnd(bnd0), t(target0) {}
  volmap::ConeRepairResult cone(double seconds = 0) { return volmap::whole_mesh_cone(m, bnd, t, seconds); }
  const volmap::TetMeshData m0;
  const std::vector<std::uint8_t> bnd0;
  const std::vector<double> target0;
  volmap::TetMeshData m;
  std::vector<std::uint8_t> bnd;
  std::vector<double> t;
};

// The 4³ convex grid, its interior moved by up to 1.6 spacings (boundary: an affine map).
ConeCase scrambled_convex_grid() {
  auto m = map_test::kuhn_grid(4);
  auto bnd = map_test::grid_boundary_flags(4);
  auto target = map_test::scrambled_target(m, bnd, 7, 0.4);
  return ConeCase(std::move(m), std::move(bnd), std::move(target));
}

}  // namespace

TEST_CASE("whole-mesh cone: a scrambled convex grid becomes one cone patch, valid in both spaces") {
  ConeCase c = scrambled_convex_grid();
  REQUIRE(volmap::count_nonpositive(c.target0, c.m0.tets) > 50);
  CHECK(volmap::boundary_star_shaped_in_both_spaces(c.m0, map_test::boundary_map_of(c.bnd0, c.target0)));
  const auto r = c.cone();
  CHECK(r.patches == 1);
  CHECK(r.failed_clusters == 0);
  CHECK(r.max_region == c.m0.num_tets());
  // The cube is convex: every interior vertex sees all of ∂M, so one of them is the apex (no new
  // vertex); the cones over the 6·4·4·2 = 192 boundary triangles, plus at least 3 tets for each of
  // the other 26 interior vertices re-inserted.
  CHECK(r.vertices_added == 0);
  CHECK(c.m.num_tets() >= 192 + 3 * 26);
  refinement_checks::check_refinement(c.m0, c.target0, c.bnd0, c.m, c.t, c.bnd);
}

TEST_CASE("whole-mesh cone: a time limit that passes during the re-insertions leaves everything as it was") {
  ConeCase c = scrambled_convex_grid();
  const auto r = c.cone(1e-12);  // over before the first re-insertion
  CHECK(r.patches == 0);
  CHECK(r.failures.time_limit == 1);
  CHECK(r.failures.reinsertion + r.failures.not_positive == 0);
  refinement_checks::check_unchanged(c.m0, c.target0, c.bnd0, c.m, c.t, c.bnd);
  // The same without a limit is patched (the first test case).
  CHECK(c.cone().patches == 1);
}

TEST_CASE("whole-mesh cone: a U-shaped source has no kernel point, and everything is left as it was") {
  auto m = u_shaped_grid();
  auto bnd = boundary_flags(m);
  auto target = m.xyz;  // the identity: the image is the same U
  ConeCase c(std::move(m), std::move(bnd), std::move(target));
  REQUIRE(std::count(c.bnd0.begin(), c.bnd0.end(), 0) > 0);
  CHECK_FALSE(volmap::boundary_star_shaped_in_both_spaces(c.m0, map_test::boundary_map_of(c.bnd0, c.target0)));
  const auto r = c.cone();
  CHECK(r.patches == 0);
  CHECK(r.failed_clusters == 1);
  CHECK(r.failures.not_ball == 0);
  CHECK(r.failures.last_no_target == 1);  // the target is tried first
  refinement_checks::check_unchanged(c.m0, c.target0, c.bnd0, c.m, c.t, c.bnd);
}

TEST_CASE("star-shaped boundary test: false, never a throw, on a map that does not fit the mesh") {
  const int n = 2;
  const auto m = map_test::kuhn_grid(n);
  const auto bnd = map_test::grid_boundary_flags(n);
  const auto map = map_test::boundary_map_of(bnd, m.xyz);
  CHECK(volmap::boundary_star_shaped_in_both_spaces(m, map));
  auto missing = map;  // a boundary vertex without a target
  missing.vids.pop_back();
  missing.xyz.resize(3 * missing.vids.size());
  CHECK_FALSE(volmap::boundary_star_shaped_in_both_spaces(m, missing));
  auto out_of_range = map;
  out_of_range.vids.back() = std::uint32_t(m.num_vertices());
  CHECK_FALSE(volmap::boundary_star_shaped_in_both_spaces(m, out_of_range));
  auto flat = map;  // every boundary vertex on one plane: no strict kernel point in the image
  for (std::size_t k = 0; k < flat.vids.size(); ++k) flat.xyz[3 * k + 2] = 0;
  CHECK_FALSE(volmap::boundary_star_shaped_in_both_spaces(m, flat));
}

TEST_CASE("mapper: a time limit too short for the cascade ends with the whole-mesh cone, certified") {
  const int n = 5;
  const auto m = map_test::kuhn_grid(n);
  const auto bnd = map_test::grid_boundary_flags(n);
  const auto tangled = map_test::scrambled_target(m, bnd, 11, 0.5);
  REQUIRE(volmap::count_nonpositive(tangled, m.tets) > 100);
  const auto map = map_test::boundary_map_of(bnd, tangled);
  volmap::VolumeMapOptions o;
  o.initial_xyz = tangled;
  o.time_limit_seconds = 1e-9;  // every judged stage finds its time used up
  o.max_threads = 1;

  o.whole_mesh_cone = false;
  const auto without = volmap::compute_volume_map(m, map, o);
  REQUIRE_FALSE(without.certified);  // the case needs the last resort

  o.whole_mesh_cone = true;
  const auto r = volmap::compute_volume_map(m, map, o);
  CHECK(r.certified);
  CHECK(r.refined);
  CHECK(r.certified_by == "whole-mesh-cone");
  REQUIRE_FALSE(r.stages.empty());
  CHECK(r.stages.back().name == "whole-mesh-cone");
  CHECK(r.stages.back().failure.empty());
  CHECK(volmap::count_nonpositive(r.source.xyz, r.source.tets) == 0);
  CHECK(volmap::count_nonpositive(r.target_xyz, r.source.tets) == 0);
  for (std::size_t k = 0; k < map.vids.size(); ++k)
    for (int i = 0; i < 3; ++i) CHECK(r.target_xyz[3 * map.vids[k] + i] == map.xyz[3 * k + i]);
  // Growth stays within the last-resort cap (here the cone has fewer tets than the grid); a cap below
  // the cone's growth keeps the cascade's result and says why.
  CHECK(r.growth() <= o.max_growth_last_resort);
  CHECK(r.growth() < 0);
  o.max_growth = o.max_growth_last_resort = r.growth() - 0.01;
  const auto capped = volmap::compute_volume_map(m, map, o);
  CHECK_FALSE(capped.certified);
  CHECK(capped.stages.back().name == "whole-mesh-cone");
  CHECK(capped.stages.back().failure.find("max_growth_last_resort") != std::string::npos);
}
