// The exact predicates under a flush-to-zero / denormals-are-zero floating-point environment (MXCSR
// FTZ|DAZ, what linking with -ffast-math or a host application may leave behind). The predicates must
// stay exact: they may not trust a double filter whose error analysis assumes gradual underflow.
// Expected signs come from the independent GMP oracle, computed in the default environment first
// (GMP's double conversion itself is not DAZ-proof), then the predicates run with FTZ|DAZ set.
// Cases: subnormal coordinates, coordinates whose products underflow, mixed magnitudes, nearly
// degenerate configurations, for orient2d/orient3d/incircle/insphere and the batch orient3d_tets.
// x86-64 only (MXCSR); elsewhere the test only reports that it was skipped.
#include <doctest/doctest.h>
#include <volmap/predicates.hpp>

#include "../predicates/testing/oracle.hpp"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <random>
#include <vector>

#if defined(__SSE2__)
#include <xmmintrin.h>
#define VOLMAP_TEST_HAVE_MXCSR 1
#endif

namespace or_ = volmap_oracle;

namespace {

#ifdef VOLMAP_TEST_HAVE_MXCSR
constexpr unsigned kFtz = 0x8000, kDaz = 0x0040;

// Sets FTZ|DAZ for its lifetime and checks that the hardware really flushes.
struct FlushToZero {
  unsigned saved = _mm_getcsr();
  FlushToZero() { _mm_setcsr(saved | kFtz | kDaz); }
  ~FlushToZero() { _mm_setcsr(saved); }
};

// The default environment for its lifetime (the oracle's GMP conversions need gradual underflow).
struct DefaultEnvironment {
  unsigned saved = _mm_getcsr();
  DefaultEnvironment() { _mm_setcsr(saved & ~(kFtz | kDaz | 0x6000u)); }
  ~DefaultEnvironment() { _mm_setcsr(saved); }
};

bool flushes() {
  volatile double tiny = 0x1p-1070;  // subnormal
  volatile double one = 1.0;
  return tiny * one == 0.0;
}
#endif

// Random coordinate magnitudes around 2^e for e in [lo, hi], sign random, sometimes exactly 0 or a
// subnormal.
double coordinate(std::mt19937_64& rng, int lo, int hi) {
  std::uniform_int_distribution<int> e(lo, hi), kind(0, 9);
  std::uniform_real_distribution<double> m(1.0, 2.0);
  const int k = kind(rng);
  if (k == 0) return 0.0;
  if (k == 1) return (rng() & 1 ? 1 : -1) * std::ldexp(m(rng), -1060 + int(rng() % 30));  // subnormal
  return (rng() & 1 ? 1 : -1) * std::ldexp(m(rng), e(rng));
}

struct Case {
  std::vector<double> p;  // 5 points × 3
  int o2 = 0, o3 = 0, ic = 0, is = 0;
};

std::vector<Case> make_cases() {
  std::mt19937_64 rng(20261123);
  std::vector<Case> cases;
  const int ranges[][2] = {{-1074, -1000}, {-600, -480}, {-560, -500}, {-300, -250}, {-20, 20}, {150, 200}};
  for (const auto& r : ranges)
    for (int i = 0; i < 400; ++i) {
      Case c;
      for (int k = 0; k < 15; ++k) c.p.push_back(coordinate(rng, r[0], r[1]));
      if (i % 4 == 1) {  // nearly degenerate: d and e close to a, b, c combinations
        for (int k = 0; k < 3; ++k) c.p[9 + k] = c.p[k] + (c.p[3 + k] - c.p[k]) * 0.5;
        for (int k = 0; k < 3; ++k) c.p[12 + k] = c.p[3 + k];
        c.p[12] = std::nextafter(c.p[12], 1.0);
      }
      if (i % 4 == 2) {  // mixed: one point huge-ish, others tiny
        for (int k = 0; k < 3; ++k) c.p[k] = coordinate(rng, 100, 190);
      }
      cases.push_back(c);
    }
  for (auto& c : cases) {
    const double *a = &c.p[0], *b = &c.p[3], *d3 = &c.p[6], *e = &c.p[9], *f = &c.p[12];
    c.o2 = or_::orient2d(a, b, d3);
    c.o3 = or_::orient3d(a, b, d3, e);
    c.ic = or_::incircle(a, b, d3, e);
    c.is = or_::insphere(a, b, d3, e, f);
  }
  return cases;
}

}  // namespace

TEST_CASE("predicates stay exact under FTZ|DAZ (MXCSR)") {
#ifndef VOLMAP_TEST_HAVE_MXCSR
  MESSAGE("skipped: no MXCSR on this architecture");
#else
  std::vector<Case> cases;
  {
    DefaultEnvironment env;
    cases = make_cases();  // oracle in the default environment
  }
  std::vector<double> xyz;
  std::vector<std::uint32_t> tets;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    xyz.insert(xyz.end(), cases[i].p.begin(), cases[i].p.begin() + 12);
    for (std::uint32_t k = 0; k < 4; ++k) tets.push_back(std::uint32_t(4 * i + k));
  }
  std::vector<std::int8_t> signs(cases.size());
  int wrong2 = 0, wrong3 = 0, wrongc = 0, wrongs = 0, wrongb = 0;
  bool did_flush = false;
  volmap::TetSignCounts counts;
  {
    FlushToZero ftz;
    did_flush = flushes();
    for (const auto& c : cases) {
      const double *a = &c.p[0], *b = &c.p[3], *d3 = &c.p[6], *e = &c.p[9], *f = &c.p[12];
      wrong2 += volmap::orient2d(a, b, d3) != c.o2;
      wrong3 += volmap::orient3d(a, b, d3, e) != c.o3;
      wrongc += volmap::incircle(a, b, d3, e) != c.ic;
      wrongs += volmap::insphere(a, b, d3, e, f) != c.is;
    }
    counts = volmap::orient3d_tets(xyz.data(), xyz.size() / 3, tets.data(), cases.size(), signs.data());
    for (std::size_t i = 0; i < cases.size(); ++i) wrongb += signs[i] != cases[i].o3;
    CHECK((_mm_getcsr() & (kFtz | kDaz)) == (kFtz | kDaz));  // the caller's environment is left as it was
  }
  REQUIRE(did_flush);  // the environment really was FTZ|DAZ
  CHECK(counts.ok);
  CHECK(wrong2 == 0);
  CHECK(wrong3 == 0);
  CHECK(wrongc == 0);
  CHECK(wrongs == 0);
  CHECK(wrongb == 0);
  // Sanity of the generator: the cases are not all trivial (both signs and zeros occur).
  int pos = 0, neg = 0;
  for (const auto& c : cases) {
    pos += c.o3 > 0;
    neg += c.o3 < 0;
  }
  CHECK(pos > 100);
  CHECK(neg > 100);
#endif
}

TEST_CASE("the doctest run honours VOLMAP_TEST_FTZ_DAZ (scripts/test.sh sets it for the predicate tests)") {
#ifdef VOLMAP_TEST_HAVE_MXCSR
  const char* env = std::getenv("VOLMAP_TEST_FTZ_DAZ");
  if (env && std::string(env) == "1") {
    CHECK((_mm_getcsr() & (kFtz | kDaz)) == (kFtz | kDaz));
    CHECK(flushes());
  } else {
    CHECK((_mm_getcsr() & (kFtz | kDaz)) == 0u);
  }
#endif
}
