// predicates.cpp — layered exact predicates on doubles (layers L0–L3; L4 lives in exact.cpp).
//
// Conventions: Shewchuk's signs (see <volmap/predicates.hpp>); orient3d(a,b,c,d) = sign det[a−d; b−d;
// c−d], VOLMAP-positive tets have orient3d > 0. Design and constants: docs/predicates.md.
//   L1 (batch only) static filter  |det| > 5.1107127829973299e-15·Δx·Δy·Δz (CGAL/FPG constant, TetGen
//      and HXT use it with the bounding-box extents), valid when every input lies in the safe range.
//   L2 Shewchuk stage A: |det| > errA·permanent, plus under/overflow guards (see "Guards" below),
//      evaluated with the exact expression trees of Shewchuk's predicates.c, so his bounds apply.
//   L3 when every nonzero |coordinate| is in [2^-142, 2^201] (Shewchuk's proven range, where no
//      product of the algorithms below under- or overflows): if all Two-Diff tails are zero the
//      rounded differences are exact and one expansion evaluation gives the sign; otherwise orient2d /
//      orient3d try stage B (exact minors of the rounded differences, accept if |estimate| ≥ errB·
//      permanent), stage C (first-order tail terms, accept if |estimate| ≥ errC·permanent +
//      resulterrbound·|B|) and then (stage D) the exact expansion of the raw-coordinate determinant
//      det[p_i 1]; incircle and insphere with nonzero tails go to L4.
//   L4 exact integers (exact.cpp) for inputs outside the safe range.
// Reference: J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
// Predicates", DCG 18 (1997). This TU must be compiled without FP contraction (-ffp-contract=off).
#include <volmap/predicates.hpp>

