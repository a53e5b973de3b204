// expansion.hpp — error-free transformations and floating-point expansion arithmetic (internal).
//
// Written from the formulas of J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and
// Fast Robust Geometric Predicates", Discrete Comput. Geom. 18 (1997), §2 (Two-Sum, Fast-Two-Sum,
// Split, Two-Product, Fast-Expansion-Sum, Scale-Expansion, both zero-eliminating).
// An expansion is an array of non-overlapping doubles sorted by increasing magnitude; its value is
// the exact sum, and its sign is the sign of its last (largest) component. Our expansions always
// have at least one component (the zero expansion is {0.0}).
// Assumptions: IEEE binary64, round-to-nearest-even, no contraction (this TU family is compiled with
// -ffp-contract=off), no overflow/underflow of intermediate products (the callers guard the range).
#pragma once

#include <cmath>

namespace volmap::detail {

// s + t == a + b exactly, s = fl(a + b).
inline void two_sum(double a, double b, double& s, double& t) {
  s = a + b;
  const double bv = s - a;
  const double av = s - bv;
  t = (a - av) + (b - bv);
}
// s + t == a - b exactly.
inline void two_diff(double a, double b, double& s, double& t) {
  s = a - b;
  const double bv = a - s;
  const double av = s + bv;
  t = (a - av) + (bv - b);
}
// Requires |a| >= |b| (or a == 0).
inline void fast_two_sum(double a, double b, double& s, double& t) {
  s = a + b;
  t = b - (s - a);
}
// p + e == a * b exactly (no underflow assumed).
inline void two_product(double a, double b, double& p, double& e) {
  p = a * b;
#ifdef FP_FAST_FMA
  e = std::fma(a, b, -p);  // hardware FMA: the only place a fused operation is allowed
#else
  constexpr double splitter = 134217729.0;  // 2^27 + 1 (Veltkamp/Dekker split)
  double c = splitter * a;
  const double ahi = c - (c - a);
  const double alo = a - ahi;
  c = splitter * b;
  const double bhi = c - (c - b);
  const double blo = b - bhi;
  e = alo * blo - (((p - ahi * bhi) - alo * bhi) - ahi * blo);
#endif
}

// h = e + f (zero-eliminating Fast-Expansion-Sum: merge by magnitude, then a Two-Sum chain).
// h must hold elen + flen components and must not alias e or f. Returns the length of h (>= 1).
inline int expansion_sum(const double* e, int elen, const double* f, int flen, double* h) {
  int i = 0, j = 0, k = 0;
  auto next = [&]() -> double {
    if (j >= flen || (i < elen && std::fabs(e[i]) <= std::fabs(f[j]))) return e[i++];
    return f[j++];
  };
  double q = next();
  while (i < elen || j < flen) {
    double s, t;
    two_sum(q, next(), s, t);
    if (t != 0.0) h[k++] = t;
    q = s;
  }
  if (q != 0.0 || k == 0) h[k++] = q;
  return k;
}

// h = b * e (zero-eliminating Scale-Expansion). h must hold 2*elen components. Returns length >= 1.
inline int scale_expansion(const double* e, int elen, double b, double* h) {
  int k = 0;
  double q, t;
  two_product(e[0], b, q, t);
  if (t != 0.0) h[k++] = t;
  for (int i = 1; i < elen; ++i) {
    double p1, p0, sum;
    two_product(e[i], b, p1, p0);
    two_sum(q, p0, sum, t);
    if (t != 0.0) h[k++] = t;
    fast_two_sum(p1, sum, q, t);
    if (t != 0.0) h[k++] = t;
  }
  if (q != 0.0 || k == 0) h[k++] = q;
  return k;
}

// h = e * f. h must hold 2*elen*flen components; scratch must hold 4*elen*flen. Returns length.
inline int expansion_product(const double* e, int elen, const double* f, int flen, double* h, double* scratch) {
  double* term = scratch;                  // 2*elen
  double* acc = scratch + 2 * elen;        // ping-pong partner of h, 2*elen*flen
  int len = scale_expansion(e, elen, f[0], h);
  for (int j = 1; j < flen; ++j) {
    const int tl = scale_expansion(e, elen, f[j], term);
    for (int c = 0; c < len; ++c) acc[c] = h[c];
    len = expansion_sum(acc, len, term, tl, h);
  }
  return len;
}

// {x1, x0} - {y1, y0} for two-component expansions, as an expansion (up to 4 components).
inline int two_two_diff(double x1, double x0, double y1, double y0, double* h) {
  const double a[2] = {x0, x1};
  const double b[2] = {-y0, -y1};
  return expansion_sum(a, 2, b, 2, h);
}
// a*b - c*d exactly, up to 4 components.
inline int cross_diff(double a, double b, double c, double d, double* h) {
  double p1, p0, q1, q0;
  two_product(a, b, p1, p0);
  two_product(c, d, q1, q0);
  return two_two_diff(p1, p0, q1, q0, h);
}
// a*a + b*b exactly, up to 4 components.
inline int sum_of_squares(double a, double b, double* h) {
  double p1, p0, q1, q0;
  two_product(a, a, p1, p0);
  two_product(b, b, q1, q0);
  const double x[2] = {p0, p1};
  const double y[2] = {q0, q1};
  return expansion_sum(x, 2, y, 2, h);
}

// det[a; b; c] of three rows (ax ay az), (bx by bz), (cx cy cz) exactly, up to 24 components:
// az·(bx·cy − cx·by) + bz·(cx·ay − ax·cy) + cz·(ax·by − bx·ay).
inline int det3_expansion(double ax, double ay, double az, double bx, double by, double bz, double cx, double cy,
                          double cz, double* out) {
  double m[4], s1[8], s2[8], s3[8], t16[16];
  int lm = cross_diff(bx, cy, cx, by, m);
  const int l1 = scale_expansion(m, lm, az, s1);
  lm = cross_diff(cx, ay, ax, cy, m);
  const int l2 = scale_expansion(m, lm, bz, s2);
  lm = cross_diff(ax, by, bx, ay, m);
  const int l3 = scale_expansion(m, lm, cz, s3);
  const int l16 = expansion_sum(s1, l1, s2, l2, t16);
  return expansion_sum(t16, l16, s3, l3, out);
}

inline int expansion_sign(const double* e, int len) { return (e[len - 1] > 0.0) - (e[len - 1] < 0.0); }
inline double expansion_estimate(const double* e, int len) {
  double s = 0.0;
  for (int i = 0; i < len; ++i) s += e[i];
  return s;
}

}  // namespace volmap::detail
