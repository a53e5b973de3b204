// small_lp.cpp — the dense simplex of small_lp.hpp (conventions there).
#include <volmap/core/small_lp.hpp>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <utility>

namespace volmap {

bool simplex_max(int m, int n, std::vector<double>& A, std::vector<double>& b, std::vector<double> c, double* x,
                 double* duals) {
  std::vector<int> row_label(m), col_label(n);  // labels: 0..n-1 original vars, n.. slacks
  for (int j = 0; j < n; ++j) col_label[j] = j;
  for (int i = 0; i < m; ++i) row_label[i] = n + i;
  const double eps = 1e-12;
  constexpr double kPivotTolerance = 1e-9, kFeasibilityTolerance = 1e-12;
  for (int iter = 0; iter < 50 * (m + n); ++iter) {
    int e = -1;
    for (int j = 0; j < n; ++j)
      if (c[j] > eps && (e < 0 || col_label[j] < col_label[e])) e = j;
    if (e < 0) break;  // optimal
    double bound = std::numeric_limits<double>::infinity();
    for (int i = 0; i < m; ++i) {
      const double a = A[std::size_t(i) * n + e];
      if (a > kPivotTolerance) bound = std::min(bound, (std::max(b[i], 0.0) + kFeasibilityTolerance) / a);
    }
    int r = -1;
    double largest_pivot = 0;
    for (int i = 0; i < m; ++i) {
      const double a = A[std::size_t(i) * n + e];
      if (a > kPivotTolerance && std::max(b[i], 0.0) / a <= bound && a > largest_pivot) {
        largest_pivot = a;
        r = i;
      }
    }
    if (r < 0) return false;  // unbounded
    const double piv = A[std::size_t(r) * n + e];
    // Row r.
    for (int j = 0; j < n; ++j)
      if (j != e) A[std::size_t(r) * n + j] /= piv;
    b[r] /= piv;
    A[std::size_t(r) * n + e] = 1.0 / piv;
    for (int i = 0; i < m; ++i) {
      if (i == r) continue;
      const double aie = A[std::size_t(i) * n + e];
      if (aie == 0) continue;
      for (int j = 0; j < n; ++j)
        if (j != e) A[std::size_t(i) * n + j] -= aie * A[std::size_t(r) * n + j];
      b[i] -= aie * b[r];
      A[std::size_t(i) * n + e] = -aie / piv;
    }
    const double ce = c[e];
    for (int j = 0; j < n; ++j)
      if (j != e) c[j] -= ce * A[std::size_t(r) * n + j];
    c[e] = -ce / piv;
    std::swap(row_label[r], col_label[e]);
  }
  for (int j = 0; j < n; ++j) x[j] = 0;
  for (int i = 0; i < m; ++i)
    if (row_label[i] < n) x[row_label[i]] = b[i];
  if (duals) {
    for (int i = 0; i < m; ++i) duals[i] = 0;
    for (int j = 0; j < n; ++j)
      if (col_label[j] >= n) duals[col_label[j] - n] = std::max(0.0, -c[j]);
  }
  return true;
}


}  // namespace volmap
