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

#include "../../predicates/testing/oracle.hpp"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
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

// FpEnvironmentScope: one check for a loop, then unchecked member predicates. Inside a scope entered
// under FTZ|DAZ (and under round-toward-zero) the unchecked calls must give the oracle's signs, and
// the caller's MXCSR must come back exactly (control bits) after the scope, also when the scope is
// left by an exception.
#ifdef VOLMAP_TEST_HAVE_MXCSR
namespace {

// The oracle cases, computed in the default environment (GMP's conversions need gradual underflow).
std::vector<Case> oracle_cases() {
  DefaultEnvironment env;
  return make_cases();
}

struct ScopeRun {
  int wrong2 = 0, wrong3 = 0, wrongc = 0, wrongs = 0;
  bool switched = false;
  unsigned inside = 0;  // MXCSR seen inside the scope
};

ScopeRun run_in_scope(const std::vector<Case>& cases) {
  ScopeRun r;
  volmap::FpEnvironmentScope fp;
  r.switched = fp.switched();
  r.inside = _mm_getcsr();
  for (const auto& c : cases) {
    const double *a = &c.p[0], *b = &c.p[3], *d3 = &c.p[6], *e = &c.p[9], *f = &c.p[12];
    r.wrong2 += fp.orient2d(a, b, d3) != c.o2;
    r.wrong3 += fp.orient3d(a, b, d3, e) != c.o3;
    r.wrongc += fp.incircle(a, b, d3, e) != c.ic;
    r.wrongs += fp.insphere(a, b, d3, e, f) != c.is;
  }
  return r;
}

// How many cases the plain double determinant (orient3d form) signs differently in the current
// environment than in `reference`: shows that the inputs are sensitive to FTZ|DAZ, so a scope that
// forgot to switch the environment would fail the exactness checks.
std::vector<int> naive_signs(const std::vector<Case>& cases) {
  std::vector<int> s;
  for (const auto& c : cases) {
    const double* p = c.p.data();
    volatile double det = or_::naive_orient3d(p, p + 3, p + 6, p + 9);
    s.push_back((det > 0) - (det < 0));
  }
  return s;
}

}  // namespace
#endif

TEST_CASE("FpEnvironmentScope makes unchecked predicates exact when the caller set FTZ|DAZ") {
#ifndef VOLMAP_TEST_HAVE_MXCSR
  MESSAGE("skipped: no MXCSR on this architecture");
#else
  const std::vector<Case> cases = oracle_cases();
  ScopeRun run;
  unsigned before = 0, after = 0;
  std::vector<int> naive_default, naive_ftz;
  {
    DefaultEnvironment env;
    naive_default = naive_signs(cases);
  }
  {
    FlushToZero ftz;
    REQUIRE(flushes());
    naive_ftz = naive_signs(cases);
    before = _mm_getcsr();
    run = run_in_scope(cases);
    after = _mm_getcsr();
  }
  int sensitive = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) sensitive += naive_default[i] != naive_ftz[i];
  CHECK(sensitive > 10);  // the inputs do flush under FTZ|DAZ: a scope that did not switch would be wrong
  CHECK(run.switched);
  CHECK((run.inside & 0xE040u) == 0u);  // inside: no FTZ, no DAZ, round-to-nearest
  CHECK(run.wrong2 == 0);
  CHECK(run.wrong3 == 0);
  CHECK(run.wrongc == 0);
  CHECK(run.wrongs == 0);
  CHECK((after & ~0x3Fu) == (before & ~0x3Fu));  // control bits restored (exception flags may differ)
  CHECK((after & (kFtz | kDaz)) == (kFtz | kDaz));
#endif
}

