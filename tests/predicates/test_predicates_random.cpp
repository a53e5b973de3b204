// Randomised cross-check of the four double predicates against the independent GMP oracle
// (predicates/testing/oracle.hpp, untranslated Laplace determinants in mpz/mpq):
//   * 10^6 cases per predicate on integer-valued doubles (oracle in __int128 or mpz: cheap), mixing
//     tiny ranges (many exact degeneracies), 2^20 ranges, exact integer combinations (coplanar /
//     collinear), and integers up to 2^56 whose differences round (nonzero Two-Diff tails);
//   * a smaller set of general doubles (oracle in mpq): uniform, mesh-like, near-degenerate, and
//     log-uniform exponents over the whole double range (subnormals to 2^1000).
// For the three small integer modes (|x| ≤ 2^20) the oracle runs in __int128: the 5×5 insphere
// Laplace sum is below 120·3·2^100 < 2^109, so nothing overflows.
#include <doctest/doctest.h>
#include <volmap/predicates.hpp>

#include "../../predicates/testing/oracle.hpp"

#include <cmath>
#include <random>

namespace or_ = volmap_oracle;

namespace {

constexpr int kIntegerCases = 1000000;

struct IntegerSource {
  std::mt19937_64 rng;
  explicit IntegerSource(unsigned seed) : rng(seed) {}
  // Fills n points of dim coordinates; the mode cycles with the case index.
  void fill(double (*p)[3], int n, int dim, int mode) {
    std::uniform_int_distribution<long> tiny(-3, 3), mid(-(1L << 20), 1L << 20), big(-(1L << 26), 1L << 26);
    std::uniform_int_distribution<int> shift(0, 30);
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < dim; ++k) {
        switch (mode) {
          case 0: p[i][k] = double(tiny(rng)); break;
          case 1:
          case 3: p[i][k] = double(mid(rng)); break;
          default: p[i][k] = std::ldexp(double(big(rng)), shift(rng)); break;  // up to 2^56, exact
        }
      }
    if (mode == 3 && n >= 4) {  // last point an exact integer combination (coplanar / collinear)
      const long s = tiny(rng), t = tiny(rng);
      for (int k = 0; k < dim; ++k) p[n - 1][k] = p[0][k] + s * (p[1][k] - p[0][k]) + t * (p[2][k] - p[0][k]);
    }
  }
};

struct DoubleSource {
  std::mt19937_64 rng;
  explicit DoubleSource(unsigned seed) : rng(seed) {}
  double log_uniform() {
    std::uniform_int_distribution<int> e(-1074, 1000);
    std::uniform_real_distribution<double> m(0.5, 1.0);
    std::bernoulli_distribution neg(0.5), zero(0.05);
    if (zero(rng)) return 0.0;
    const double v = std::ldexp(m(rng), e(rng));
    return neg(rng) ? -v : v;
  }
  void fill(double (*p)[3], int n, int dim, int mode) {
    std::uniform_real_distribution<double> u(-1.0, 1.0), small(-1e-3, 1e-3);
    switch (mode) {
      case 0:
        for (int i = 0; i < n; ++i)
          for (int k = 0; k < dim; ++k) p[i][k] = u(rng);
        break;
      case 1: {  // mesh-like: a small simplex around a point
        double c[3] = {u(rng) * 10, u(rng) * 10, u(rng) * 10};
        for (int i = 0; i < n; ++i)
          for (int k = 0; k < dim; ++k) p[i][k] = c[k] + small(rng);
        break;
      }
      case 2:
        for (int i = 0; i < n; ++i)
          for (int k = 0; k < dim; ++k) p[i][k] = log_uniform();
        break;
      default:  // near-degenerate
        if (dim == 3 && n == 4) or_::near_coplanar(rng, p[0], p[1], p[2], p[3]);
        else if (dim == 2 && n == 4) or_::near_cocircular(rng, p[0], p[1], p[2], p[3]);
        else if (dim == 3 && n == 5) or_::near_cospherical(rng, p[0], p[1], p[2], p[3], p[4]);
        else or_::near_collinear(rng, p[0], p[1], p[2]);  // orient2d: rounded point on a line
    }
  }
};

struct Tally {
  long wrong = 0, zeros = 0, naive_wrong = 0;
};

}  // namespace

TEST_CASE("orient2d: 10^6 integer cases + 10^5 doubles vs GMP oracle") {
  IntegerSource is(1);
  Tally t;
  double p[5][3];
  for (int i = 0; i < kIntegerCases; ++i) {
    is.fill(p, 3, 2, i % 4);
    const int e = (i % 4 != 2) ? or_::orient2d<__int128>(p[0], p[1], p[2]) : or_::orient2d<or_::Z>(p[0], p[1], p[2]);
    t.zeros += e == 0;
    t.wrong += volmap::orient2d(p[0], p[1], p[2]) != e;
  }
  CHECK(t.wrong == 0);
  CHECK(t.zeros > 10000);
  DoubleSource ds(2);
  for (int i = 0; i < 100000; ++i) {
    ds.fill(p, 3, 2, i % 4);
    const int e = or_::orient2d(p[0], p[1], p[2]);
    t.naive_wrong += or_::naive_sign(or_::naive_orient2d(p[0], p[1], p[2])) != e;
    t.wrong += volmap::orient2d(p[0], p[1], p[2]) != e;
  }
  CHECK(t.wrong == 0);
  CHECK(t.naive_wrong > 100);
}

