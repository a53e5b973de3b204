// kernel_lp.cpp — the strict-kernel LP of docs/mapping.md §7 (conventions in kernel_lp.hpp).
#include <volmap/volume/kernel_lp.hpp>

#include <volmap/core/small_lp.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace volmap {

double inward_face_normal(const double* a, const double* b, const double* c, double scale, double* n) {
  double u[3], v[3];
  for (int i = 0; i < 3; ++i) {
    u[i] = (c[i] - a[i]) * scale;
    v[i] = (b[i] - a[i]) * scale;
  }
  n[0] = u[1] * v[2] - u[2] * v[1];
  n[1] = u[2] * v[0] - u[0] * v[2];
  n[2] = u[0] * v[1] - u[1] * v[0];
  return std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

bool chebyshev_point(const std::vector<double>& tri, double* q, double* slack) {
  const std::size_t nf = tri.size() / 9;
  if (nf == 0) return false;
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (std::size_t k = 0; k < 3 * nf; ++k)
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], tri[3 * k + i]);
      hi[i] = std::max(hi[i], tri[3 * k + i]);
    }
  return chebyshev_point_in_box(tri, lo, hi, q, slack);
}

bool chebyshev_point_in_box(const std::vector<double>& tri, const double* lo, const double* hi, double* q, double* slack) {
  const std::size_t nf = tri.size() / 9;
  if (nf == 0) return false;
  const double diag = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
  if (!(diag > 0)) return false;
  // Work in a frame centred at lo and scaled by 1/diag (conditioning).
  const double inv = 1.0 / diag;
  const double S0 = 2.0;
  const int n = 4;
  std::vector<double> A, b;
  A.reserve((nf + 4) * n);
  b.reserve(nf + 4);
  for (std::size_t f = 0; f < nf; ++f) {
    const double* a = &tri[9 * f];
    const double* bb = a + 3;
    const double* c = a + 6;
    double nn[3];
    const double len = inward_face_normal(a, bb, c, inv, nn);
    if (!(len > 0)) continue;  // degenerate in double: no strict kernel (left to the exact check)
    // n̂·(q' − a') ≥ s  ⇔  −n̂·q' + s' ≤ −n̂·a' + S0   (q' = (q − lo)/diag, s' = s + S0)
    double rhs = S0;
    for (int i = 0; i < 3; ++i) {
      const double ni = nn[i] / len;
      A.push_back(-ni);
      rhs -= ni * (a[i] - lo[i]) * inv;
    }
    A.push_back(1.0);
    b.push_back(std::max(rhs, 0.0));
  }
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) A.push_back(i == j ? 1.0 : 0.0);
    b.push_back(i < 3 ? (hi[i] - lo[i]) * inv : S0 + 1.0);
  }
  const int m = int(b.size());
  double x[4];
  if (!simplex_max(m, n, A, b, {0, 0, 0, 1}, x)) return false;
  *slack = x[3] - S0;
  for (int i = 0; i < 3; ++i) q[i] = lo[i] + x[i] * diag;
  return true;
}

bool max_min_slack_in_box(const std::vector<double>& rows, int dim, double* x, double* slack, std::vector<double>* row_weights) {
  if (dim <= 0 || rows.empty() || rows.size() % std::size_t(dim) != 0) return false;
  // Shifted variables y = x + 1 in [0, 2] and s' = s + S0 >= 0, so that the origin is feasible:
  // r·x >= s  ⇔  −r·y + s' <= −Σr + S0, with S0 larger than any |Σr| over the rows.
  const std::size_t m0 = rows.size() / std::size_t(dim);
  double S0 = 1.0;
  for (std::size_t i = 0; i < m0; ++i) {
    double sum = 0;
    for (int j = 0; j < dim; ++j) sum += rows[i * std::size_t(dim) + std::size_t(j)];
    S0 = std::max(S0, 1.0 + std::fabs(sum));
  }
  const int n = dim + 1;
  std::vector<double> A, b;
  A.reserve((m0 + std::size_t(n)) * std::size_t(n));
  for (std::size_t i = 0; i < m0; ++i) {
    double sum = 0;
    for (int j = 0; j < dim; ++j) {
      const double r = rows[i * std::size_t(dim) + std::size_t(j)];
      A.push_back(-r);
      sum += r;
    }
    A.push_back(1.0);
    b.push_back(std::max(S0 - sum, 0.0));
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) A.push_back(i == j ? 1.0 : 0.0);
    b.push_back(i < dim ? 2.0 : S0 + 1.0);
  }
  std::vector<double> c(static_cast<std::size_t>(n), 0.0), y(static_cast<std::size_t>(n));
  c[std::size_t(dim)] = 1.0;
  std::vector<double> duals(b.size());
  if (!simplex_max(int(b.size()), n, A, b, c, y.data(), duals.data())) return false;
  if (row_weights) row_weights->assign(duals.begin(), duals.begin() + std::ptrdiff_t(m0));
  for (int j = 0; j < dim; ++j) x[j] = y[std::size_t(j)] - 1.0;
  *slack = y[std::size_t(dim)] - S0;
  return true;
}

bool verified_inside(const FpEnvironmentScope& fp, const std::vector<double>& tri, const double* q) {
  for (std::size_t f = 0; f < tri.size() / 9; ++f)
    if (fp.orient3d(&tri[9 * f], &tri[9 * f + 3], &tri[9 * f + 6], q) <= 0) return false;
  return true;
}

bool strict_kernel_point(const FpEnvironmentScope& fp, const std::vector<double>& tri, double* q) {
  double slack = 0;
  if (!chebyshev_point(tri, q, &slack) || !(slack > 0)) return false;
  return verified_inside(fp, tri, q);
}

bool strict_kernel_point(const std::vector<double>& tri, double* q) {
  const FpEnvironmentScope fp;
  return strict_kernel_point(fp, tri, q);
}

}  // namespace volmap
