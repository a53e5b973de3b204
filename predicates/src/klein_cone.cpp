// klein_cone.cpp — exact test that a pointed polyhedral cone of six-vectors holds no line's Plücker
// coordinates (see predicates_rational.hpp): its extreme rays by exact elimination, then the sign
// of the Klein form on every pair of them (docs/predicates.md §9). Exact rationals only.
#include <volmap/predicates_rational.hpp>

#include <algorithm>

namespace volmap {

namespace {

// Rank of the rows (Gaussian elimination on a copy).
std::size_t rank_of(std::vector<SixVector> m) {
  std::size_t rank = 0;
  for (std::size_t c = 0; c < 6 && rank < m.size(); ++c) {
    std::size_t p = rank;
    while (p < m.size() && m[p][c] == 0) ++p;
    if (p == m.size()) continue;
    std::swap(m[p], m[rank]);
    for (std::size_t r = rank + 1; r < m.size(); ++r)
      if (m[r][c] != 0) {
        const Rational f = m[r][c] / m[rank][c];
        for (std::size_t j = c; j < 6; ++j) m[r][j] -= f * m[rank][j];
      }
    ++rank;
  }
  return rank;
}

// The null vector of five rows when their rank is five (false otherwise), scaled so that its first
// nonzero entry is ±1.
bool null_vector_of_five(const std::array<const SixVector*, 5>& rows, SixVector& x) {
  std::vector<std::vector<Rational>> m;
  for (const SixVector* r : rows) m.emplace_back(r->begin(), r->end());
  const std::vector<Rational> n = one_dimensional_null_vector(std::move(m));
  if (n.empty()) return false;
  const auto first = std::find_if(n.begin(), n.end(), [](const Rational& v) { return v != 0; });
  const Rational scale = abs(*first);
  for (std::size_t i = 0; i < 6; ++i) x[i] = n[i] / scale;
  return true;
}

Rational dot(const SixVector& a, const SixVector& b) {
  Rational s = 0;
  for (std::size_t i = 0; i < 6; ++i) s += a[i] * b[i];
  return s;
}

bool in_cone(const std::vector<SixVector>& rows, const SixVector& x) {
  return std::all_of(rows.begin(), rows.end(), [&](const SixVector& r) { return dot(r, x) >= 0; });
}

Rational klein(const SixVector& a, const SixVector& b) {
  Rational s = 0;
  for (std::size_t i = 0; i < 3; ++i) s += a[i] * b[i + 3] + b[i] * a[i + 3];
  return s;
}

// The extreme rays of the pointed cone, each once.
std::vector<SixVector> extreme_rays(const std::vector<SixVector>& rows) {
  std::vector<SixVector> rays;
  const std::size_t k = rows.size();
  std::array<std::size_t, 5> s = {0, 1, 2, 3, 4};
  while (true) {
    SixVector x;
    if (null_vector_of_five({&rows[s[0]], &rows[s[1]], &rows[s[2]], &rows[s[3]], &rows[s[4]]}, x)) {
      for (int sign = 0; sign < 2; ++sign) {
        if (sign == 1)
          for (Rational& v : x) v = -v;
        if (in_cone(rows, x) && std::find(rays.begin(), rays.end(), x) == rays.end()) rays.push_back(x);
      }
    }
    std::size_t i = 5;
    while (i > 0 && s[i - 1] == k - 5 + i - 1) --i;
    if (i == 0) break;
    ++s[i - 1];
    for (std::size_t j = i; j < 5; ++j) s[j] = s[j - 1] + 1;
  }
  return rays;
}

}  // namespace

bool cone_holds_no_line(const std::vector<SixVector>& rows) {
  if (rows.size() < 6 || rank_of(rows) != 6) return false;
  const std::vector<SixVector> rays = extreme_rays(rows);
  int sign = 0;
  for (std::size_t a = 0; a < rays.size(); ++a)
    for (std::size_t b = a; b < rays.size(); ++b) {
      const Rational q = klein(rays[a], rays[b]);
      const int s = q > 0 ? 1 : q < 0 ? -1 : 0;
      if (s == 0 || (sign != 0 && s != sign)) return false;
      sign = s;
    }
  return true;
}

}  // namespace volmap