TEST_CASE("orient3d: 10^6 integer cases + 10^5 doubles vs GMP oracle") {
  IntegerSource is(3);
  Tally t;
  double p[5][3];
  for (int i = 0; i < kIntegerCases; ++i) {
    is.fill(p, 4, 3, i % 4);
    const int e = (i % 4 != 2) ? or_::orient3d<__int128>(p[0], p[1], p[2], p[3]) : or_::orient3d<or_::Z>(p[0], p[1], p[2], p[3]);
    t.zeros += e == 0;
    t.wrong += volmap::orient3d(p[0], p[1], p[2], p[3]) != e;
  }
  CHECK(t.wrong == 0);
  CHECK(t.zeros > 50000);
  DoubleSource ds(4);
  for (int i = 0; i < 100000; ++i) {
    ds.fill(p, 4, 3, i % 4);
    const int e = or_::orient3d(p[0], p[1], p[2], p[3]);
    t.naive_wrong += or_::naive_sign(or_::naive_orient3d(p[0], p[1], p[2], p[3])) != e;
    t.wrong += volmap::orient3d(p[0], p[1], p[2], p[3]) != e;
  }
  CHECK(t.wrong == 0);
  CHECK(t.naive_wrong > 100);
}

TEST_CASE("incircle: 10^6 integer cases + 5·10^4 doubles vs GMP oracle") {
  IntegerSource is(5);
  Tally t;
  double p[5][3];
  for (int i = 0; i < kIntegerCases; ++i) {
    is.fill(p, 4, 2, i % 4);
    const int e = (i % 4 != 2) ? or_::incircle<__int128>(p[0], p[1], p[2], p[3]) : or_::incircle<or_::Z>(p[0], p[1], p[2], p[3]);
    t.zeros += e == 0;
    t.wrong += volmap::incircle(p[0], p[1], p[2], p[3]) != e;
  }
  CHECK(t.wrong == 0);
  CHECK(t.zeros > 20000);
  DoubleSource ds(6);
  for (int i = 0; i < 50000; ++i) {
    ds.fill(p, 4, 2, i % 4);
    const int e = or_::incircle(p[0], p[1], p[2], p[3]);
    t.naive_wrong += or_::naive_sign(or_::naive_incircle(p[0], p[1], p[2], p[3])) != e;
    t.wrong += volmap::incircle(p[0], p[1], p[2], p[3]) != e;
  }
  CHECK(t.wrong == 0);
  CHECK(t.naive_wrong > 100);
}

TEST_CASE("insphere: 10^6 integer cases + 2·10^4 doubles vs GMP oracle") {
  IntegerSource is(7);
  Tally t;
  double p[5][3];
  for (int i = 0; i < kIntegerCases; ++i) {
    is.fill(p, 5, 3, i % 4);
    const int e = (i % 4 != 2) ? or_::insphere<__int128>(p[0], p[1], p[2], p[3], p[4]) : or_::insphere<or_::Z>(p[0], p[1], p[2], p[3], p[4]);
    t.zeros += e == 0;
    t.wrong += volmap::insphere(p[0], p[1], p[2], p[3], p[4]) != e;
  }
  CHECK(t.wrong == 0);
  CHECK(t.zeros > 20000);
  DoubleSource ds(8);
  for (int i = 0; i < 20000; ++i) {
    ds.fill(p, 5, 3, i % 4);
    const int e = or_::insphere(p[0], p[1], p[2], p[3], p[4]);
    t.naive_wrong += or_::naive_sign(or_::naive_insphere(p[0], p[1], p[2], p[3], p[4])) != e;
    t.wrong += volmap::insphere(p[0], p[1], p[2], p[3], p[4]) != e;
  }
  CHECK(t.wrong == 0);
  CHECK(t.naive_wrong > 100);
}

// Heavier volumes of general doubles (mpq oracle): ctest label "long", excluded from the default run.
TEST_SUITE("long") {
  TEST_CASE("all four predicates: 10^6 general doubles each vs GMP mpq oracle") {
    DoubleSource ds(99);
    long wrong[4] = {0, 0, 0, 0};
    double p[5][3];
    for (int i = 0; i < 1000000; ++i) {
      ds.fill(p, 3, 2, i % 4);
      wrong[0] += volmap::orient2d(p[0], p[1], p[2]) != or_::orient2d(p[0], p[1], p[2]);
      ds.fill(p, 4, 3, i % 4);
      wrong[1] += volmap::orient3d(p[0], p[1], p[2], p[3]) != or_::orient3d(p[0], p[1], p[2], p[3]);
      ds.fill(p, 4, 2, i % 4);
      wrong[2] += volmap::incircle(p[0], p[1], p[2], p[3]) != or_::incircle(p[0], p[1], p[2], p[3]);
      ds.fill(p, 5, 3, i % 4);
      wrong[3] += volmap::insphere(p[0], p[1], p[2], p[3], p[4]) != or_::insphere(p[0], p[1], p[2], p[3], p[4]);
    }
    CHECK(wrong[0] == 0);
    CHECK(wrong[1] == 0);
    CHECK(wrong[2] == 0);
    CHECK(wrong[3] == 0);
  }
}
