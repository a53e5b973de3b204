// enclosed_volume.cpp — exact sign of Σ det[a; b; c] over a triangle surface (<volmap/predicates.hpp>).
// Layers: (1) double sum S and magnitude M = Σ perm, perm = Σ_k |a_k|·(|p_k| + |q_k|) for the three
// products a_k·(p_k − q_k) of a term; (2) exact expansion sum; (3) exact rational sum.
// Filter (1): each term is a depth-5 expression, error ≤ γ5·perm; the recursive sum adds ≤ γ(n−1)·Σ|term|,
// so |S − exact| ≤ (n + 4)·u·M·(1 + O(nu)), u = 2^-53. We accept |S| > 2(n + 8)·u·fl(M) (twice that,
// which also covers the rounding of M and of the bound) when every referenced coordinate is zero or
// has |x| in Shewchuk's range [2^-142, 2^201] (then no product underflows and nothing overflows) and
// n < 2^40. (2) in that range det3_expansion is exact and expansion sums are exact. (3) otherwise.
#include <volmap/predicates_rational.hpp>

#include "expansion.hpp"
#include "fp_env.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace volmap {
namespace {

using detail::det3_expansion;
using detail::expansion_sign;
using detail::expansion_sum;

bool in_safe_range(double x) {
  const double ax = std::fabs(x);
  return ax == 0.0 || (ax >= 0x1p-142 && ax <= 0x1p201);
}

const double* corner(const double* xyz, std::size_t num_vertices, std::uint32_t id) {
  if (id >= num_vertices)
    throw std::out_of_range("enclosed_volume_sign: vertex id " + std::to_string(id) + " >= " +
                            std::to_string(num_vertices));
  return xyz + 3 * std::size_t(id);
}

int expansion_sum_sign(const double* xyz, std::size_t num_vertices, const std::uint32_t* tris, std::size_t n) {
  std::vector<double> acc{0.0}, next;
  double term[24];
  for (std::size_t t = 0; t < n; ++t) {
    const double* a = corner(xyz, num_vertices, tris[3 * t]);
    const double* b = corner(xyz, num_vertices, tris[3 * t + 1]);
    const double* c = corner(xyz, num_vertices, tris[3 * t + 2]);
    const int len = det3_expansion(a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2], term);
    next.resize(acc.size() + std::size_t(len));
    next.resize(std::size_t(expansion_sum(acc.data(), int(acc.size()), term, len, next.data())));
    std::swap(acc, next);
  }
  return expansion_sign(acc.data(), int(acc.size()));
}

int rational_sum_sign(const double* xyz, std::size_t num_vertices, const std::uint32_t* tris, std::size_t n) {
  Rational sum = 0;
  for (std::size_t t = 0; t < n; ++t) {
    Rational p[9];
    for (int k = 0; k < 3; ++k) {
      const double* q = corner(xyz, num_vertices, tris[3 * t + k]);
      for (int i = 0; i < 3; ++i) p[3 * k + i] = q[i];
    }
    sum += p[0] * (p[4] * p[8] - p[5] * p[7]) + p[1] * (p[5] * p[6] - p[3] * p[8]) + p[2] * (p[3] * p[7] - p[4] * p[6]);
  }
  return sum > 0 ? 1 : (sum < 0 ? -1 : 0);
}

}  // namespace

int enclosed_volume_sign(const double* xyz, std::size_t num_vertices, const std::uint32_t* triangles,
                         std::size_t num_triangles) {
  VOLMAP_REQUIRE_DEFAULT_FP_ENV(enclosed_volume_sign(xyz, num_vertices, triangles, num_triangles));
  double sum = 0, magnitude = 0;
  bool safe = true;
  for (std::size_t t = 0; t < num_triangles; ++t) {
    const double* a = corner(xyz, num_vertices, triangles[3 * t]);
    const double* b = corner(xyz, num_vertices, triangles[3 * t + 1]);
    const double* c = corner(xyz, num_vertices, triangles[3 * t + 2]);
    for (const double* p : {a, b, c})
      for (int k = 0; k < 3; ++k) {
        if (!std::isfinite(p[k])) throw NonFiniteInput("enclosed_volume_sign: non-finite vertex coordinate");
        safe &= in_safe_range(p[k]);
      }
    const double p0 = b[1] * c[2], q0 = b[2] * c[1], p1 = b[2] * c[0], q1 = b[0] * c[2];
    const double p2 = b[0] * c[1], q2 = b[1] * c[0];
    sum += a[0] * (p0 - q0) + a[1] * (p1 - q1) + a[2] * (p2 - q2);
    magnitude += std::fabs(a[0]) * (std::fabs(p0) + std::fabs(q0)) + std::fabs(a[1]) * (std::fabs(p1) + std::fabs(q1)) +
                 std::fabs(a[2]) * (std::fabs(p2) + std::fabs(q2));
  }
  if (!safe) return rational_sum_sign(xyz, num_vertices, triangles, num_triangles);
  const double bound = 2.0 * (double(num_triangles) + 8.0) * 0x1p-53 * magnitude;
  if (num_triangles < (std::size_t(1) << 40)) {
    if (sum > bound) return 1;
    if (sum < -bound) return -1;
  }
  return expansion_sum_sign(xyz, num_vertices, triangles, num_triangles);
}

}  // namespace volmap
