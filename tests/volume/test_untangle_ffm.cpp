// FFM untangler: χ without cancellation, analytic gradient vs central finite differences, and
// untangling of scrambled interior vertices certified by the exact check.
#include <doctest/doctest.h>

#include <volmap/volume/ffm.hpp>
#include <volmap/volume/volume_map.hpp>
#include <volmap/predicates.hpp>

#include "map_test_meshes.hpp"

#include <cmath>
#include <random>

using map_test::scrambled_target;

TEST_CASE("chi is the smooth positive part, cancellation-free for very negative D") {
  CHECK(volmap::ffm_chi(0, 2) == doctest::Approx(1));
  CHECK(volmap::ffm_chi(3, 0) == doctest::Approx(3));
  CHECK(volmap::ffm_chi(-3, 0) == 0);
  // D = -1e8, eps = 1: the naive (D + sqrt(eps²+D²))/2 gives 0; the true value is ≈ eps²/(4|D|).
  CHECK(volmap::ffm_chi(-1e8, 1) == doctest::Approx(1.0 / 4e8).epsilon(1e-9));
  CHECK(volmap::ffm_chi(-1e8, 1) > 0);
  CHECK(volmap::ffm_chi_derivative(-1e8, 1) > 0);
  CHECK(volmap::ffm_chi_derivative(0, 1) == doctest::Approx(0.5));
  // χ' matches a finite difference.
  for (double D : {-2.0, -0.1, 0.0, 0.3, 5.0}) {
    const double h = 1e-6, eps = 0.7;
    const double fd = (volmap::ffm_chi(D + h, eps) - volmap::ffm_chi(D - h, eps)) / (2 * h);
    CHECK(volmap::ffm_chi_derivative(D, eps) == doctest::Approx(fd).epsilon(1e-6));
  }
}

TEST_CASE("FFM gradient matches central finite differences (both reference shapes, tangled and not)") {
  const int n = 3;
  auto m = map_test::kuhn_grid(n);
  auto bnd = map_test::grid_boundary_flags(n);
  auto target = scrambled_target(m, bnd, 7, 0.3);
  REQUIRE(volmap::count_nonpositive(target, m.tets) > 0);  // some tets are tangled: exercises the D < 0 branch
  for (auto ref : {volmap::ReferenceShape::RegularTet, volmap::ReferenceShape::RestShape}) {
    volmap::FfmEnergy E(m.xyz, m.tets, bnd, target, ref, 0.5);
    REQUIRE(E.num_variables() == 3 * 8);
    auto x = E.initial_variables();
    std::vector<double> g(x.size());
    for (double eps : {1.0, 0.05}) {
      E.evaluate(x.data(), eps, g.data());
      double max_err = 0, max_g = 0;
      for (std::size_t i = 0; i < x.size(); ++i) {
        const double h = 1e-6;
        auto xp = x, xm = x;
        xp[i] += h;
        xm[i] -= h;
        const double fd = (E.evaluate(xp.data(), eps, nullptr) - E.evaluate(xm.data(), eps, nullptr)) / (2 * h);
        max_err = std::max(max_err, std::abs(fd - g[i]));
        max_g = std::max(max_g, std::abs(g[i]));
      }
      INFO("eps " << eps << " max |g| " << max_g << " max err " << max_err);
      CHECK(max_g > 0);
      CHECK(max_err <= 1e-5 * std::max(1.0, max_g));
    }
  }
}

TEST_CASE("FFM energy: D > 0 exactly for VOLMAP-positive tets (reference handedness)") {
  auto m = map_test::kuhn_grid(2);
  auto bnd = map_test::grid_boundary_flags(2);
  volmap::FfmEnergy E(m.xyz, m.tets, bnd, m.xyz, volmap::ReferenceShape::RegularTet);
  auto x = E.initial_variables();
  CHECK(E.min_det(x.data()) > 0);
  // Mirror the interior vertex through the centre far away: some tets become negative.
  x[0] = 8;
  CHECK(E.min_det(x.data()) < 0);
}

