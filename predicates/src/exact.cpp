// exact.cpp — layer L4 of the predicates (see exact.hpp): exact integer evaluation.
//
// Doubles: every finite double is m·2^e with an odd integer m (|m| < 2^53). With emin the smallest e
// of the call, each coordinate becomes the integer m·2^(e−emin); the predicate is a homogeneous
// polynomial of degree k in the translated coordinates, so its sign is unchanged. With B the largest
// bit length, differences need B+1 bits and the determinant at most k(B+1) + log2(#terms) bits
// (predicates.md §4: N ≥ 3(B+1)+3 for orient3d); we pick the smallest fixed-width cpp_int that fits
// (no allocation) and fall back to the arbitrary-precision cpp_int for extreme exponent spreads
// (e.g. 2^-1074 next to 2^1000).
// Rationals: point i = (X_i, Y_i, Z_i)/W_i with W_i > 0 (canonical mpq). orient = det[p_i 1] and the
// lifted predicates are det[p_i |p_i|² 1]; multiplying row i by W_i (or W_i²) > 0 keeps the sign, so
// every rational predicate is the sign of an integer determinant (Bareiss, fraction-free), no gcd.
// orient3d on rationals (scalar and batch) first tries a double prefilter with the conversion error
// folded into the bound (see orient3d_rational_filter).
#include "exact.hpp"
#include "fp_env.hpp"

