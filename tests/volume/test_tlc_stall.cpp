// The untanglers' stall stop (GuardedObjective::stall_evaluations / stall_max_bad, used by TLC's
// hand-over to B1): a scripted sequence of double counts is the oracle for when it must stop and at
// which point it leaves the run.
#include <doctest/doctest.h>

#if defined(VOLMAP_TEST_UNTANGLE_SUPPORT)
#include "untangle_support.hpp"

#include <cstddef>
#include <vector>

namespace {

// Evaluates the objective at x = (k) for k = 0, 1, ... with the scripted counts; returns the index
// of the evaluation that threw StallStop (-1 when none did) and the point it left in last_x.
long run_script(volmap::untangle::GuardedObjective& obj, const std::vector<std::size_t>& counts, double* left_at) {
  std::size_t k = 0;
  obj.stop_when_certified = false;
  obj.evaluate = [&](const double*, double*, bool* all_positive) {
    obj.double_nonpositive = counts[k];
    *all_positive = counts[k] == 0;
    return 1.0;
  };
  Eigen::VectorXd x(1), g(1);
  for (; k < counts.size(); ++k) {
    x[0] = double(k);
    try {
      obj(x, g);
    } catch (const volmap::untangle::StallStop&) {
      *left_at = obj.last_x[0];
      return long(k);
    }
  }
  return -1;
}

volmap::untangle::GuardedObjective stall_objective(long evaluations, std::size_t max_bad) {
  volmap::untangle::GuardedObjective obj;
  obj.stall_evaluations = evaluations;
  obj.stall_max_bad = max_bad;
  return obj;
}

}  // namespace

TEST_CASE("stall stop: after stall_evaluations without a new minimum within stall_max_bad, at the minimum") {
  const std::vector<std::size_t> counts = {40, 12, 9, 11, 10, 8, 12, 9, 13, 9, 9, 9, 9, 9};
  double left_at = -1;
  SUBCASE("enabled: 9 at 2, a new minimum 8 at 5 restarts the wait, no better one in the next 4 -> stop at 9, left at 5") {
    auto obj = stall_objective(4, 10);
    CHECK(run_script(obj, counts, &left_at) == 9);
    CHECK(left_at == 5.0);
  }
  SUBCASE("a repeated count is not a new minimum: the 9s at 5 and 7 do not restart the wait from 2") {
    const std::vector<std::size_t> repeats = {40, 12, 9, 11, 10, 9, 12, 9, 13};
    auto obj = stall_objective(4, 10);
    CHECK(run_script(obj, repeats, &left_at) == 6);
    CHECK(left_at == 2.0);
  }
  SUBCASE("minimum never within the bound: no stop") {
    auto obj = stall_objective(4, 7);
    CHECK(run_script(obj, counts, &left_at) == -1);
  }
  SUBCASE("disabled (stall_evaluations 0): no stop") {
    auto obj = stall_objective(0, 100);
    CHECK(run_script(obj, counts, &left_at) == -1);
  }
}

TEST_CASE("CappedBacktracking: no trial step moves a variable farther than max_move") {
  // f(x) = |x - c|² / 2 from x = 0 with c = (100, 50): L-BFGS's first trial step has unit length
  // (x = d/|d|, a move of 0.89 in the first variable); with max_move 0.1 it must be at most 0.1.
  for (double cap : {0.0, 0.1}) {
    volmap::untangle::GuardedObjective obj;
    obj.stop_when_certified = false;
    obj.max_move = cap;
    std::vector<Eigen::VectorXd> points;
    const Eigen::Vector2d c(100, 50);
    obj.evaluate = [&](const double* v, double* g, bool* all_positive) {
      const Eigen::Vector2d x(v[0], v[1]);
      points.emplace_back(x);
      if (g) {
        g[0] = x[0] - c[0];
        g[1] = x[1] - c[1];
      }
      *all_positive = true;
      return 0.5 * (x - c).squaredNorm();
    };
    LBFGSpp::LBFGSParam<double> param = volmap::untangle::lbfgs_param(1, 1e-12, 0, LBFGSpp::LBFGS_LINESEARCH_BACKTRACKING_ARMIJO);
    LBFGSpp::LBFGSSolver<double, volmap::untangle::CappedBacktracking> solver(param);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(2);
    volmap::untangle::run_lbfgs(solver, obj, x);
    REQUIRE(points.size() >= 2);
    const double first_move = (points[1] - points[0]).cwiseAbs().maxCoeff();
    if (cap > 0) {
      CHECK(first_move <= cap * (1 + 1e-12));
      CHECK(first_move >= cap * (1 - 1e-12));  // capped, not shrunk further: the step is accepted
    } else {
      CHECK(first_move == doctest::Approx(100 / std::sqrt(100.0 * 100 + 50 * 50)));
    }
  }
}
#endif
