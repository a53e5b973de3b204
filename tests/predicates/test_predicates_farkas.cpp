// strict_halfspace / farkas_certifies_empty / one_dimensional_null_vector against independent
// oracles: the half-space agrees with orient3d's sign at random points; a certificate is accepted for
// systems that are empty by construction and refused for every multiplier vector when a witness point
// is strictly inside all half-spaces (checked exactly with orient3d), since Σλ(n·x − d) > 0
// contradicts Σλn = 0, Σλd >= 0; the null vector solves M x = 0 exactly and exists exactly when the
// oracle's rank leaves nullity one.
#include <doctest/doctest.h>
#include <volmap/predicates_rational.hpp>

#include "../../predicates/testing/oracle.hpp"

#include <algorithm>
#include <array>
#include <random>
#include <vector>

using volmap::Rational;
using Face = std::array<std::array<double, 3>, 3>;

namespace {
volmap::StrictHalfspace halfspace(const Face& f) { return volmap::strict_halfspace(f[0].data(), f[1].data(), f[2].data()); }
Face reversed(const Face& f) { return {f[0], f[2], f[1]}; }
}  // namespace

TEST_CASE("strict_halfspace: n·x > d exactly when orient3d(a,b,c,x) > 0") {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> u(-8, 8);
  for (int it = 0; it < 2000; ++it) {
    Face f;
    std::array<double, 3> x;
    for (auto& p : f)
      for (auto& c : p) c = u(rng) * 0.125;
    for (auto& c : x) c = u(rng) * 0.125;
    const auto h = halfspace(f);
    const Rational value = h.n[0] * Rational(x[0]) + h.n[1] * Rational(x[1]) + h.n[2] * Rational(x[2]) - h.d;
    const int sign = value > 0 ? 1 : value < 0 ? -1 : 0;
    CHECK(sign == volmap::orient3d(f[0].data(), f[1].data(), f[2].data(), x.data()));
  }
}

TEST_CASE("farkas_certifies_empty: a face and its reverse, and the outside of a tet's four faces") {
  const Face f = {{{0.1, 0, 0}, {0, 1.3, 0}, {0, 0, 0.7}}};
  const std::vector<volmap::StrictHalfspace> pair = {halfspace(f), halfspace(reversed(f))};
  CHECK(volmap::farkas_certifies_empty(pair, {Rational(1), Rational(1)}));
  CHECK(volmap::farkas_certifies_empty(pair, {Rational(3, 7), Rational(3, 7)}));
  CHECK_FALSE(volmap::farkas_certifies_empty(pair, {Rational(1), Rational(2)}));  // Σλn != 0
  CHECK_FALSE(volmap::farkas_certifies_empty(pair, {Rational(0), Rational(0)}));  // all zero
  CHECK_FALSE(volmap::farkas_certifies_empty(pair, {Rational(-1), Rational(-1)}));
  CHECK_FALSE(volmap::farkas_certifies_empty(pair, {Rational(1)}));  // sizes differ
  CHECK_FALSE(volmap::farkas_certifies_empty({}, {}));
  // Being on the positive side of all four faces of a positive tet, each seen from outside (the
  // faces reversed), is impossible: λ_j = area-weighted (Σ n_j = 0 for a closed surface), λ = 1.
  const std::array<double, 3> p[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  REQUIRE(volmap::orient3d(p[0].data(), p[1].data(), p[2].data(), p[3].data()) < 0);  // VOLMAP-positive is > 0: flip
  // Faces of the tet (1,0,2,3) (positive) in kTetFace order, reversed to face inward-out.
  const int t[4] = {1, 0, 2, 3};
  const int F[4][3] = {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}};
  std::vector<volmap::StrictHalfspace> outside;
  for (const auto& fl : F) outside.push_back(halfspace(reversed({p[t[fl[0]]], p[t[fl[1]]], p[t[fl[2]]]})));
  CHECK(volmap::farkas_certifies_empty(outside, std::vector<Rational>(4, Rational(1))));
  // ...whereas the inward system (the tet's interior) is not empty: no multiplier vector certifies it.
  std::vector<volmap::StrictHalfspace> inside;
  for (const auto& fl : F) inside.push_back(halfspace({p[t[fl[0]]], p[t[fl[1]]], p[t[fl[2]]]}));
  CHECK_FALSE(volmap::farkas_certifies_empty(inside, std::vector<Rational>(4, Rational(1))));
}

