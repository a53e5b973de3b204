// orient3d's fast path is a filter that needs no floating-point-environment check (predicates/src/
// orient3d.cpp): it must stay exact under every rounding mode, with and without FTZ|DAZ, and leave
// the caller's MXCSR as it was. Both builds (SSE2 and, where the CPU has it, AVX2) and both batch pass-1
// kernels are run directly, against the GMP oracle computed in the default environment. Cases aim at
// the filter's guards: per-column magnitudes around 2^-300 and 2^300, products that overflow,
// subnormal inputs, near-coplanar points scaled per column, and |det| around the filter's bound.
#include <doctest/doctest.h>
#include <volmap/predicates.hpp>

#include "../../predicates/src/layers.hpp"
#include "../../predicates/testing/oracle.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#if defined(__SSE2__)
#include <xmmintrin.h>
#define VOLMAP_TEST_HAVE_MXCSR 1
#endif

namespace or_ = volmap_oracle;

namespace {

struct O3Case {
  double p[12];
  int expected = 0;
};

double signed_mantissa(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> m(1.0, 2.0);
  return (rng() & 1 ? 1.0 : -1.0) * m(rng);
}

std::vector<O3Case> orient3d_cases() {
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> u(-1.0, 1.0), w(0.0, 1.0);
  // Column exponent classes: subnormal, around the 2^-300 guard, ordinary, around 2^300, overflowing.
  const int classes[][2] = {{-1074, -1023}, {-310, -290}, {-20, 20}, {290, 310}, {330, 520}};
  std::uniform_int_distribution<int> pick(0, 4);
  std::vector<O3Case> cases;
  for (int i = 0; i < 6000; ++i) {
    O3Case c;
    const int kind = i % 3;
    int e[3];
    for (int k = 0; k < 3; ++k) {
      const auto& cl = classes[pick(rng)];
      e[k] = std::uniform_int_distribution<int>(cl[0], cl[1])(rng);
    }
    if (kind == 0) {  // independent points, column k scaled by 2^e[k]
      for (int v = 0; v < 4; ++v)
        for (int k = 0; k < 3; ++k) c.p[3 * v + k] = std::ldexp(signed_mantissa(rng), e[k] - (rng() % 3 == 0 ? 40 : 0));
    } else {  // near-coplanar, then scaled per column (exact scaling keeps it near-coplanar)
      double q[12];
      for (int k = 0; k < 9; ++k) q[k] = u(rng);
      const double s = w(rng), t = w(rng);
      for (int k = 0; k < 3; ++k) q[9 + k] = q[k] + s * (q[3 + k] - q[k]) + t * (q[6 + k] - q[k]);
      if (kind == 2) {  // push d off the plane by a relative 2^-38 ... 2^-52: |det| around the bound
        const int shift = 38 + i % 15;
        for (int k = 0; k < 3; ++k) q[9 + k] += std::ldexp(u(rng), -shift);
      }
      for (int v = 0; v < 4; ++v)
        for (int k = 0; k < 3; ++k) c.p[3 * v + k] = std::ldexp(q[3 * v + k], e[k]);
    }
    c.expected = or_::orient3d(c.p, c.p + 3, c.p + 6, c.p + 9);
    cases.push_back(c);
  }
  return cases;
}

#ifdef VOLMAP_TEST_HAVE_MXCSR
constexpr unsigned kFtzDaz = 0x8040u;
constexpr unsigned kRounding[4] = {0x0000u, 0x2000u, 0x4000u, 0x6000u};  // nearest, down, up, toward zero

struct Mxcsr {  // sets the control bits for its lifetime
  unsigned saved = _mm_getcsr();
  explicit Mxcsr(unsigned bits) { _mm_setcsr((saved & ~0xE040u) | bits); }
  ~Mxcsr() { _mm_setcsr(saved); }
};
#endif

}  // namespace

TEST_CASE("orient3d fast path: exact in every rounding mode with and without FTZ|DAZ, both builds") {
  const std::vector<O3Case> cases = orient3d_cases();
  int zeros = 0, positives = 0;
  for (const auto& c : cases) zeros += c.expected == 0, positives += c.expected > 0;
  CHECK(zeros > 0);
  CHECK(positives > 1000);
  const bool avx2 = volmap::detail::cpu_has_avx2();
  if (!avx2) MESSAGE("no AVX2 on this CPU: only the SSE2 build runs");
#ifdef VOLMAP_TEST_HAVE_MXCSR
  for (unsigned flush : {0u, kFtzDaz})
    for (unsigned rounding : kRounding) {
      CAPTURE(flush);
      CAPTURE(rounding);
      int wrong_public = 0, wrong_sse2 = 0, wrong_avx2 = 0;
      unsigned after = 0, before = 0;
      {
        const Mxcsr env(flush | rounding);
        before = _mm_getcsr() & ~0x3Fu;
        for (const auto& c : cases) {
          const double *a = c.p, *b = c.p + 3, *cc = c.p + 6, *d = c.p + 9;
          wrong_public += volmap::orient3d(a, b, cc, d) != c.expected;
          wrong_sse2 += volmap::detail::orient3d_sse2(a, b, cc, d) != c.expected;
          if (avx2) wrong_avx2 += volmap::detail::orient3d_avx2(a, b, cc, d) != c.expected;
        }
        after = _mm_getcsr() & ~0x3Fu;
      }
      CHECK(wrong_public == 0);
      CHECK(wrong_sse2 == 0);
      CHECK(wrong_avx2 == 0);
      CHECK(after == before);  // the caller's control bits are left alone
    }
#else
  int wrong = 0;
  for (const auto& c : cases) wrong += volmap::orient3d(c.p, c.p + 3, c.p + 6, c.p + 9) != c.expected;
  CHECK(wrong == 0);
#endif
}