#include <boost/multiprecision/cpp_int.hpp>
#include <boost/multiprecision/gmp.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace volmap::detail {
namespace {

namespace mp = boost::multiprecision;
template <unsigned Bits>
using FixedInt = mp::number<mp::cpp_int_backend<Bits, Bits, mp::signed_magnitude, mp::unchecked, void>, mp::et_off>;
using BigInt = mp::number<mp::cpp_int_backend<>, mp::et_off>;
using Mpz = mp::number<mp::gmp_int, mp::et_off>;

// value = (negative ? -1 : 1) * magnitude * 2^exponent, magnitude odd (or 0).
struct Dyadic {
  std::uint64_t magnitude = 0;
  int exponent = 0;
  bool negative = false;
};

Dyadic decompose(double x) {
  Dyadic d;
  if (x == 0.0) return d;
  int e = 0;
  const double f = std::frexp(std::fabs(x), &e);  // f in [0.5, 1), exact for subnormals too
  std::uint64_t m = static_cast<std::uint64_t>(std::ldexp(f, 53));
  e -= 53;
  const int tz = __builtin_ctzll(m);
  d.magnitude = m >> tz;
  d.exponent = e + tz;
  d.negative = x < 0.0;
  return d;
}

int bit_length(std::uint64_t m) { return m == 0 ? 0 : 64 - __builtin_clzll(m); }

template <class T>
int sgn(const T& v) {
  return v > 0 ? 1 : (v < 0 ? -1 : 0);
}

// Kernels on translated integer coordinates, same expression shapes as Shewchuk's predicates.
template <class T>
int orient2d_kernel(const T* p) {  // a = p[0..1], b = p[2..3], c = p[4..5]
  const T acx = p[0] - p[4], acy = p[1] - p[5], bcx = p[2] - p[4], bcy = p[3] - p[5];
  return sgn(T(acx * bcy - acy * bcx));
}
template <class T>
int orient3d_kernel(const T* p) {
  const T adx = p[0] - p[9], ady = p[1] - p[10], adz = p[2] - p[11];
  const T bdx = p[3] - p[9], bdy = p[4] - p[10], bdz = p[5] - p[11];
  const T cdx = p[6] - p[9], cdy = p[7] - p[10], cdz = p[8] - p[11];
  const T det = adz * T(bdx * cdy - cdx * bdy) + bdz * T(cdx * ady - adx * cdy) + cdz * T(adx * bdy - bdx * ady);
  return sgn(det);
}
template <class T>
int incircle_kernel(const T* p) {
  const T adx = p[0] - p[6], ady = p[1] - p[7], bdx = p[2] - p[6], bdy = p[3] - p[7];
  const T cdx = p[4] - p[6], cdy = p[5] - p[7];
  const T alift = adx * adx + ady * ady, blift = bdx * bdx + bdy * bdy, clift = cdx * cdx + cdy * cdy;
  const T det = alift * T(bdx * cdy - cdx * bdy) + blift * T(cdx * ady - adx * cdy) + clift * T(adx * bdy - bdx * ady);
  return sgn(det);
}
template <class T>
int insphere_kernel(const T* p) {
  const T aex = p[0] - p[12], aey = p[1] - p[13], aez = p[2] - p[14];
  const T bex = p[3] - p[12], bey = p[4] - p[13], bez = p[5] - p[14];
  const T cex = p[6] - p[12], cey = p[7] - p[13], cez = p[8] - p[14];
  const T dex = p[9] - p[12], dey = p[10] - p[13], dez = p[11] - p[14];
  const T ab = aex * bey - bex * aey, bc = bex * cey - cex * bey, cd = cex * dey - dex * cey;
  const T da = dex * aey - aex * dey, ac = aex * cey - cex * aey, bd = bex * dey - dex * bey;
  const T abc = aez * bc - bez * ac + cez * ab;
  const T bcd = bez * cd - cez * bd + dez * bc;
  const T cda = cez * da + dez * ac + aez * cd;
  const T dab = dez * ab + aez * bd + bez * da;
  const T alift = aex * aex + aey * aey + aez * aez, blift = bex * bex + bey * bey + bez * bez;
  const T clift = cex * cex + cey * cey + cez * cez, dlift = dex * dex + dey * dey + dez * dez;
  const T det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
  return sgn(det);
}

enum class Kind { Orient2d, Orient3d, Incircle, Insphere };

template <class T>
int evaluate(Kind kind, const Dyadic* v, int n, int emin) {
  T c[15];
  for (int i = 0; i < n; ++i) {
    c[i] = T(v[i].magnitude);
    if (v[i].magnitude != 0) c[i] <<= static_cast<unsigned>(v[i].exponent - emin);
    if (v[i].negative) c[i] = -c[i];
  }
  switch (kind) {
    case Kind::Orient2d: return orient2d_kernel(c);
    case Kind::Orient3d: return orient3d_kernel(c);
    case Kind::Incircle: return incircle_kernel(c);
    case Kind::Insphere: return insphere_kernel(c);
  }
  return 0;
}

// points: `count` pointers to `dim` doubles each.
int integer_sign(Kind kind, const double* const* points, int count, int dim, int degree) {
  Dyadic v[15];
  int n = 0;
  int emin = 0, emax_bits = 0;
  bool any = false;
  for (int i = 0; i < count; ++i)
    for (int k = 0; k < dim; ++k, ++n) {
      v[n] = decompose(points[i][k]);
      if (v[n].magnitude == 0) continue;
      if (!any || v[n].exponent < emin) emin = v[n].exponent;
      any = true;
    }
  if (!any) return 0;
  for (int i = 0; i < n; ++i)
    if (v[i].magnitude != 0) emax_bits = std::max(emax_bits, bit_length(v[i].magnitude) + v[i].exponent - emin);
  // |difference| < 2^(B+1); products of `degree` differences and lifts, summed over <= 72 terms,
  // plus one sign bit: degree*(B+1) + 8 bits suffice for every kernel above (insphere: 72 terms).
  const int needed = degree * (emax_bits + 1) + 8;
  if (needed <= 128) return evaluate<FixedInt<128>>(kind, v, n, emin);
  if (needed <= 256) return evaluate<FixedInt<256>>(kind, v, n, emin);
  if (needed <= 512) return evaluate<FixedInt<512>>(kind, v, n, emin);
  if (needed <= 1024) return evaluate<FixedInt<1024>>(kind, v, n, emin);
  return evaluate<BigInt>(kind, v, n, emin);
}

// Sign of det(m) for an n×n integer matrix (Bareiss fraction-free elimination with row pivoting).
template <int N>
int bareiss_sign(Mpz (&m)[N][N]) {
  int sign = 1;
  Mpz prev = 1;
  for (int k = 0; k < N - 1; ++k) {
    if (m[k][k] == 0) {
      int r = k + 1;
      while (r < N && m[r][k] == 0) ++r;
      if (r == N) return 0;
      for (int j = 0; j < N; ++j) std::swap(m[k][j], m[r][j]);
      sign = -sign;
    }
    for (int i = k + 1; i < N; ++i) {
      for (int j = k + 1; j < N; ++j) {
        m[i][j] = m[i][j] * m[k][k] - m[i][k] * m[k][j];
        if (k > 0) m[i][j] /= prev;  // exact by Sylvester's identity
      }
    }
    prev = m[k][k];
  }
  return sign * sgn(m[N - 1][N - 1]);
}

// Homogeneous integer coordinates of a rational point: (X_1..X_dim, W) with p_k = X_k / W, W > 0.
template <int Dim>
void homogenize(const Rational* p, Mpz* out) {
  Mpz w = 1;
  Mpz den[Dim];
  for (int k = 0; k < Dim; ++k) {
    den[k] = mp::denominator(p[k]);
    w *= den[k];
  }
  for (int k = 0; k < Dim; ++k) out[k] = mp::numerator(p[k]) * (w / den[k]);
  out[Dim] = w;
}

// Rows for orient (X.., W) and for the lifted predicates (X·W.., |X|², W²).
template <int Dim, int N>
void orient_row(const Mpz* h, Mpz (&row)[N]) {
  for (int k = 0; k <= Dim; ++k) row[k] = h[k];
}
template <int Dim, int N>
void lifted_row(const Mpz* h, Mpz (&row)[N]) {
  Mpz lift = 0;
  for (int k = 0; k < Dim; ++k) {
    row[k] = h[k] * h[Dim];
    lift += h[k] * h[k];
  }
  row[Dim] = lift;
  row[Dim + 1] = h[Dim] * h[Dim];
}

}  // namespace