#include "exact.hpp"
#include "layers.hpp"
#include "fp_env.hpp"
#include "expansion.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace volmap {
namespace {

using namespace detail;

constexpr double kEps = 0x1p-53;
// Shewchuk's stage-A bounds with 8ε² of extra slack for the underflow guards below (a larger bound
// is always sound).
constexpr double kO2ErrA = (3.0 + 24.0 * kEps) * kEps;
constexpr double kO2ErrB = (2.0 + 12.0 * kEps) * kEps;
constexpr double kO3ErrA = (7.0 + 64.0 * kEps) * kEps;
constexpr double kO3ErrB = (3.0 + 28.0 * kEps) * kEps;
constexpr double kO3ErrC = (26.0 + 288.0 * kEps) * kEps * kEps;
constexpr double kO2ErrC = (9.0 + 64.0 * kEps) * kEps * kEps;
constexpr double kResultErr = (3.0 + 8.0 * kEps) * kEps;
constexpr double kIcErrA = (10.0 + 104.0 * kEps) * kEps;
constexpr double kIsErrA = (16.0 + 232.0 * kEps) * kEps;
// Stage A assumes no overflow: every accepted threshold requires a permanent below this bound (then
// no partial sum of the determinant can overflow either).
constexpr double kPermanentMax = 0x1p1000;
// Guards of stage A (our derivation). Shewchuk's relative bounds assume no underflow. With gradual
// underflow, additions and subtractions stay exact and each product adds an absolute error ≤ η =
// 2^-1075, which the later factors scale: the extra error is ≤ 14η(Σ|z| + 1) for orient3d, ≤ 2η for
// orient2d, ≤ 64η(Σlift + 1) for incircle and ≤ 512η(Σlift + 1)² for insphere. Rather than add that
// margin T (a subnormal computation, slow on x86), the filter accepts only when |det| is large
// enough and the scale factor small enough that T ≤ 2^-64·|det|, which the 8ε² of extra slack in the
// constants absorbs: orient3d |det| ≥ 2^-590 and Σ|z| ≤ 2^400; orient2d |det| ≥ 2^-900; incircle
// |det| ≥ 2^-590 and Σlift ≤ 2^400; insphere |det| ≥ 2^-580 and Σlift ≤ 2^200. Overflow: every
// accepted case also needs permanent < 2^1000 (false for inf/NaN), so no partial sum overflowed.
// Everything else falls through to the exact layers, which are always correct.

// Shewchuk's proven range: nonzero |x| in [2^-142, 2^201] keeps every expansion product exact.
inline bool in_safe_range(double x) {
  const double ax = std::fabs(x);
  return ax == 0.0 || (ax >= 0x1p-142 && ax <= 0x1p201);
}
template <int N>
bool all_in_safe_range(const double* const (&p)[N], int dim) {
  bool ok = true;
  for (int i = 0; i < N; ++i)
    for (int k = 0; k < dim; ++k) ok &= in_safe_range(p[i][k]);
  return ok;
}
inline int sign_of(double x) { return (x > 0.0) - (x < 0.0); }

// ---------------------------------------------------------------------------------------------
// orient2d
int orient2d_exact_tail(const double* a, const double* b, const double* c, double permanent) {
  double acx, acxt, acy, acyt, bcx, bcxt, bcy, bcyt;
  two_diff(a[0], c[0], acx, acxt);
  two_diff(a[1], c[1], acy, acyt);
  two_diff(b[0], c[0], bcx, bcxt);
  two_diff(b[1], c[1], bcy, bcyt);
  double e[4];
  const int n = cross_diff(acx, bcy, acy, bcx, e);
  if (acxt == 0.0 && acyt == 0.0 && bcxt == 0.0 && bcyt == 0.0) return expansion_sign(e, n);
  double est = expansion_estimate(e, n);
  if (std::fabs(est) >= kO2ErrB * permanent) return sign_of(est);
  // Stage C: first-order tail terms.
  const double errbound = kO2ErrC * permanent + kResultErr * std::fabs(est);
  est += (acx * bcyt + bcy * acxt) - (acy * bcxt + bcx * acyt);
  if (std::fabs(est) >= errbound) return sign_of(est);
  // Exact: det[p_i 1] = ab − ac + bc with xy-minors of the raw coordinates.
  double ab[4], ac[4], bc[4], t8[8], r[12];
  const int lab = cross_diff(a[0], b[1], a[1], b[0], ab);
  const int lac = cross_diff(c[0], a[1], c[1], a[0], ac);  // = −(a × c)
  const int lbc = cross_diff(b[0], c[1], b[1], c[0], bc);
  const int l8 = expansion_sum(ab, lab, ac, lac, t8);
  const int lr = expansion_sum(t8, l8, bc, lbc, r);
  return expansion_sign(r, lr);
}

__attribute__((noinline, cold)) int orient2d_slow(const double* a, const double* b, const double* c, double permanent) {
  const double* const p[3] = {a, b, c};
  if (!all_in_safe_range(p, 2)) return orient2d_integer(a, b, c);
  return orient2d_exact_tail(a, b, c, permanent);
}

// ---------------------------------------------------------------------------------------------
// orient3d
// Exact orient3d = det4[p_i 1] from raw coordinates:
//   za·(bc − bd + cd) − zb·(ac − ad + cd) + zc·(ab − ad + bd) − zd·(ab − ac + bc),
// with pq = px·qy − py·qx (Laplace expansion along the x,y columns).
int orient3d_raw_exact(const double* a, const double* b, const double* c, const double* d) {
  double ab[4], ac[4], ad[4], bc[4], bd[4], cd[4];
  const int lab = cross_diff(a[0], b[1], a[1], b[0], ab);
  const int lac = cross_diff(a[0], c[1], a[1], c[0], ac);
  const int lad = cross_diff(a[0], d[1], a[1], d[0], ad);
  const int lbc = cross_diff(b[0], c[1], b[1], c[0], bc);
  const int lbd = cross_diff(b[0], d[1], b[1], d[0], bd);
  const int lcd = cross_diff(c[0], d[1], c[1], d[0], cd);
  auto negate = [](double* e, int n) {
    for (int i = 0; i < n; ++i) e[i] = -e[i];
  };
  // three-term minors: x − y + z
  auto minor3 = [&](const double* x, int lx, double* y, int ly, const double* z, int lz, double* out) {
    double t8[8], ny[4];
    for (int i = 0; i < ly; ++i) ny[i] = -y[i];
    const int l8 = expansion_sum(x, lx, ny, ly, t8);
    return expansion_sum(t8, l8, z, lz, out);
  };
  double bcd[12], acd[12], abd[12], abc[12];
  const int lbcd = minor3(bc, lbc, bd, lbd, cd, lcd, bcd);
  const int lacd = minor3(ac, lac, ad, lad, cd, lcd, acd);
  const int labd = minor3(ab, lab, ad, lad, bd, lbd, abd);
  const int labc = minor3(ab, lab, ac, lac, bc, lbc, abc);
  negate(acd, lacd);
  negate(abc, labc);
  double ta[24], tb[24], tc[24], td[24], s48a[48], s48b[48], r[96];
  const int la = scale_expansion(bcd, lbcd, a[2], ta);
  const int lb = scale_expansion(acd, lacd, b[2], tb);
  const int lc = scale_expansion(abd, labd, c[2], tc);
  const int ld = scale_expansion(abc, labc, d[2], td);
  const int l1 = expansion_sum(ta, la, tb, lb, s48a);
  const int l2 = expansion_sum(tc, lc, td, ld, s48b);
  const int lr = expansion_sum(s48a, l1, s48b, l2, r);
  return expansion_sign(r, lr);
}

// L3 for orient3d (inputs in the safe range): tail-free exact, stage B, then the raw exact sum.
int orient3d_exact_tail(const double* a, const double* b, const double* c, const double* d, double permanent) {
  double adx, adxt, ady, adyt, adz, adzt, bdx, bdxt, bdy, bdyt, bdz, bdzt, cdx, cdxt, cdy, cdyt, cdz, cdzt;
  two_diff(a[0], d[0], adx, adxt);
  two_diff(a[1], d[1], ady, adyt);
  two_diff(a[2], d[2], adz, adzt);
  two_diff(b[0], d[0], bdx, bdxt);
  two_diff(b[1], d[1], bdy, bdyt);
  two_diff(b[2], d[2], bdz, bdzt);
  two_diff(c[0], d[0], cdx, cdxt);
  two_diff(c[1], d[1], cdy, cdyt);
  two_diff(c[2], d[2], cdz, cdzt);
  double e[24];
  const int n = det3_expansion(adx, ady, adz, bdx, bdy, bdz, cdx, cdy, cdz, e);
  if (adxt == 0.0 && adyt == 0.0 && adzt == 0.0 && bdxt == 0.0 && bdyt == 0.0 && bdzt == 0.0 && cdxt == 0.0 &&
      cdyt == 0.0 && cdzt == 0.0)
    return expansion_sign(e, n);
  double est = expansion_estimate(e, n);
  if (std::fabs(est) >= kO3ErrB * permanent) return sign_of(est);
  // Stage C: first-order tail terms (Shewchuk 1997, orient3dadapt).
  const double errbound = kO3ErrC * permanent + kResultErr * std::fabs(est);
  est += (adz * ((bdx * cdyt + cdy * bdxt) - (bdy * cdxt + cdx * bdyt)) + adzt * (bdx * cdy - bdy * cdx)) +
         (bdz * ((cdx * adyt + ady * cdxt) - (cdy * adxt + adx * cdyt)) + bdzt * (cdx * ady - cdy * adx)) +
         (cdz * ((adx * bdyt + bdy * adxt) - (ady * bdxt + bdx * adyt)) + cdzt * (adx * bdy - ady * bdx));
  if (std::fabs(est) >= errbound) return sign_of(est);
  return orient3d_raw_exact(a, b, c, d);
}

// After stage A failed (any finite input): zero-column shortcut, then L3 or L4.
__attribute__((noinline, cold)) int orient3d_slow(const double* a, const double* b, const double* c, const double* d, double permanent) {
  for (int k = 0; k < 3; ++k)  // a whole translated column is zero: the determinant is exactly 0
    if (a[k] == d[k] && b[k] == d[k] && c[k] == d[k]) return 0;
  const double* const p[4] = {a, b, c, d};
  if (!all_in_safe_range(p, 3)) return orient3d_integer(a, b, c, d);
  return orient3d_exact_tail(a, b, c, d, permanent);
}

// Stage A on (already translated) differences. Returns ±1, or 0 when undecided (then *permanent is
// set for stage B). See "Guards" above: accepted only when |det| ≥ 2^-590 and Σ|z| ≤ 2^400.
inline int orient3d_stage_a(double adx, double ady, double adz, double bdx, double bdy, double bdz, double cdx,
                            double cdy, double cdz, double* permanent_out) {
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  const double az = std::fabs(adz), bz = std::fabs(bdz), cz = std::fabs(cdz);
  const double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * az + (std::fabs(cdxady) + std::fabs(adxcdy)) * bz +
                           (std::fabs(adxbdy) + std::fabs(bdxady)) * cz;
  *permanent_out = permanent;
  const double abs_det = std::fabs(det);
  // one branch for the whole test (non-short-circuit &)
  if ((abs_det > kO3ErrA * permanent) & (abs_det >= 0x1p-590) & (permanent < kPermanentMax) &
      ((az + bz + cz) <= 0x1p400))
    return sign_of(det);
  return 0;
}

// ---------------------------------------------------------------------------------------------
// incircle
// Exact incircle from exact differences: Σ lift_i · minor_jk as an expansion.
int incircle_diff_exact(double adx, double ady, double bdx, double bdy, double cdx, double cdy) {
  double lift[4], m[4], prod[32], scratch[64], t64[64], s[32], r[96];
  int ll = sum_of_squares(adx, ady, lift);
  int lm = cross_diff(bdx, cdy, cdx, bdy, m);
  int lp = expansion_product(lift, ll, m, lm, prod, scratch);
  for (int i = 0; i < lp; ++i) s[i] = prod[i];
  int ls = lp;
  ll = sum_of_squares(bdx, bdy, lift);
  lm = cross_diff(cdx, ady, adx, cdy, m);
  lp = expansion_product(lift, ll, m, lm, prod, scratch);
  const int l64 = expansion_sum(s, ls, prod, lp, t64);
  ll = sum_of_squares(cdx, cdy, lift);
  lm = cross_diff(adx, bdy, bdx, ady, m);
  lp = expansion_product(lift, ll, m, lm, prod, scratch);
  ls = expansion_sum(t64, l64, prod, lp, r);
  return expansion_sign(r, ls);
}

__attribute__((noinline, cold)) int incircle_slow(const double* a, const double* b, const double* c, const double* d) {
  const double* const p[4] = {a, b, c, d};
  if (!all_in_safe_range(p, 2)) return incircle_integer(a, b, c, d);
  double adx, adxt, ady, adyt, bdx, bdxt, bdy, bdyt, cdx, cdxt, cdy, cdyt;
  two_diff(a[0], d[0], adx, adxt);
  two_diff(a[1], d[1], ady, adyt);
  two_diff(b[0], d[0], bdx, bdxt);
  two_diff(b[1], d[1], bdy, bdyt);
  two_diff(c[0], d[0], cdx, cdxt);
  two_diff(c[1], d[1], cdy, cdyt);
  if (adxt == 0.0 && adyt == 0.0 && bdxt == 0.0 && bdyt == 0.0 && cdxt == 0.0 && cdyt == 0.0)
    return incircle_diff_exact(adx, ady, bdx, bdy, cdx, cdy);
  return incircle_integer(a, b, c, d);
}

// ---------------------------------------------------------------------------------------------
// insphere
// Exact insphere from exact differences (Shewchuk's expression):
//   (dlift·abc − clift·dab) + (blift·cda − alift·bcd).
int insphere_diff_exact(const double (&ex)[4][3]) {
  // 2×2 xy-minors of the translated rows: m[i][j] = ex_i·ey_j − ex_j·ey_i
  double ab[4], bc[4], cd[4], da[4], ac[4], bd[4];
  const int lab = cross_diff(ex[0][0], ex[1][1], ex[1][0], ex[0][1], ab);
  const int lbc = cross_diff(ex[1][0], ex[2][1], ex[2][0], ex[1][1], bc);
  const int lcd = cross_diff(ex[2][0], ex[3][1], ex[3][0], ex[2][1], cd);
  const int lda = cross_diff(ex[3][0], ex[0][1], ex[0][0], ex[3][1], da);
  const int lac = cross_diff(ex[0][0], ex[2][1], ex[2][0], ex[0][1], ac);
  const int lbd = cross_diff(ex[1][0], ex[3][1], ex[3][0], ex[1][1], bd);
  // z1·m1 + z2·m2 + z3·m3 (up to 24 components)
  auto three = [](const double* m1, int l1, double z1, const double* m2, int l2, double z2, const double* m3, int l3,
                  double z3, double* out) {
    double s1[8], s2[8], s3[8], t16[16];
    const int a1 = scale_expansion(m1, l1, z1, s1);
    const int a2 = scale_expansion(m2, l2, z2, s2);
    const int a3 = scale_expansion(m3, l3, z3, s3);
    const int a16 = expansion_sum(s1, a1, s2, a2, t16);
    return expansion_sum(t16, a16, s3, a3, out);
  };
  const double aez = ex[0][2], bez = ex[1][2], cez = ex[2][2], dez = ex[3][2];
  double abc[24], bcd[24], cda[24], dab[24];
  const int labc = three(bc, lbc, aez, ac, lac, -bez, ab, lab, cez, abc);
  const int lbcd = three(cd, lcd, bez, bd, lbd, -cez, bc, lbc, dez, bcd);
  const int lcda = three(da, lda, cez, ac, lac, dez, cd, lcd, aez, cda);
  const int ldab = three(ab, lab, dez, bd, lbd, aez, da, lda, bez, dab);
  double lift[4][6];
  int llift[4];
  for (int i = 0; i < 4; ++i) {
    double xy[4], zz[2];
    const int lxy = sum_of_squares(ex[i][0], ex[i][1], xy);
    two_product(ex[i][2], ex[i][2], zz[1], zz[0]);
    llift[i] = expansion_sum(xy, lxy, zz, 2, lift[i]);
  }
  // terms: +dlift·abc, −clift·dab, +blift·cda, −alift·bcd (each up to 288 components)
  double term[288], scratch[576], acc1[1152], acc2[1152];
  int lacc = 0;
  const double* minors[4] = {abc, dab, cda, bcd};
  const int lminors[4] = {labc, ldab, lcda, lbcd};
  const int lift_of[4] = {3, 2, 1, 0};
  const double sgn[4] = {1.0, -1.0, 1.0, -1.0};
  for (int k = 0; k < 4; ++k) {
    double* lf = lift[lift_of[k]];
    int lt = expansion_product(minors[k], lminors[k], lf, llift[lift_of[k]], term, scratch);
    for (int i = 0; i < lt; ++i) term[i] *= sgn[k];
    if (k == 0) {
      for (int i = 0; i < lt; ++i) acc1[i] = term[i];
      lacc = lt;
    } else {
      for (int i = 0; i < lacc; ++i) acc2[i] = acc1[i];
      lacc = expansion_sum(acc2, lacc, term, lt, acc1);
    }
  }
  return expansion_sign(acc1, lacc);
}

__attribute__((noinline, cold)) int insphere_slow(const double* a, const double* b, const double* c, const double* d, const double* e) {
  const double* const p[5] = {a, b, c, d, e};
  if (!all_in_safe_range(p, 3)) return insphere_integer(a, b, c, d, e);
  double ex[4][3];
  bool tails_zero = true;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      double t;
      two_diff(p[i][k], e[k], ex[i][k], t);
      tails_zero &= (t == 0.0);
    }
  if (tails_zero) return insphere_diff_exact(ex);
  return insphere_integer(a, b, c, d, e);
}