TEST_CASE("orient3d_tets: the AVX2 and the portable pass 1 agree with the oracle, local and shuffled ids") {
  // Kuhn grid 34³·6 = 235 824 tets, 42 875 vertices (> 2^15: a shuffled order turns the prefetch on),
  // the upper half flattened onto a tilted plane (exact zeros for pass 2), every 7th tet flipped; prefixes
  // of 1, 3, 4, 1029 and all tets, so that partial four-tet steps and several chunks occur.
  const int n = 34;
  or_::IndexedTets g = or_::kuhn_grid(n, 1.0 / 64);
  const double zc = (n / 2) / 64.0;
  for (std::size_t v = 0; v < g.xyz.size() / 3; ++v) {
    double* p = &g.xyz[3 * v];
    if (p[2] > zc + (p[0] + p[1]) / 4) p[2] = zc + (p[0] + p[1]) / 4;
  }
  for (std::size_t t = 0; t < g.tets.size() / 4; t += 7) std::swap(g.tets[4 * t], g.tets[4 * t + 1]);
  const std::size_t nv = g.xyz.size() / 3, all = g.tets.size() / 4;
  std::vector<std::int8_t> oracle(all);  // the geometry of tet t does not depend on the vertex order
  for (std::size_t t = 0; t < all; ++t) {
    const std::uint32_t* q = &g.tets[4 * t];
    oracle[t] = std::int8_t(or_::orient3d(&g.xyz[3 * q[0]], &g.xyz[3 * q[1]], &g.xyz[3 * q[2]], &g.xyz[3 * q[3]]));
  }
  for (bool shuffled : {false, true}) {
    CAPTURE(shuffled);
    std::vector<double> xyz = g.xyz;
    std::vector<std::uint32_t> tets = g.tets;
    if (shuffled) {
      std::vector<std::uint32_t> perm(nv);
      for (std::uint32_t i = 0; i < nv; ++i) perm[i] = i;
      std::shuffle(perm.begin(), perm.end(), std::mt19937_64(5));
      for (std::size_t v = 0; v < nv; ++v)
        for (int k = 0; k < 3; ++k) xyz[3 * perm[v] + k] = g.xyz[3 * v + k];
      for (auto& id : tets) id = perm[id];
    }
    for (std::size_t nt : {std::size_t(1), std::size_t(3), std::size_t(4), std::size_t(1029), all}) {
      CAPTURE(nt);
      const std::vector<std::int8_t> expected(oracle.begin(), oracle.begin() + std::ptrdiff_t(nt));
      std::vector<std::int8_t> fast(nt, 9), portable(nt, 9);
      std::size_t expected_zero = 0;
      for (std::int8_t s : expected) expected_zero += s == 0;
      const volmap::Orient3dBatchFilter f = volmap::orient3d_batch_filter(xyz.data(), nv);
      const auto a = volmap::orient3d_tets(f, xyz.data(), nv, tets.data(), nt, fast.data());
      const auto b = volmap::detail::orient3d_tets_portable(f, xyz.data(), nv, tets.data(), nt, portable.data());
      CHECK(fast == expected);
      CHECK(portable == expected);
      CHECK(a.zero == expected_zero);
      CHECK(b.zero == expected_zero);
      CHECK(a.positive == b.positive);
    }
    // An id out of range anywhere is refused by both kernels (no pointer formed from it).
    std::vector<std::uint32_t> bad = tets;
    bad[4 * 1500 + 3] = std::uint32_t(nv);
    const volmap::Orient3dBatchFilter f = volmap::orient3d_batch_filter(xyz.data(), nv);
    CHECK_FALSE(volmap::orient3d_tets(f, xyz.data(), nv, bad.data(), bad.size() / 4, nullptr).ok);
    CHECK_FALSE(volmap::detail::orient3d_tets_portable(f, xyz.data(), nv, bad.data(), bad.size() / 4, nullptr).ok);
  }
}
