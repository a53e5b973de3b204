// null_vector.cpp — the exact one-dimensional null vector of a rational matrix by reduced row echelon
// form (see predicates_rational.hpp). Exact rationals only.
#include <volmap/predicates_rational.hpp>

#include <algorithm>
#include <cstdint>

namespace volmap {

std::vector<Rational> one_dimensional_null_vector(std::vector<std::vector<Rational>> m) {
  if (m.empty() || m[0].empty()) return {};
  const std::size_t rows = m.size(), k = m[0].size();
  std::vector<std::size_t> pivot_col;
  std::size_t row = 0;
  for (std::size_t c = 0; c < k && row < rows; ++c) {
    std::size_t p = row;
    while (p < rows && m[p][c] == 0) ++p;
    if (p == rows) continue;
    std::swap(m[p], m[row]);
    const Rational inv = Rational(1) / m[row][c];
    for (std::size_t j = 0; j < k; ++j) m[row][j] *= inv;
    for (std::size_t r = 0; r < rows; ++r)
      if (r != row && m[r][c] != 0) {
        const Rational f = m[r][c];
        for (std::size_t j = 0; j < k; ++j) m[r][j] -= f * m[row][j];
      }
    pivot_col.push_back(c);
    ++row;
  }
  if (pivot_col.size() + 1 != k) return {};
  std::vector<std::uint8_t> is_pivot(k, 0);
  for (std::size_t c : pivot_col) is_pivot[c] = 1;
  const std::size_t free_col = std::size_t(std::find(is_pivot.begin(), is_pivot.end(), 0) - is_pivot.begin());
  std::vector<Rational> x(k, Rational(0));
  x[free_col] = 1;
  for (std::size_t r = 0; r < pivot_col.size(); ++r) x[pivot_col[r]] = -m[r][free_col];
  return x;
}

}  // namespace volmap