bool finite_points(const double* const* p, int n, int dim) {
  bool ok = true;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < dim; ++k) ok &= std::isfinite(p[i][k]);
  return ok;
}

// -----------------------------------------------------------------------------------------------
// Scalar predicate bodies (L2 filter, then the slow layers), without the environment check: the
// public functions check MXCSR first, FpEnvironmentScope's members rely on the scope instead.

__attribute__((always_inline)) inline int orient2d_body(const double* a, const double* b, const double* c) {
  const double detleft = (a[0] - c[0]) * (b[1] - c[1]);
  const double detright = (a[1] - c[1]) * (b[0] - c[0]);
  const double det = detleft - detright;
  const double permanent = std::fabs(detleft) + std::fabs(detright);
  const double abs_det = std::fabs(det);
  if ((abs_det > kO2ErrA * permanent) & (abs_det >= 0x1p-900) & (permanent < kPermanentMax)) return sign_of(det);
  return orient2d_slow(a, b, c, permanent);
}

__attribute__((always_inline)) inline int orient3d_body(const double* a, const double* b, const double* c, const double* d) {
#if defined(__SSE2__)
  // Stage A with the x,y columns in SSE2 pairs: the same products, minors, sums and evaluation order
  // as orient3d_stage_a (det = (adz·m1 + bdz·m2) + cdz·m3), so Shewchuk's bound applies unchanged;
  // only the independent operations are paired. -ffp-contract=off keeps mul and add separate.
  const __m128d dxy = _mm_loadu_pd(d);
  const __m128d A = _mm_sub_pd(_mm_loadu_pd(a), dxy);  // (adx, ady)
  const __m128d B = _mm_sub_pd(_mm_loadu_pd(b), dxy);  // (bdx, bdy)
  const __m128d C = _mm_sub_pd(_mm_loadu_pd(c), dxy);  // (cdx, cdy)
  const __m128d Z = _mm_sub_pd(_mm_set_pd(b[2], a[2]), _mm_set1_pd(d[2]));  // (adz, bdz)
  const double cdz = c[2] - d[2];
  const __m128d P1 = _mm_mul_pd(B, _mm_shuffle_pd(C, C, 1));  // (bdx·cdy, bdy·cdx)
  const __m128d P2 = _mm_mul_pd(C, _mm_shuffle_pd(A, A, 1));  // (cdx·ady, cdy·adx)
  const __m128d P3 = _mm_mul_pd(A, _mm_shuffle_pd(B, B, 1));  // (adx·bdy, ady·bdx)
  const __m128d L = _mm_unpacklo_pd(P1, P2), H = _mm_unpackhi_pd(P1, P2);
  const __m128d M = _mm_sub_pd(L, H);  // (m1, m2)
  const double p3lo = _mm_cvtsd_f64(P3), p3hi = _mm_cvtsd_f64(_mm_unpackhi_pd(P3, P3));
  const __m128d T = _mm_mul_pd(Z, M);  // (adz·m1, bdz·m2)
  const double det = (_mm_cvtsd_f64(T) + _mm_cvtsd_f64(_mm_unpackhi_pd(T, T))) + cdz * (p3lo - p3hi);
  const __m128d abs_mask = _mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffffLL));
  const __m128d Za = _mm_and_pd(Z, abs_mask);
  const __m128d U = _mm_mul_pd(_mm_add_pd(_mm_and_pd(L, abs_mask), _mm_and_pd(H, abs_mask)), Za);
  const double cz = std::fabs(cdz);
  const double permanent =
      (_mm_cvtsd_f64(U) + _mm_cvtsd_f64(_mm_unpackhi_pd(U, U))) + (std::fabs(p3lo) + std::fabs(p3hi)) * cz;
  const double zsum = (_mm_cvtsd_f64(Za) + _mm_cvtsd_f64(_mm_unpackhi_pd(Za, Za))) + cz;
  const double abs_det = std::fabs(det);
  if ((abs_det > kO3ErrA * permanent) & (abs_det >= 0x1p-590) & (permanent < kPermanentMax) & (zsum <= 0x1p400))
    return sign_of(det);
  return orient3d_slow(a, b, c, d, permanent);