int orient2d_integer(const double* a, const double* b, const double* c) {
  const double* p[3] = {a, b, c};
  return integer_sign(Kind::Orient2d, p, 3, 2, 2);
}
int orient3d_integer(const double* a, const double* b, const double* c, const double* d) {
  const double* p[4] = {a, b, c, d};
  return integer_sign(Kind::Orient3d, p, 4, 3, 3);
}
int incircle_integer(const double* a, const double* b, const double* c, const double* d) {
  const double* p[4] = {a, b, c, d};
  return integer_sign(Kind::Incircle, p, 4, 2, 4);
}
int insphere_integer(const double* a, const double* b, const double* c, const double* d, const double* e) {
  const double* p[5] = {a, b, c, d, e};
  return integer_sign(Kind::Insphere, p, 5, 3, 5);
}

// ---- interval-style prefilter for rational orient3d (our derivation, see predicates.md §2 L4) ------
// Each rational q is replaced once by d = mpq_get_d(q) (truncation): |q − d| < ulp(d) ≤ 2ε|d| when
// |d| is normal; we require every nonzero |d| in [2^-142, 2^201] (then no product below under- or
// overflows) and d = 0 only for q = 0. With S = |ã_k| + |d̃_k| per translated entry, the true
// difference differs from fl(ã − d̃) by ≤ 3εS, |fl(ã − d̃)| ≤ (1+ε)S, so the exact determinant differs
// from the stage-A evaluation on the doubles by ≤ 9ε·perm(S) (input error) + 7ε·perm(S) (rounding)
// up to O(ε²) terms; 20ε·fl(perm(S)) bounds both with margin for the rounding of perm(S) itself.
bool rational_to_safe_double(const Rational& q, double& d) {
  d = mpq_get_d(q.backend().data());
  const double ad = std::fabs(d);
  if (ad == 0.0) return mpq_sgn(q.backend().data()) == 0;
  return ad >= 0x1p-142 && ad <= 0x1p201;
}

int orient3d_rational_filter(const double* a, const double* b, const double* c, const double* d) {
  const double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  const double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  const double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  const double det = adz * (bdx * cdy - cdx * bdy) + bdz * (cdx * ady - adx * cdy) + cdz * (adx * bdy - bdx * ady);
  const double dx = std::fabs(d[0]), dy = std::fabs(d[1]), dz = std::fabs(d[2]);
  const double sax = std::fabs(a[0]) + dx, say = std::fabs(a[1]) + dy, saz = std::fabs(a[2]) + dz;
  const double sbx = std::fabs(b[0]) + dx, sby = std::fabs(b[1]) + dy, sbz = std::fabs(b[2]) + dz;
  const double scx = std::fabs(c[0]) + dx, scy = std::fabs(c[1]) + dy, scz = std::fabs(c[2]) + dz;
  const double permanent = (sbx * scy + scx * sby) * saz + (scx * say + sax * scy) * sbz + (sax * sby + sbx * say) * scz;
  constexpr double kBound = 20.0 * 0x1p-53;
  const double bound = kBound * permanent;
  return (det > bound) - (det < -bound);
}

}  // namespace volmap::detail

