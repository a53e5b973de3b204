// plucker_line / side / gordan_certifies_no_line against independent oracles: the side product of
// two lines agrees with −orient3d of their four points at random grid points (the exact orient3d
// predicate decides); a certificate is accepted for a ring of segments that no line sees all on one
// side by construction (a bow-tie, multipliers derived by hand) and refused for every multiplier
// vector tried when a witness line is strictly on the required side of all of them.
#include <doctest/doctest.h>
#include <volmap/predicates_rational.hpp>

#include <array>
#include <random>
#include <vector>

using volmap::Rational;
using Point = std::array<double, 3>;

namespace {
int sign_of(const Rational& x) { return x > 0 ? 1 : x < 0 ? -1 : 0; }
std::vector<volmap::PluckerLine> ring_lines(const std::vector<Point>& ring) {
  std::vector<volmap::PluckerLine> lines;
  for (std::size_t i = 0; i < ring.size(); ++i) lines.push_back(volmap::plucker_line(ring[i].data(), ring[(i + 1) % ring.size()].data()));
  return lines;
}
}  // namespace

TEST_CASE("side(line(u, v), line(x, y)) = -orient3d(u, v, x, y) in sign") {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> g(-6, 6);
  int zeros = 0;
  for (int it = 0; it < 3000; ++it) {
    Point p[4];
    for (auto& q : p)
      for (auto& c : q) c = g(rng) * 0.25;
    const Rational s = volmap::side(volmap::plucker_line(p[0].data(), p[1].data()), volmap::plucker_line(p[2].data(), p[3].data()));
    const int o = volmap::orient3d(p[0].data(), p[1].data(), p[2].data(), p[3].data());
    CHECK(sign_of(s) == -o);
    zeros += o == 0;
  }
  CHECK(zeros > 0);  // the grid hits degenerate cases too
}

TEST_CASE("gordan_certifies_no_line: a bow-tie ring in a plane, and a convex ring that a line passes through") {
  // Bow-tie x1 x2 x3 x4 in z = 0: Σ L_j = 0 (directions (2,2,0) + (0,-2,0) + (-2,2,0) + (0,-2,0) and
  // moments (0,0,0) + (0,0,-2) + (0,0,0) + (0,0,2)), so no line is on one side of all four segments.
  const auto bowtie = ring_lines({{-1, -1, 0}, {1, 1, 0}, {1, -1, 0}, {-1, 1, 0}});
  CHECK(volmap::gordan_certifies_no_line(bowtie, std::vector<Rational>(4, Rational(1))));
  CHECK(volmap::gordan_certifies_no_line(bowtie, std::vector<Rational>(4, Rational(5, 3))));
  CHECK_FALSE(volmap::gordan_certifies_no_line(bowtie, {Rational(1), Rational(1), Rational(1), Rational(2)}));
  CHECK_FALSE(volmap::gordan_certifies_no_line(bowtie, std::vector<Rational>(4, Rational(0))));
  CHECK_FALSE(volmap::gordan_certifies_no_line(bowtie, std::vector<Rational>(4, Rational(-1))));
  CHECK_FALSE(volmap::gordan_certifies_no_line(bowtie, {Rational(1)}));  // sizes differ
  CHECK_FALSE(volmap::gordan_certifies_no_line({}, {}));
  // A segment and its reverse: λ = (1, 1).
  const Point a = {0.3, -1.1, 2}, b = {1.7, 0.2, -0.4};
  CHECK(volmap::gordan_certifies_no_line({volmap::plucker_line(a.data(), b.data()), volmap::plucker_line(b.data(), a.data())},
                                         {Rational(1), Rational(1)}));
  // A convex square ring: the z axis sees every segment counter-clockwise, orient3d(u, v, x, y) > 0
  // for u = (0,0,1), v = (0,0,-1) — a witness, so no multipliers can certify.
  const std::vector<Point> square = {{1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {-1, -1, 0}};
  const Point u = {0, 0, 1}, v = {0, 0, -1};
  for (std::size_t i = 0; i < 4; ++i) REQUIRE(volmap::orient3d(u.data(), v.data(), square[i].data(), square[(i + 1) % 4].data()) > 0);
  const auto lines = ring_lines(square);
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> g(0, 4);
  for (int it = 0; it < 200; ++it) {
    std::vector<Rational> lambda(4);
    for (auto& x : lambda) x = g(rng);
    CHECK_FALSE(volmap::gordan_certifies_no_line(lines, lambda));
  }
}