#else
  const double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  const double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  const double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  double permanent;
  const int s = orient3d_stage_a(adx, ady, adz, bdx, bdy, bdz, cdx, cdy, cdz, &permanent);
  if (s != 0) return s;
  return orient3d_slow(a, b, c, d, permanent);
#endif
}

__attribute__((always_inline)) inline int incircle_body(const double* a, const double* b, const double* c, const double* d) {
  const double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
  const double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy, alift = adx * adx + ady * ady;
  const double cdxady = cdx * ady, adxcdy = adx * cdy, blift = bdx * bdx + bdy * bdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady, clift = cdx * cdx + cdy * cdy;
  const double det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
  const double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * alift +
                           (std::fabs(cdxady) + std::fabs(adxcdy)) * blift +
                           (std::fabs(adxbdy) + std::fabs(bdxady)) * clift;
  const double abs_det = std::fabs(det);
  if ((abs_det > kIcErrA * permanent) & (abs_det >= 0x1p-590) & (permanent < kPermanentMax) &
      ((alift + blift + clift) <= 0x1p400))
    return sign_of(det);
  return incircle_slow(a, b, c, d);
}

__attribute__((always_inline)) inline int insphere_body(const double* a, const double* b, const double* c, const double* d, const double* e) {
  const double aex = a[0] - e[0], bex = b[0] - e[0], cex = c[0] - e[0], dex = d[0] - e[0];
  const double aey = a[1] - e[1], bey = b[1] - e[1], cey = c[1] - e[1], dey = d[1] - e[1];
  const double aez = a[2] - e[2], bez = b[2] - e[2], cez = c[2] - e[2], dez = d[2] - e[2];
  const double aexbey = aex * bey, bexaey = bex * aey, ab = aexbey - bexaey;
  const double bexcey = bex * cey, cexbey = cex * bey, bc = bexcey - cexbey;
  const double cexdey = cex * dey, dexcey = dex * cey, cd = cexdey - dexcey;
  const double dexaey = dex * aey, aexdey = aex * dey, da = dexaey - aexdey;
  const double aexcey = aex * cey, cexaey = cex * aey, ac = aexcey - cexaey;
  const double bexdey = bex * dey, dexbey = dex * bey, bd = bexdey - dexbey;
  const double abc = aez * bc - bez * ac + cez * ab;
  const double bcd = bez * cd - cez * bd + dez * bc;
  const double cda = cez * da + dez * ac + aez * cd;
  const double dab = dez * ab + aez * bd + bez * da;
  const double alift = aex * aex + aey * aey + aez * aez;
  const double blift = bex * bex + bey * bey + bez * bez;
  const double clift = cex * cex + cey * cey + cez * cez;
  const double dlift = dex * dex + dey * dey + dez * dez;
  const double det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
  const double aezp = std::fabs(aez), bezp = std::fabs(bez), cezp = std::fabs(cez), dezp = std::fabs(dez);
  const double aexbeyp = std::fabs(aexbey), bexaeyp = std::fabs(bexaey), bexceyp = std::fabs(bexcey);
  const double cexbeyp = std::fabs(cexbey), cexdeyp = std::fabs(cexdey), dexceyp = std::fabs(dexcey);
  const double dexaeyp = std::fabs(dexaey), aexdeyp = std::fabs(aexdey), aexceyp = std::fabs(aexcey);
  const double cexaeyp = std::fabs(cexaey), bexdeyp = std::fabs(bexdey), dexbeyp = std::fabs(dexbey);
  const double permanent =
      ((cexdeyp + dexceyp) * bezp + (dexbeyp + bexdeyp) * cezp + (bexceyp + cexbeyp) * dezp) * alift +
      ((dexaeyp + aexdeyp) * cezp + (aexceyp + cexaeyp) * dezp + (cexdeyp + dexceyp) * aezp) * blift +
      ((aexbeyp + bexaeyp) * dezp + (bexdeyp + dexbeyp) * aezp + (dexaeyp + aexdeyp) * bezp) * clift +
      ((bexceyp + cexbeyp) * aezp + (cexaeyp + aexceyp) * bezp + (aexbeyp + bexaeyp) * cezp) * dlift;
  const double abs_det = std::fabs(det);
  if ((abs_det > kIsErrA * permanent) & (abs_det >= 0x1p-580) & (permanent < kPermanentMax) &
      ((alift + blift + clift + dlift) <= 0x1p200))
    return sign_of(det);
  return insphere_slow(a, b, c, d, e);
}

}  // namespace