namespace volmap {
using detail::Mpz;

int orient2d(const Rational* a, const Rational* b, const Rational* c) {
  VOLMAP_REQUIRE_DEFAULT_FP_ENV(orient2d(a, b, c));
  const Rational* p[3] = {a, b, c};
  Mpz m[3][3];
  for (int i = 0; i < 3; ++i) {
    Mpz h[3];
    detail::homogenize<2>(p[i], h);
    detail::orient_row<2>(h, m[i]);
  }
  return detail::bareiss_sign(m);
}
int orient3d(const Rational* a, const Rational* b, const Rational* c, const Rational* d) {
  VOLMAP_REQUIRE_DEFAULT_FP_ENV(orient3d(a, b, c, d));
  const Rational* p[4] = {a, b, c, d};
  double approx[4][3];
  bool safe = true;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) safe &= detail::rational_to_safe_double(p[i][k], approx[i][k]);
  if (safe) {
    const int s = detail::orient3d_rational_filter(approx[0], approx[1], approx[2], approx[3]);
    if (s != 0) return s;
  }
  for (int k = 0; k < 3; ++k)  // zero-column shortcut: a whole translated column is zero
    if (a[k] == d[k] && b[k] == d[k] && c[k] == d[k]) return 0;
  Mpz m[4][4];
  for (int i = 0; i < 4; ++i) {
    Mpz h[4];
    detail::homogenize<3>(p[i], h);
    detail::orient_row<3>(h, m[i]);
  }
  return detail::bareiss_sign(m);
}
int incircle(const Rational* a, const Rational* b, const Rational* c, const Rational* d) {
  VOLMAP_REQUIRE_DEFAULT_FP_ENV(incircle(a, b, c, d));
  const Rational* p[4] = {a, b, c, d};
  Mpz m[4][4];
  for (int i = 0; i < 4; ++i) {
    Mpz h[3];
    detail::homogenize<2>(p[i], h);
    detail::lifted_row<2>(h, m[i]);
  }
  return detail::bareiss_sign(m);
}
int insphere(const Rational* a, const Rational* b, const Rational* c, const Rational* d, const Rational* e) {
  VOLMAP_REQUIRE_DEFAULT_FP_ENV(insphere(a, b, c, d, e));
  const Rational* p[5] = {a, b, c, d, e};
  Mpz m[5][5];
  for (int i = 0; i < 5; ++i) {
    Mpz h[4];
    detail::homogenize<3>(p[i], h);
    detail::lifted_row<3>(h, m[i]);
  }
  return detail::bareiss_sign(m);
}

TetSignCounts orient3d_tets(const Rational* xyz, std::size_t num_vertices, const std::uint32_t* tets,
                            std::size_t num_tets, std::int8_t* signs) {
  TetSignCounts r;
  for (std::size_t t = 0; t < 4 * num_tets; ++t)
    if (tets[t] >= num_vertices) {
      r.ok = false;
      r.error = "vertex id out of range";
      return r;
    }
  // Double approximations once per vertex (two allocations, outside the loop); per tet the filter
  // decides unless a vertex is out of the safe range or the tet is (nearly) degenerate, then the exact
  // homogeneous integer determinant runs.
  std::vector<double> approx(3 * num_vertices);
  std::vector<unsigned char> vertex_safe(num_vertices);
  for (std::size_t v = 0; v < num_vertices; ++v) {
    bool ok = true;
    for (int k = 0; k < 3; ++k) ok &= detail::rational_to_safe_double(xyz[3 * v + k], approx[3 * v + k]);
    vertex_safe[v] = ok;
  }
  for (std::size_t t = 0; t < num_tets; ++t) {
    const std::uint32_t* v = tets + 4 * t;
    int s = 0;
    if (vertex_safe[v[0]] & vertex_safe[v[1]] & vertex_safe[v[2]] & vertex_safe[v[3]])
      s = detail::orient3d_rational_filter(&approx[3 * v[0]], &approx[3 * v[1]], &approx[3 * v[2]], &approx[3 * v[3]]);
    if (s == 0) s = orient3d(xyz + 3 * v[0], xyz + 3 * v[1], xyz + 3 * v[2], xyz + 3 * v[3]);
    if (signs) signs[t] = static_cast<std::int8_t>(s);
    (s > 0 ? r.positive : s < 0 ? r.negative : r.zero) += 1;
  }
  return r;
}

}  // namespace volmap
