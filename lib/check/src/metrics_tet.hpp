// metrics_tet.hpp (internal to lib/check) — the per-tet kernels of the metrics (volmap-reference.md §7).
// Conventions: points are 3 doubles; a tet is evaluated in the INPUT tet's vertex order on both meshes;
// F = [p1−p0 | p2−p0 | p3−p0] (edge vectors as columns); J = F_out·F_in⁻¹; s1 ≥ s2 ≥ s3 its singular
// values; I1 = ‖J‖² = Σsᵢ², I2 = ‖cof J‖² = Σ_{i<j} sᵢ²sⱼ², d = det J (|d| = s1s2s3).
//
// Two ways to the five VOLMAP energies of a tet, with the same printed digits:
//  * compat_energies(JacobiSVD singular values): VOLMAP's own floating-point path (Eigen's fixed-size
//    inverse of F_in, J by a plain i-j-k product from 0, Eigen::JacobiSVD, cinolib's formulas);
//  * closed_form_energies(invariants of the same J): Dirichlet = I1, SymDir = I1 + I2/d²,
//    Conformal = I1/(3|d|^{2/3}), MIPS3D = (I1·I2 − d²)/(8d²) (from (a+b)(b+c)(c+a) = ΣaΣab − abc with
//    a = s1² ...), ARAP = I1 − 2Σsᵢ + 3 with Σsᵢ from sum_of_singular_values, or clamped without it when
//    (√I1 − √3)² ≥ upper (‖s − 1‖ ≥ ‖s‖ − √3).
//  The closed forms agree with the SVD path to a few ulps on every value below the clamp (a value
//  below `upper` bounds the condition number of J), so they are used unless a value lies within
//  kAgreementBand (relative) of a clamp bound, or or ARAP cancels (ARAP < kArapCancellation·(I1 + 2Σs + 3)):
//  there the clamped result or the rounding noise itself is what VOLMAP prints (e.g. the identity map's
//  ARAP 7.3e−30), and the tet takes the SVD path. Overflowing or vanishing invariants take it too.
#pragma once

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace volmap::metrics_detail {

inline constexpr int kEnergies = 5;  // conformal, dirichlet, symmetric dirichlet, arap, mips3d
inline constexpr double kLowerBound[kEnergies] = {1.0, 3.0, 6.0, 0.0, 1.0};
inline constexpr double kAgreementBand = 1e-7;
inline constexpr double kArapCancellation = 1e-6;

using RowMat3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

inline double clamp_energy(double d, double lower, double upper) {
  if (std::isinf(d) || std::isnan(d)) d = upper;
  return std::clamp(d, lower, upper);
}

// F (row-major, columns p1−p0, p2−p0, p3−p0).
inline RowMat3 edge_matrix(const double* const p[4]) {
  RowMat3 f;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) f(r, c) = p[c + 1][r] - p[0][r];
  return f;
}

inline double det3(const RowMat3& m) {
  return m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0)) +
         m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
}

// VOLMAP's J = F_out·F_in⁻¹: Eigen's fixed-size inverse, then a plain triple loop accumulating from 0.
inline RowMat3 compat_jacobian(const RowMat3& f_in, const RowMat3& f_out) {
  const RowMat3 inv = f_in.inverse();
  RowMat3 j;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      double acc = 0;
      for (int k = 0; k < 3; ++k) acc += f_out(r, k) * inv(k, c);
      j(r, c) = acc;
    }
  return j;
}