// -----------------------------------------------------------------------------------------------
// Public scalar predicates: one MXCSR check per call (fp_env.hpp), then the body. orient3d is in
// orient3d.cpp (a filter that is valid in every environment comes first).

int orient2d(const double* a, const double* b, const double* c) {
  VOLMAP_REQUIRE_DEFAULT_FP_ENV(orient2d_body(a, b, c));
  return orient2d_body(a, b, c);
}
int incircle(const double* a, const double* b, const double* c, const double* d) {
  VOLMAP_REQUIRE_DEFAULT_FP_ENV(incircle_body(a, b, c, d));
  return incircle_body(a, b, c, d);
}
int insphere(const double* a, const double* b, const double* c, const double* d, const double* e) {
  VOLMAP_REQUIRE_DEFAULT_FP_ENV(insphere_body(a, b, c, d, e));
  return insphere_body(a, b, c, d, e);
}

// -----------------------------------------------------------------------------------------------
// FpEnvironmentScope: one check for a whole loop; the members are the bodies without a check.

FpEnvironmentScope::FpEnvironmentScope() noexcept {
#ifdef VOLMAP_PREDICATES_HAVE_MXCSR
  saved_ = _mm_getcsr();
  switched_ = (saved_ & kNonDefaultFpBits) != 0u;
  if (switched_) _mm_setcsr(saved_ & ~kNonDefaultFpBits);
#endif
}
FpEnvironmentScope::~FpEnvironmentScope() {
#ifdef VOLMAP_PREDICATES_HAVE_MXCSR
  // The caller's control bits; exception flags raised inside the scope (bits 0-5) stay raised.
  if (switched_) _mm_setcsr(saved_ | (_mm_getcsr() & 0x3Fu));
#endif
}
int FpEnvironmentScope::orient2d(const double* a, const double* b, const double* c) const {
  return orient2d_body(a, b, c);
}
int FpEnvironmentScope::orient3d(const double* a, const double* b, const double* c, const double* d) const {
  return volmap::orient3d(a, b, c, d);  // its fast path needs no check (orient3d.cpp)
}
int FpEnvironmentScope::incircle(const double* a, const double* b, const double* c, const double* d) const {
  return incircle_body(a, b, c, d);
}
int FpEnvironmentScope::insphere(const double* a, const double* b, const double* c, const double* d,
                                 const double* e) const {
  return insphere_body(a, b, c, d, e);
}

