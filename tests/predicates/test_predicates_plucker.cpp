// plucker_line / side / gordan_certifies_no_line / cone_holds_no_line against independent oracles:
// the side product of two lines agrees with −orient3d of their four points at random grid points (the
// exact orient3d predicate decides); a certificate is accepted for a ring of segments that no line
// sees all on one side by construction (a bow-tie, multipliers derived by hand) and refused for every
// multiplier vector tried when a witness line is strictly on the required side of all of them; a thin
// cone around a six-vector off the Klein quadric holds no line (checked at points built inside it by
// hand), a wide one holds a line given by hand.
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

namespace {
// The cone {L : |w_i·L| <= delta (L0·L)} around L0 = (1,0,0, 1,0,0) (d·m = 1: not a line), w_i the
// five unit directions orthogonal to L0 (up to scale): rows delta·L0 ± w_i.
std::vector<volmap::SixVector> cone_around_l0(const Rational& delta) {
  const volmap::SixVector l0 = {1, 0, 0, 1, 0, 0};
  const volmap::SixVector w[5] = {{0, 1, 0, 0, 0, 0}, {0, 0, 1, 0, 0, 0}, {0, 0, 0, 0, 1, 0}, {0, 0, 0, 0, 0, 1}, {1, 0, 0, -1, 0, 0}};
  std::vector<volmap::SixVector> rows;
  for (const auto& wi : w)
    for (int sign : {1, -1}) {
      volmap::SixVector r;
      for (std::size_t j = 0; j < 6; ++j) r[j] = delta * l0[j] + sign * wi[j];
      rows.push_back(r);
    }
  return rows;
}
Rational klein_form(const volmap::SixVector& l) { return 2 * (l[0] * l[3] + l[1] * l[4] + l[2] * l[5]); }
bool strictly_inside(const std::vector<volmap::SixVector>& rows, const volmap::SixVector& l) {
  for (const auto& r : rows) {
    Rational s = 0;
    for (std::size_t j = 0; j < 6; ++j) s += r[j] * l[j];
    if (s <= 0) return false;
  }
  return true;
}
}  // namespace

TEST_CASE("cone_holds_no_line: a thin cone off the Klein quadric, a wide one through a line, degenerate rows") {
  const auto thin = cone_around_l0(Rational(1, 10));
  CHECK(volmap::cone_holds_no_line(thin));
  // Oracle: points L0 + Σ t_i w_i with |t_i| < 1/20 are inside (by construction) and off the quadric.
  std::mt19937 rng(2);
  std::uniform_int_distribution<int> g(-49, 49);
  for (int it = 0; it < 300; ++it) {
    const Rational t[5] = {Rational(g(rng), 1000), Rational(g(rng), 1000), Rational(g(rng), 1000), Rational(g(rng), 1000),
                           Rational(g(rng), 1000)};
    const volmap::SixVector l = {1 + t[4], t[0], t[1], 1 - t[4], t[2], t[3]};
    REQUIRE(strictly_inside(thin, l));
    CHECK(klein_form(l) > 0);
  }
  // The x axis, (d, m) = (1,0,0, 0,0,0), is a line strictly inside the wide cone: no certificate.
  const auto wide = cone_around_l0(Rational(3));
  const volmap::SixVector x_axis = {1, 0, 0, 0, 0, 0};
  REQUIRE(strictly_inside(wide, x_axis));
  CHECK(klein_form(x_axis) == 0);
  CHECK_FALSE(volmap::cone_holds_no_line(wide));
  // Rank below six (the cone holds a linear subspace), or too few rows: no claim.
  std::vector<volmap::SixVector> flat = thin;
  for (auto& r : flat) r[5] = 0;
  CHECK_FALSE(volmap::cone_holds_no_line(flat));
  CHECK_FALSE(volmap::cone_holds_no_line({thin.begin(), thin.begin() + 5}));
}