TEST_CASE("FpEnvironmentScope switches rounding mode to nearest and restores it") {
#ifdef VOLMAP_TEST_HAVE_MXCSR
  const std::vector<Case> cases = oracle_cases();
  const unsigned saved = _mm_getcsr();
  _mm_setcsr((saved & ~0x6000u) | 0x6000u);  // round toward zero
  const ScopeRun run = run_in_scope(cases);
  const unsigned after = _mm_getcsr();
  _mm_setcsr(saved);
  CHECK(run.switched);
  CHECK((run.inside & 0x6000u) == 0u);
  CHECK(run.wrong3 == 0);
  CHECK(run.wrongs == 0);
  CHECK((after & 0x6000u) == 0x6000u);
#endif
}

TEST_CASE("FpEnvironmentScope restores the caller's MXCSR when an exception leaves the scope") {
#ifdef VOLMAP_TEST_HAVE_MXCSR
  FlushToZero ftz;
  const unsigned before = _mm_getcsr();
  bool caught = false;
  try {
    volmap::FpEnvironmentScope fp;
    CHECK(fp.switched());
    CHECK((_mm_getcsr() & (kFtz | kDaz)) == 0u);
    const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0}, d[3] = {0, 0, -1};
    if (fp.orient3d(a, b, c, d) > 0) throw std::runtime_error("leave the scope");
  } catch (const std::runtime_error&) {
    caught = true;
  }
  CHECK(caught);
  CHECK((_mm_getcsr() & ~0x3Fu) == (before & ~0x3Fu));
  CHECK(flushes());
#endif
}

TEST_CASE("FpEnvironmentScope in the default environment and nested scopes change nothing") {
#ifdef VOLMAP_TEST_HAVE_MXCSR
  DefaultEnvironment env;
  const unsigned before = _mm_getcsr();
  {
    volmap::FpEnvironmentScope outer;
    CHECK_FALSE(outer.switched());
    CHECK(_mm_getcsr() == before);
    {
      FlushToZero ftz;  // the caller changes MXCSR inside the outer scope, then opens an inner one
      volmap::FpEnvironmentScope inner;
      CHECK(inner.switched());
      CHECK((_mm_getcsr() & (kFtz | kDaz)) == 0u);
      const double a[3] = {0x1p-1060, 0, 0}, b[3] = {0, 0x1p-1060, 0}, c[3] = {0, 0, 0x1p-1060}, d[3] = {0, 0, 0};
      CHECK(inner.orient3d(a, b, c, d) == 1);  // det diag(2^-1060, 2^-1060, 2^-1060) > 0; DAZ would give 0
    }
    CHECK((_mm_getcsr() & ~0x3Fu) == (before & ~0x3Fu));
  }
  CHECK((_mm_getcsr() & ~0x3Fu) == (before & ~0x3Fu));
#endif
}

TEST_CASE("negative control: unchecked members misused under FTZ|DAZ inside a default-entered scope") {
#ifdef VOLMAP_TEST_HAVE_MXCSR
  // Breaking the contract on purpose (MXCSR changed inside the scope) must be able to give wrong
  // signs: this shows the members really skip the check, so the exactness above is the scope's work.
  DefaultEnvironment env;
  const std::vector<Case> cases = oracle_cases();
  volmap::FpEnvironmentScope fp;
  REQUIRE_FALSE(fp.switched());
  int wrong = 0, checked_wrong = 0;
  {
    FlushToZero ftz;
    for (const auto& c : cases) {
      const double *a = &c.p[0], *b = &c.p[3], *d3 = &c.p[6], *e = &c.p[9], *f = &c.p[12];
      wrong += (fp.orient2d(a, b, d3) != c.o2) + (fp.orient3d(a, b, d3, e) != c.o3) +
               (fp.incircle(a, b, d3, e) != c.ic) + (fp.insphere(a, b, d3, e, f) != c.is);
      checked_wrong += (volmap::orient3d(a, b, d3, e) != c.o3) + (volmap::insphere(a, b, d3, e, f) != c.is);
    }
  }
  MESSAGE("unchecked members under FTZ|DAZ: " << wrong << " wrong signs of " << 4 * cases.size());
  CHECK(wrong > 0);
  CHECK(checked_wrong == 0);  // the checked free functions stay exact in the same environment
#endif
}