int orient2d_checked(const double* a, const double* b, const double* c) {
  const double* p[3] = {a, b, c};
  if (!finite_points(p, 3, 2)) throw NonFiniteInput("orient2d: non-finite input coordinate");
  return orient2d(a, b, c);
}
int orient3d_checked(const double* a, const double* b, const double* c, const double* d) {
  const double* p[4] = {a, b, c, d};
  if (!finite_points(p, 4, 3)) throw NonFiniteInput("orient3d: non-finite input coordinate");
  return orient3d(a, b, c, d);
}
int incircle_checked(const double* a, const double* b, const double* c, const double* d) {
  const double* p[4] = {a, b, c, d};
  if (!finite_points(p, 4, 2)) throw NonFiniteInput("incircle: non-finite input coordinate");
  return incircle(a, b, c, d);
}
int insphere_checked(const double* a, const double* b, const double* c, const double* d, const double* e) {
  const double* p[5] = {a, b, c, d, e};
  if (!finite_points(p, 5, 3)) throw NonFiniteInput("insphere: non-finite input coordinate");
  return insphere(a, b, c, d, e);
}

// -----------------------------------------------------------------------------------------------
// Entry points for orient3d.cpp and orient3d_tets.cpp (layers.hpp).
namespace detail {

int orient3d_guarded(const double* a, const double* b, const double* c, const double* d) {
  VOLMAP_REQUIRE_DEFAULT_FP_ENV(orient3d_body(a, b, c, d));
  return orient3d_body(a, b, c, d);
}

// Per-tet work once L1 did not decide, on a mesh known to be safe.
int orient3d_safe_after_static(const double* a, const double* b, const double* c, const double* d) {
  const double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  const double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  const double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  double permanent;
  const int s = orient3d_stage_a(adx, ady, adz, bdx, bdy, bdz, cdx, cdy, cdz, &permanent);
  if (s != 0) return s;
  if ((adx == 0.0 && bdx == 0.0 && cdx == 0.0) || (ady == 0.0 && bdy == 0.0 && cdy == 0.0) ||
      (adz == 0.0 && bdz == 0.0 && cdz == 0.0))
    return 0;
  return orient3d_exact_tail(a, b, c, d, permanent);
}


}  // namespace detail

}  // namespace volmap
