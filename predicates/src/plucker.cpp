// plucker.cpp — lines in Plücker coordinates and the exact check of a Gordan certificate that no
// line lies on the required side of all of them (predicates_rational.hpp, docs/predicates.md §9).
// Exact rationals only.
#include <volmap/predicates_rational.hpp>

namespace volmap {

PluckerLine plucker_line(const double* p, const double* q) {
  std::array<Rational, 3> a, b;
  for (int i = 0; i < 3; ++i) {
    a[i] = Rational(p[i]);
    b[i] = Rational(q[i]);
  }
  PluckerLine line;
  line.d = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  line.m = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  return line;
}

Rational side(const PluckerLine& a, const PluckerLine& b) {
  Rational s = 0;
  for (int i = 0; i < 3; ++i) s += a.d[i] * b.m[i] + b.d[i] * a.m[i];
  return s;
}

bool gordan_certifies_no_line(const std::vector<PluckerLine>& lines, const std::vector<Rational>& multipliers) {
  if (lines.size() != multipliers.size() || lines.empty()) return false;
  std::array<Rational, 6> sum = {Rational(0), Rational(0), Rational(0), Rational(0), Rational(0), Rational(0)};
  bool some_positive = false;
  for (std::size_t j = 0; j < lines.size(); ++j) {
    if (multipliers[j] < 0) return false;
    if (multipliers[j] > 0) some_positive = true;
    for (int i = 0; i < 3; ++i) {
      sum[std::size_t(i)] += multipliers[j] * lines[j].d[std::size_t(i)];
      sum[std::size_t(i) + 3] += multipliers[j] * lines[j].m[std::size_t(i)];
    }
  }
  if (!some_positive) return false;
  for (const Rational& x : sum)
    if (x != 0) return false;
  return true;
}

}  // namespace volmap
