// farkas.cpp — strict half-spaces of oriented faces and the exact check of a Farkas certificate that
// their intersection is empty (see predicates_rational.hpp). All arithmetic in exact rationals.
#include <volmap/predicates_rational.hpp>

namespace volmap {

StrictHalfspace strict_halfspace(const double* a, const double* b, const double* c) {
  std::array<Rational, 3> u, w, pa;
  for (int i = 0; i < 3; ++i) {
    pa[i] = Rational(a[i]);
    u[i] = Rational(c[i]) - pa[i];
    w[i] = Rational(b[i]) - pa[i];
  }
  StrictHalfspace h;
  h.n = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
  h.d = h.n[0] * pa[0] + h.n[1] * pa[1] + h.n[2] * pa[2];
  return h;
}

bool farkas_certifies_empty(const std::vector<StrictHalfspace>& halfspaces, const std::vector<Rational>& multipliers) {
  if (halfspaces.size() != multipliers.size() || halfspaces.empty()) return false;
  std::array<Rational, 3> sum_n = {Rational(0), Rational(0), Rational(0)};
  Rational sum_d = 0;
  bool some_positive = false;
  for (std::size_t j = 0; j < halfspaces.size(); ++j) {
    if (multipliers[j] < 0) return false;
    if (multipliers[j] > 0) some_positive = true;
    for (int i = 0; i < 3; ++i) sum_n[i] += multipliers[j] * halfspaces[j].n[i];
    sum_d += multipliers[j] * halfspaces[j].d;
  }
  return some_positive && sum_n[0] == 0 && sum_n[1] == 0 && sum_n[2] == 0 && sum_d >= 0;
}

}  // namespace volmap