TEST_CASE("farkas_certifies_empty never certifies a system with a strictly interior witness") {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> u(-6, 6), lam(0, 3);
  int systems = 0;
  for (int it = 0; it < 3000 && systems < 400; ++it) {
    const std::array<double, 3> x = {u(rng) * 0.25, u(rng) * 0.25, u(rng) * 0.25};
    std::vector<volmap::StrictHalfspace> hs;
    for (int j = 0; j < 4; ++j) {
      Face f;
      for (auto& q : f)
        for (auto& c : q) c = u(rng) * 0.25;
      const int s = volmap::orient3d(f[0].data(), f[1].data(), f[2].data(), x.data());
      if (s == 0) break;
      hs.push_back(halfspace(s > 0 ? f : reversed(f)));  // x strictly inside every half-space
    }
    if (hs.size() != 4) continue;
    ++systems;
    for (int k = 0; k < 20; ++k) {
      std::vector<Rational> l(4);
      for (auto& v : l) v = lam(rng);
      CHECK_FALSE(volmap::farkas_certifies_empty(hs, l));
    }
  }
  CHECK(systems == 400);
}

TEST_CASE("one_dimensional_null_vector: M x = 0 exactly on random integer matrices, empty when the nullity is not one") {
  std::mt19937 rng(13);
  std::uniform_int_distribution<int> g(-9, 9);
  int found = 0;
  for (int it = 0; it < 300; ++it) {
    const std::size_t rows = 1 + std::size_t(it % 6), cols = rows + 1;
    std::vector<std::vector<Rational>> m(rows, std::vector<Rational>(cols));
    for (auto& r : m)
      for (auto& v : r) v = Rational(g(rng), 1 + (g(rng) + 9) % 4);
    if (it % 5 == 0 && rows >= 2) m[1] = m[0];  // rank drops: nullity two
    const std::vector<Rational> x = volmap::one_dimensional_null_vector(m);
    // Oracle: the nullity from the rank, by elimination on a copy with oracle rationals.
    std::vector<std::vector<volmap_oracle::Q>> a(rows, std::vector<volmap_oracle::Q>(cols));
    for (std::size_t r = 0; r < rows; ++r)
      for (std::size_t c = 0; c < cols; ++c) a[r][c] = volmap_oracle::Q(m[r][c]);
    std::size_t rank = 0;
    for (std::size_t c = 0; c < cols && rank < rows; ++c) {
      std::size_t p = rank;
      while (p < rows && a[p][c] == 0) ++p;
      if (p == rows) continue;
      std::swap(a[p], a[rank]);
      for (std::size_t r = rank + 1; r < rows; ++r) {
        const volmap_oracle::Q f = a[r][c] / a[rank][c];
        for (std::size_t j = 0; j < cols; ++j) a[r][j] -= f * a[rank][j];
      }
      ++rank;
    }
    if (cols - rank != 1) {
      CHECK(x.empty());
      continue;
    }
    REQUIRE(x.size() == cols);
    CHECK(std::any_of(x.begin(), x.end(), [](const Rational& v) { return v != 0; }));
    for (const auto& r : m) {
      Rational s = 0;
      for (std::size_t c = 0; c < cols; ++c) s += r[c] * x[c];
      CHECK(s == 0);
    }
    ++found;
  }
  CHECK(found > 100);
  CHECK(volmap::one_dimensional_null_vector({}).empty());
}