TEST_CASE("FFM untangles scrambled interior vertices and the exact check certifies it") {
  const int n = 4;
  auto m = map_test::kuhn_grid(n);
  auto bnd = map_test::grid_boundary_flags(n);
  for (auto solver : {volmap::FfmSolver::Lbfgs, volmap::FfmSolver::Newton})
  for (unsigned seed : {1u, 2u, 3u}) {
    auto target = scrambled_target(m, bnd, seed, 0.8);
    const auto before = target;
    REQUIRE(volmap::count_nonpositive(target, m.tets) > 0);
    volmap::FfmOptions options;
    options.solver = solver;  // L-BFGS and Newton (SPD-projected Hessians) inner solvers
    auto r = volmap::ffm_untangle(m.xyz, m.tets, bnd, target, options);
    MESSAGE("solver " << int(solver) << " outer " << r.outer_iterations << " lbfgs " << r.lbfgs_iterations << " evals " << r.evaluations << " eps " << r.final_epsilon << " dmin " << r.min_det);
    CHECK(r.certified);
    CHECK(r.nonpositive == 0);
    CHECK(volmap::count_nonpositive(target, m.tets) == 0);
    for (std::size_t v = 0; v < m.num_vertices(); ++v)
      if (bnd[v])
        for (int i = 0; i < 3; ++i) CHECK(target[3 * v + i] == before[3 * v + i]);  // bit-exact boundary
    // Quality pass keeps validity.
    // The stop rule: an iteration lowering the energy by less than half of it ends a pass that
    // would otherwise go lower (from the same start). The longer pass keeps its lowest valid point
    // even when its line search gives up at the end (it used to return a worse trial point).
    auto early_target = target;
    auto early = volmap::ffm_quality_pass(m.xyz, m.tets, bnd, early_target, volmap::ReferenceShape::RegularTet, 200, 10, 0.5);
    CHECK(volmap::count_nonpositive(early_target, m.tets) == 0);
    auto q = volmap::ffm_quality_pass(m.xyz, m.tets, bnd, target, volmap::ReferenceShape::RegularTet, 200, 10);
    CHECK(volmap::count_nonpositive(target, m.tets) == 0);
    CHECK(q.energy_after <= q.energy_before);
    CHECK(early.energy_after < early.energy_before);
    CHECK(q.energy_after < early.energy_after);
  }
}

// A source mesh squashed to 1e-10 of its height: every tet exactly positive, none invertible as a
// rest shape in double precision (relative volume ~1e-10). Issue: the quality pass (FFM rest shape)
// used to reject such a source as "degenerate or inverted" and fail the whole map as bad input.
namespace {
volmap::TetMeshData squashed_grid(int n, double height) {
  auto m = map_test::kuhn_grid(n);
  for (std::size_t v = 0; v < m.num_vertices(); ++v) m.xyz[3 * v + 2] *= height;
  return m;
}
}  // namespace

TEST_CASE("FFM rest shape: exactly positive slivers take the regular reference instead of failing") {
  const auto flat = squashed_grid(3, 1e-10);
  REQUIRE(volmap::count_nonpositive(flat.xyz, flat.tets) == 0);  // premise: a valid source mesh
  const auto bnd = map_test::grid_boundary_flags(3);
  const auto cube = map_test::kuhn_grid(3);  // target: the unit cube itself
  const volmap::FfmEnergy squashed(flat.xyz, flat.tets, bnd, cube.xyz, volmap::ReferenceShape::RestShape);
  CHECK(squashed.unusable_rest_shapes() == flat.num_tets());
  const volmap::FfmEnergy normal(cube.xyz, cube.tets, bnd, cube.xyz, volmap::ReferenceShape::RestShape);
  CHECK(normal.unusable_rest_shapes() == 0u);
  // Energy finite with the stand-in reference.
  const auto vars = squashed.initial_variables();
  CHECK(std::isfinite(squashed.evaluate(vars.data(), 1e-3, nullptr)));
}

TEST_CASE("mapper: a valid but flat source is mapped and certified, never reported as bad input") {
  const auto flat = squashed_grid(3, 1e-10);
  const auto bnd = map_test::grid_boundary_flags(3);
  const auto cube = map_test::kuhn_grid(3);
  const auto map = map_test::boundary_map_of(bnd, cube.xyz);
  volmap::VolumeMapOptions opt;  // default cascade, quality pass on (rest shape)
  const auto r = volmap::compute_volume_map(flat, map, opt);
  CHECK(r.certified);
  CHECK(volmap::count_nonpositive(r.target_xyz, r.source.tets) == 0);
  bool quality_ran = false;
  for (const auto& s : r.stages) quality_ran |= s.name == "quality" && s.failure.empty();
  CHECK(quality_ran);
}
