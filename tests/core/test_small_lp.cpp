// The dense simplex of small_lp.hpp against LPs solved by hand: the optimum, its value and the dual
// values (complementary slackness: a row with slack has dual 0; the duals price the objective).
#include <doctest/doctest.h>

#include <volmap/core/small_lp.hpp>

#include <vector>

TEST_CASE("small LP: max x + y s.t. x + 2y <= 4, 3x + y <= 6 is 2.8 at (1.6, 1.2), duals (0.4, 0.2)") {
  std::vector<double> A = {1, 2, 3, 1}, b = {4, 6};
  double x[2], duals[2];
  REQUIRE(volmap::simplex_max(2, 2, A, b, {1, 1}, x, duals));
  CHECK(x[0] == doctest::Approx(1.6));
  CHECK(x[1] == doctest::Approx(1.2));
  CHECK(duals[0] == doctest::Approx(0.4));  // 0.4 (1, 2) + 0.2 (3, 1) = (1, 1)
  CHECK(duals[1] == doctest::Approx(0.2));
}

TEST_CASE("small LP: a row with slack has dual 0; an unbounded LP returns false") {
  std::vector<double> A = {1, 0, 0, 1, 1, 1}, b = {1, 1, 5};  // x <= 1, y <= 1, x + y <= 5 (slack)
  double x[2], duals[3];
  REQUIRE(volmap::simplex_max(3, 2, A, b, {2, 1}, x, duals));
  CHECK(x[0] == doctest::Approx(1));
  CHECK(x[1] == doctest::Approx(1));
  CHECK(duals[0] == doctest::Approx(2));
  CHECK(duals[1] == doctest::Approx(1));
  CHECK(duals[2] == doctest::Approx(0));
  std::vector<double> open = {1, -1}, rhs = {1};  // x - y <= 1: x, y grow together
  double z[2];
  CHECK_FALSE(volmap::simplex_max(1, 2, open, rhs, {1, 1}, z));
}