// Eigen::JacobiSVD (full U and V, as the reference) of a finite J; NaN when J is not finite (then Eigen
// 3.4 returns early and the reference reads uninitialised values, see MetricsOptions).
inline void jacobi_singular_values(const RowMat3& j, double sigma[3]) {
  if (!j.allFinite()) {
    sigma[0] = sigma[1] = sigma[2] = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  const Eigen::JacobiSVD<RowMat3> svd(j, Eigen::ComputeFullU | Eigen::ComputeFullV);
  for (int k = 0; k < 3; ++k) sigma[k] = svd.singularValues()[k];
}

// cinolib's five 3D energies of (s_max, s_mid, s_min), in its operation order, clamped as VOLMAP does.
inline void compat_energies(const double s[3], double upper, double* out) {
  const double a = s[0], b = s[1], c = s[2];
  const double conformal = (a * a + b * b + c * c) / (3 * std::pow(a * b * c, 2. / 3.));
  const double dirichlet = a * a + b * b + c * c;
  const double symdir = a * a + b * b + c * c + 1 / (a * a) + 1 / (b * b) + 1 / (c * c);
  const double arap = std::pow(a - 1, 2) + std::pow(b - 1, 2) + std::pow(c - 1, 2);
  const double mips = 1. / 8. * (a / b + b / a) * (c / a + a / c) * (b / c + c / b);
  const double raw[kEnergies] = {conformal, dirichlet, symdir, arap, mips};
  for (int e = 0; e < kEnergies; ++e) out[e] = clamp_energy(raw[e], kLowerBound[e], upper);
}

// x^{−1/3} for x > 0 to a few ulps, without division: a bit-level first guess (exponent and mantissa
// scaled by −1/3, ≤ 4 % off) refined by four Newton steps y ← y(4 − x·y³)/3 (quadratic convergence:
// 4e−2 → 5e−3 → 7e−5 → 2e−8 → rounding). Outside [1e−300, 1e300] and for non-finite x, libm's cbrt.
inline double inverse_cube_root(double x) {
  if (!(x > 1e-300 && x < 1e300)) return 1.0 / std::cbrt(x);
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  bits = 0x553EF0FF289DD796ull - bits / 3;
  double y;
  std::memcpy(&y, &bits, sizeof y);
  for (int it = 0; it < 4; ++it) y *= (4.0 - x * y * y * y) * (1.0 / 3.0);
  return y;
}

struct Invariants {
  double i1 = 0, i2 = 0, det = 0;
};

inline Invariants invariants_of(const RowMat3& j, double det) {
  Invariants v;
  v.det = det;
  v.i1 = j.squaredNorm();
  for (int r = 0; r < 3; ++r) {
    const int r1 = (r + 1) % 3, r2 = (r + 2) % 3;
    for (int c = 0; c < 3; ++c) {
      const int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
      const double minor = j(r1, c1) * j(r2, c2) - j(r1, c2) * j(r2, c1);
      v.i2 += minor * minor;
    }
  }
  return v;
}

// Invariants that the closed forms can use at all: finite, no overflow in I1·I2 or d².
inline bool invariants_in_range(const Invariants& v) {
  const double d2 = v.det * v.det;
  return std::isfinite(v.i1) && std::isfinite(v.i2) && v.i1 < 1e100 && v.i2 < 1e200 && std::isfinite(d2) && d2 < 1e200;
}

// det J accurate: its rounding error is a few ulps of the product of the row norms, ≤ (I1/3)^{3/2}, so
// d² ≥ kDetConditioning·(I1/3)³ keeps it below ~1e−10 relative. Every tet whose Conformal, MIPS3D or
// symmetric Dirichlet energy is below 100 passes (Conformal < 100 alone implies d² > 1e−6·(I1/3)³).
inline constexpr double kDetConditioning = 1e-12;
inline bool det_accurate(const Invariants& v) {
  const double d2 = v.det * v.det, third = v.i1 / 3;
  return d2 > 1e-200 && d2 >= kDetConditioning * third * third * third;
}

// When det J is not accurate (J near rank-deficient: heavily distorted tets, source tets flat at double
// precision), |d| < 1e−6·(I1/3)^{3/2} up to rounding, and so is the product of the singular values any
// backward-stable SVD computes (Weyl: each moves by ≤ c·ε·s1). Then Conformal ≥ (1.1e−6)^{−2/3} > 9000,
// MIPS3D ≥ (9·Conformal − 1)/8 (I2 ≥ 3d^{4/3}) and SymDir ≥ I1 + 3/(s1s2s3)^{2/3} ≥ 2·√(8.4e4) > 580 on
// the SVD path too: below this upper bound all three clamp to `upper` without evaluating them.
inline constexpr double kDegenerateEnergyFloor = 500;

// Σsᵢ from the invariants: x = Σsᵢ and y = Σ_{i<j} sᵢsⱼ satisfy x² = I1 + 2y and y² = I2 + 2|d|x, so
// x is the root in [√I1, √(3 I1)] of f(x) = ((x² − I1)/2)² − I2 − 2|d|x, which is convex and increasing
// there: Newton from the upper bound x0 = √(I1 + 2√(I2 + 2|d|√(3 I1))) decreases monotonically to it.
// No cancellation: relative accuracy ~ a few ulps even when J is far from conformal.
inline double sum_of_singular_values(const Invariants& v) {
  const double d = std::fabs(v.det);
  double x = std::sqrt(v.i1 + 2 * std::sqrt(v.i2 + 2 * d * std::sqrt(3 * v.i1)));
  for (int it = 0; it < 32; ++it) {
    const double y = 0.5 * (x * x - v.i1);
    const double f = y * y - v.i2 - 2 * d * x;
    const double fp = 2 * x * y - 2 * d;
    if (!(f > 0) || !(fp > 0)) break;
    const double step = f / fp;
    if (!(step > 0)) break;
    x -= step;
    if (step <= 1e-16 * x) break;  // quadratic convergence: the next step would be below rounding
  }
  return x;
}

// True when `value` (before clamping) may lie on the other side of a clamp bound, or in the clamp
// band itself, on the SVD path.
inline bool near_bound(double value, double lower, double upper) {
  return std::fabs(value - upper) <= kAgreementBand * upper ||
         std::fabs(value - lower) <= kAgreementBand * std::max(1.0, lower);
}

// Per-run constants of the closed forms.
struct ClosedFormBounds {
  double upper;
  double arap_clamp_i1;  // I1 at or above which (√I1 − √3)² ≥ upper·(1 + kAgreementBand): ARAP clamps
  explicit ClosedFormBounds(double upper_bound)
      : upper(upper_bound),
        arap_clamp_i1((std::sqrt(3.0) + std::sqrt(upper_bound * (1 + kAgreementBand))) *
                      (std::sqrt(3.0) + std::sqrt(upper_bound * (1 + kAgreementBand)))) {}
};

// The two costly intermediates of the closed forms of one J, kept for the energies of k·J, which
// share them: |d|^{−2/3} (Conformal and MIPS3D do not change with k) and Σsᵢ (scales with k).
// NaN until computed.
struct ClosedFormParts {
  double inverse_cbrt_d2 = std::numeric_limits<double>::quiet_NaN();
  double sum_sv = std::numeric_limits<double>::quiet_NaN();
};

// Conformal = I1·|d|^{−2/3}/3, SymDir = I1 + I2/d², MIPS3D = (I1·I2 − d²)/(8d²), into raw[0], raw[2],
// raw[4]; r = |d|^{−2/3}.
inline void scale_free_energies(const Invariants& v, double r, double* raw) {
  const double d2 = v.det * v.det, inv_d2 = 1.0 / d2;
  raw[0] = v.i1 * r * (1.0 / 3.0);
  raw[2] = v.i1 + v.i2 * inv_d2;
  raw[4] = (v.i1 * v.i2 - d2) * inv_d2 * 0.125;
}

// The five clamped compat energies from the invariants of the compat J (d = det of that J). Returns
// false (out unspecified) when the tet must take the SVD path (see the file comment). `parts`
// receives the intermediates it computed.
inline bool closed_form_energies(const Invariants& v, const ClosedFormBounds& bounds, double* out,
                                 ClosedFormParts& parts) {
  if (!invariants_in_range(v)) return false;
  const double upper = bounds.upper;
  double raw[kEnergies];
  bool clamped[kEnergies] = {false, false, false, false, false};  // known to clamp to upper
  if (det_accurate(v)) {
    parts.inverse_cbrt_d2 = inverse_cube_root(v.det * v.det);
    scale_free_energies(v, parts.inverse_cbrt_d2, raw);
  } else if (upper < kDegenerateEnergyFloor) {
    clamped[0] = clamped[2] = clamped[4] = true;
  } else {
    return false;
  }
  raw[1] = v.i1;
  if (v.i1 >= bounds.arap_clamp_i1) {
    clamped[3] = true;  // ARAP ≥ (‖s‖ − √3)² whatever the singular values
  } else if (det_accurate(v)) {
    const double x = sum_of_singular_values(v);
    parts.sum_sv = x;
    raw[3] = v.i1 - 2 * x + 3;
    if (raw[3] < kArapCancellation * (v.i1 + 2 * x + 3)) return false;
  } else {
    return false;
  }
  for (int e = 0; e < kEnergies; ++e) {
    if (clamped[e]) {
      out[e] = upper;
      continue;
    }
    if (near_bound(raw[e], kLowerBound[e], upper)) return false;
    out[e] = clamp_energy(raw[e], kLowerBound[e], upper);
  }
  return true;
}

// Energies of k·J (the output scaled by k about the origin) from the invariants of J, with d = det J
// taken as det F_out / det F_in (no cancellation in the product of singular values), reusing the
// intermediates of J's closed forms where they were computed (|d|^{−2/3} and Σsᵢ of J then come from
// det J itself, which agrees with det F_out / det F_in to rounding where the closed forms apply). Not
// a VOLMAP field: no compatibility band.
inline void scaled_energies(const Invariants& v, double k, const ClosedFormBounds& bounds, const ClosedFormParts& parts,
                            double* out) {
  const double upper = bounds.upper;
  const double k2 = k * k;
  Invariants s;
  s.i1 = v.i1 * k2;
  s.i2 = v.i2 * k2 * k2;
  s.det = v.det * k2 * k;
  double raw[kEnergies];
  // |k³d|^{−2/3} = |d|^{−2/3}/k².
  scale_free_energies(
      s, std::isnan(parts.inverse_cbrt_d2) ? inverse_cube_root(s.det * s.det) : parts.inverse_cbrt_d2 / k2, raw);
  raw[1] = s.i1;
  if (s.i1 >= bounds.arap_clamp_i1)
    raw[3] = upper;  // ARAP ≥ (‖s‖ − √3)² ≥ upper (see ClosedFormBounds)
  else
    raw[3] = s.i1 - 2 * (std::isnan(parts.sum_sv) ? sum_of_singular_values(s) : k * parts.sum_sv) + 3;
  for (int e = 0; e < kEnergies; ++e) out[e] = clamp_energy(raw[e], kLowerBound[e], upper);
}

// ---- Output-tet measures (Verdict SAND2007-1751 §6.11 radius ratio and scaled Jacobian) ----

// Scalars of the tet measures: double, or Lanes = two doubles evaluated side by side (lane 0 the input
// tet, lane 1 the output tet). Every lane operation is the IEEE operation of the scalar code, so both
// give bit-identical values (no contraction into FMA: the baseline x86-64 target has none).
using Lanes = double __attribute__((vector_size(16)));
inline double square_root(double v) { return std::sqrt(v); }
inline Lanes square_root(Lanes v) {
#if defined(__SSE2__)
  return __builtin_ia32_sqrtpd(v);
#else
  return Lanes{std::sqrt(v[0]), std::sqrt(v[1])};
#endif
}

template <class S>
struct Vec3T {
  S x, y, z;
};
template <class S>
Vec3T<S> sub(const Vec3T<S>& a, const Vec3T<S>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class S>
Vec3T<S> cross(const Vec3T<S>& a, const Vec3T<S>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class S>
S dot(const Vec3T<S>& a, const Vec3T<S>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class S>
S norm(const Vec3T<S>& a) {
  return square_root(dot(a, a));
}
using Vec3 = Vec3T<double>;
inline Vec3 point(const double* p) { return {p[0], p[1], p[2]}; }
inline Vec3 sub(const double* a, const double* b) { return sub(point(a), point(b)); }
// The same point of the input (lane 0) and of the output (lane 1).
inline Vec3T<Lanes> point_pair(const double* a, const double* b) {
  return {Lanes{a[0], b[0]}, Lanes{a[1], b[1]}, Lanes{a[2], b[2]}};
}

// The edge vectors and face normals of a tet (p0..p3) that the Verdict measures share, with
// Verdict's / cinolib's names: L0 = p1−p0, L1 = p2−p1, L2 = p0−p2, L3 = p3−p0, L4 = p3−p1, L5 = p3−p2,
// Cij = Li × Lj. Every measure below evaluates its formula in the reference's operation order.
template <class S>
struct TetFrameT {
  using V = Vec3T<S>;
  V l0, l1, l2, l3, l4;
  V c20, c30, c41, c32;
  S n0, n2, n3;  // |L0|², |L2|², |L3|²
  S jacobi;      // C20·L3 = 6 × cinolib's signed volume = −orient3d in doubles
  TetFrameT(const V& p0, const V& p1, const V& p2, const V& p3)
      : l0(sub(p1, p0)), l1(sub(p2, p1)), l2(sub(p0, p2)), l3(sub(p3, p0)), l4(sub(p3, p1)),
        c20(cross(l2, l0)), c30(cross(l3, l0)), c41(cross(l4, l1)), c32(cross(l3, l2)),
        n0(dot(l0, l0)), n2(dot(l2, l2)), n3(dot(l3, l3)), jacobi(dot(c20, l3)) {}

  // Verdict radius ratio R/(3r) before the zero-volume case (see radius_ratio_of).
  S radius_ratio_formula() const {
    const V numerator{n3 * c20.x + n2 * c30.x + n0 * c32.x, n3 * c20.y + n2 * c30.y + n0 * c32.y,
                      n3 * c20.z + n2 * c30.z + n0 * c32.z};
    const S area = (norm(c20) + norm(c30) + norm(c41) + norm(c32)) * 0.5;
    const S volume = jacobi / 6.0;
    return norm(numerator) * area / (108.0 * volume * volume);
  }
};

// R/(3r) (≥ 1, 1 for the regular tet); DBL_MAX for a zero-volume tet (jacobi = 6 × signed volume).
inline double radius_ratio_of(double formula, double jacobi) {
  return std::fabs(jacobi / 6.0) < std::numeric_limits<double>::min() ? std::numeric_limits<double>::max() : formula;
}

// Verdict scaled Jacobian from a frame's squared lengths, L1, L4, L5 = p3 − p2 and jacobi, negated so
// that VOLMAP-positive tets are > 0.
inline double scaled_jacobian_of(double n0, double n2, double n3, const Vec3& l1, const Vec3& l4, const Vec3& l5,
                                 double jacobi) {
  const double n1 = dot(l1, l1), n4 = dot(l4, l4), n5 = dot(l5, l5);
  const double products[4] = {n0 * n2 * n3, n0 * n1 * n4, n1 * n2 * n5, n3 * n4 * n5};
  double length_product = std::sqrt(std::max(std::max(products[0], products[1]), std::max(products[2], products[3])));
  if (length_product < std::fabs(jacobi)) length_product = std::fabs(jacobi);
  if (length_product < std::numeric_limits<double>::min()) return 0.0;
  return -std::sqrt(2.0) * jacobi / length_product;
}

// cinolib tet_unsigned_volume |(L2×L0)·L3| / 6 (VOLMAP's energy weight).
inline double unsigned_volume_of(double jacobi) { return std::fabs(jacobi / 6.0); }

struct TetFrame : TetFrameT<double> {
  TetFrame(const double* p0, const double* p1, const double* p2, const double* p3)
      : TetFrameT<double>(point(p0), point(p1), point(p2), point(p3)) {}
  double radius_ratio() const { return radius_ratio_of(radius_ratio_formula(), jacobi); }
  double scaled_jacobian(const double* p2, const double* p3) const {
    return scaled_jacobian_of(n0, n2, n3, l1, l4, sub(p3, p2), jacobi);
  }
};

// The input tet (lane 0) and the output tet (lane 1) with the same vertex ids, measured together.
struct TetFramePair : TetFrameT<Lanes> {
  TetFramePair(const double* const in[4], const double* const out[4])
      : TetFrameT<Lanes>(point_pair(in[0], out[0]), point_pair(in[1], out[1]), point_pair(in[2], out[2]),
                         point_pair(in[3], out[3])) {}
  static Vec3 lane(const Vec3T<Lanes>& v, int k) { return {v.x[k], v.y[k], v.z[k]}; }
};

// orient3d(p0,p1,p2,p3)/6 in doubles: −det[p1−p0, p2−p0, p3−p0]/6 (positive for VOLMAP tets).
inline double volume_volmap(const double* p0, const double* p1, const double* p2, const double* p3) {
  return -dot(cross(sub(p1, p0), sub(p2, p0)), sub(p3, p0)) / 6.0;
}

}  // namespace volmap::metrics_detail
