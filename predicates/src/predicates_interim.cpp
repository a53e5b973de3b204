// INTERIM exact predicates: every sign computed in GMP rationals (exact, slow). This file exists so the
// skeleton links; the layered filtered implementation replaces it (issue 2).
#include <volmap/predicates.hpp>

#include <cmath>

namespace volmap {
namespace {
int sgn(const Rational& r) { return r > 0 ? 1 : (r < 0 ? -1 : 0); }
Rational R(double x) { return Rational(x); }
bool finite(const double* p, int n) {
  for (int i = 0; i < n; ++i) if (!std::isfinite(p[i])) return false;
  return true;
}
int o2(const Rational* a, const Rational* b, const Rational* c) {
  return sgn((a[0] - c[0]) * (b[1] - c[1]) - (a[1] - c[1]) * (b[0] - c[0]));
}
int o3(const Rational* a, const Rational* b, const Rational* c, const Rational* d) {
  Rational adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  Rational bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  Rational cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  return sgn(adx * (bdy * cdz - bdz * cdy) + bdx * (cdy * adz - cdz * ady) + cdx * (ady * bdz - adz * bdy));
}
int ic(const Rational* a, const Rational* b, const Rational* c, const Rational* d) {
  Rational adx = a[0] - d[0], ady = a[1] - d[1], bdx = b[0] - d[0], bdy = b[1] - d[1];
  Rational cdx = c[0] - d[0], cdy = c[1] - d[1];
  Rational al = adx * adx + ady * ady, bl = bdx * bdx + bdy * bdy, cl = cdx * cdx + cdy * cdy;
  return sgn(al * (bdx * cdy - cdx * bdy) + bl * (cdx * ady - adx * cdy) + cl * (adx * bdy - bdx * ady));
}
int is(const Rational* a, const Rational* b, const Rational* c, const Rational* d, const Rational* e) {
  Rational ex[4][4];
  const Rational* p[4] = {a, b, c, d};
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 3; ++k) ex[i][k] = p[i][k] - e[k];
    ex[i][3] = ex[i][0] * ex[i][0] + ex[i][1] * ex[i][1] + ex[i][2] * ex[i][2];
  }
  // 4x4 determinant by cofactor expansion along the last column.
  auto det3 = [&](int r0, int r1, int r2) {
    return ex[r0][0] * (ex[r1][1] * ex[r2][2] - ex[r1][2] * ex[r2][1]) -
           ex[r0][1] * (ex[r1][0] * ex[r2][2] - ex[r1][2] * ex[r2][0]) +
           ex[r0][2] * (ex[r1][0] * ex[r2][1] - ex[r1][1] * ex[r2][0]);
  };
  Rational det = -ex[0][3] * det3(1, 2, 3) + ex[1][3] * det3(0, 2, 3) - ex[2][3] * det3(0, 1, 3) +
                 ex[3][3] * det3(0, 1, 2);
  // Shewchuk: insphere > 0 when e inside sphere of positively oriented a,b,c,d.
  return -sgn(det);
}
template <int N>
struct Pt {
  Rational v[N];
  explicit Pt(const double* p) { for (int i = 0; i < N; ++i) v[i] = R(p[i]); }
};
}  // namespace

int orient2d(const double* a, const double* b, const double* c) { return o2(Pt<2>(a).v, Pt<2>(b).v, Pt<2>(c).v); }
int orient3d(const double* a, const double* b, const double* c, const double* d) {
  return o3(Pt<3>(a).v, Pt<3>(b).v, Pt<3>(c).v, Pt<3>(d).v);
}
int incircle(const double* a, const double* b, const double* c, const double* d) {
  return ic(Pt<2>(a).v, Pt<2>(b).v, Pt<2>(c).v, Pt<2>(d).v);
}
int insphere(const double* a, const double* b, const double* c, const double* d, const double* e) {
  return is(Pt<3>(a).v, Pt<3>(b).v, Pt<3>(c).v, Pt<3>(d).v, Pt<3>(e).v);
}
int orient2d_checked(const double* a, const double* b, const double* c) {
  if (!finite(a, 2) || !finite(b, 2) || !finite(c, 2)) throw NonFiniteInput("orient2d: non-finite input");
  return orient2d(a, b, c);
}
int orient3d_checked(const double* a, const double* b, const double* c, const double* d) {
  if (!finite(a, 3) || !finite(b, 3) || !finite(c, 3) || !finite(d, 3)) throw NonFiniteInput("orient3d: non-finite input");
  return orient3d(a, b, c, d);
}
int incircle_checked(const double* a, const double* b, const double* c, const double* d) {
  if (!finite(a, 2) || !finite(b, 2) || !finite(c, 2) || !finite(d, 2)) throw NonFiniteInput("incircle: non-finite input");
  return incircle(a, b, c, d);
}
int insphere_checked(const double* a, const double* b, const double* c, const double* d, const double* e) {
  if (!finite(a, 3) || !finite(b, 3) || !finite(c, 3) || !finite(d, 3) || !finite(e, 3))
    throw NonFiniteInput("insphere: non-finite input");
  return insphere(a, b, c, d, e);
}
int orient2d(const Rational* a, const Rational* b, const Rational* c) { return o2(a, b, c); }
int orient3d(const Rational* a, const Rational* b, const Rational* c, const Rational* d) { return o3(a, b, c, d); }
int incircle(const Rational* a, const Rational* b, const Rational* c, const Rational* d) { return ic(a, b, c, d); }
int insphere(const Rational* a, const Rational* b, const Rational* c, const Rational* d, const Rational* e) {
  return is(a, b, c, d, e);
}

template <class T>
static TetSignCounts batch(const T* xyz, std::size_t nv, const std::uint32_t* tets, std::size_t nt, std::int8_t* signs,
                           bool check_finite) {
  TetSignCounts r;
  if (check_finite) {
    for (std::size_t i = 0; i < 3 * nv; ++i)
      if (!std::isfinite(static_cast<double>(xyz[i]))) { r.ok = false; r.error = "non-finite coordinate"; return r; }
  }
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint32_t* v = tets + 4 * t;
    if (v[0] >= nv || v[1] >= nv || v[2] >= nv || v[3] >= nv) { r = TetSignCounts{}; r.ok = false; r.error = "vertex id out of range"; return r; }
    int s = orient3d(xyz + 3 * v[0], xyz + 3 * v[1], xyz + 3 * v[2], xyz + 3 * v[3]);
    if (signs) signs[t] = static_cast<std::int8_t>(s);
    (s > 0 ? r.positive : s < 0 ? r.negative : r.zero) += 1;
  }
  return r;
}
TetSignCounts orient3d_tets(const double* xyz, std::size_t nv, const std::uint32_t* tets, std::size_t nt, std::int8_t* signs) {
  return batch(xyz, nv, tets, nt, signs, true);
}
TetSignCounts orient3d_tets(const Rational* xyz, std::size_t nv, const std::uint32_t* tets, std::size_t nt, std::int8_t* signs) {
  return batch(xyz, nv, tets, nt, signs, false);
}

}  // namespace volmap
