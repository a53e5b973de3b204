// oracle.hpp — independent exact oracle and hard-case generators for testing volmap predicates.
// Used by tests/predicates/test_predicates*.cpp, bench/bench_predicates.cpp and tools/volmap-predicates-selftest.cpp
// only (not installed, not part of the predicates library).
//
// The oracle never calls volmap code: every coordinate is converted exactly to a GMP rational (or a
// GMP integer when the caller knows the coordinates are integers) and the predicate is evaluated as the
// untranslated determinant by Laplace expansion:
//   orient2d = det[p_i 1] (3×3), orient3d = det[p_i 1] (4×4),
//   incircle = det[p_i |p_i|² 1] (4×4), insphere = det[p_i |p_i|² 1] (5×5),
// which equal Shewchuk's translated determinants (subtracting the last row and folding the linear part
// of the lifted column leaves the determinant unchanged).
#pragma once

#include <boost/multiprecision/gmp.hpp>
#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

namespace volmap_oracle {

namespace mp = boost::multiprecision;
using Q = mp::number<mp::gmp_rational, mp::et_off>;
using Z = mp::number<mp::gmp_int, mp::et_off>;

template <class T>
int sign(const T& v) {
  return v > 0 ? 1 : (v < 0 ? -1 : 0);
}

// Determinant of an n×n matrix (n ≤ 5) by Laplace expansion along the first row.
template <class T>
T laplace_det(const T* m, int n, int stride, const int* cols) {
  if (n == 1) return m[cols[0]];
  if (n == 2) return m[cols[0]] * m[stride + cols[1]] - m[cols[1]] * m[stride + cols[0]];
  T sum = 0;
  int sub[5];
  for (int j = 0; j < n; ++j) {
    if (m[cols[j]] == 0) continue;
    int k = 0;
    for (int i = 0; i < n; ++i)
      if (i != j) sub[k++] = cols[i];
    T minor = laplace_det(m + stride, n - 1, stride, sub);
    if (j % 2 == 0) sum += m[cols[j]] * minor;
    else sum -= m[cols[j]] * minor;
  }
  return sum;
}

// GMP's double -> rational conversion uses floating-point arithmetic, which MXCSR flush-to-zero /
// denormals-are-zero would corrupt (subnormals read as 0): the oracle converts in the default
// environment whatever the caller's is (tests/predicates/test_predicates_ftz.cpp, VOLMAP_TEST_FTZ_DAZ=1 runs).
struct DefaultFpEnvironment {
#if defined(__SSE2__)
  unsigned saved = _mm_getcsr();
  DefaultFpEnvironment() { _mm_setcsr(saved & ~0xE040u); }  // FTZ, rounding control, DAZ cleared
  ~DefaultFpEnvironment() { _mm_setcsr(saved); }
#endif
};

template <class T>
T to_exact(double x) {
  return T(x);  // exact for every finite double (integers only for Z)
}

// `lifted`: add the |p|² column. points: npts pointers to dim coordinates; matrix is npts×npts.
template <class T>
int det_sign(const double* const* points, int npts, int dim, bool lifted) {
  const DefaultFpEnvironment environment;
  T m[25];
  for (int i = 0; i < npts; ++i) {
    T lift = 0;
    int k = 0;
    for (; k < dim; ++k) {
      m[i * npts + k] = to_exact<T>(points[i][k]);
      lift += m[i * npts + k] * m[i * npts + k];
    }
    if (lifted) m[i * npts + k++] = lift;
    m[i * npts + k] = 1;
  }
  const int cols[5] = {0, 1, 2, 3, 4};
  return sign(laplace_det(m, npts, npts, cols));
}

template <class T = Q>
int orient2d(const double* a, const double* b, const double* c) {
  const double* p[3] = {a, b, c};
  return det_sign<T>(p, 3, 2, false);
}
template <class T = Q>
int orient3d(const double* a, const double* b, const double* c, const double* d) {
  const double* p[4] = {a, b, c, d};
  return det_sign<T>(p, 4, 3, false);
}
template <class T = Q>
int incircle(const double* a, const double* b, const double* c, const double* d) {
  const double* p[4] = {a, b, c, d};
  return det_sign<T>(p, 4, 2, true);
}
template <class T = Q>
int insphere(const double* a, const double* b, const double* c, const double* d, const double* e) {
  const double* p[5] = {a, b, c, d, e};
  return det_sign<T>(p, 5, 3, true);
}

// Exact tests built on the predicates: point equality, 3D collinearity ((b−a)×(c−a) = 0) and the
// sign of Σ det[a; b; c] over triangles (xyz: 3 doubles per vertex, tris: 3 ids per triangle).
inline bool points_equal(const double* p, const double* q) {
  const DefaultFpEnvironment environment;
  for (int k = 0; k < 3; ++k)
    if (std::isnan(p[k]) || Q(p[k]) != Q(q[k])) return false;
  return true;
}
// p, q in one open half-plane of the line ab: n_p = (b−a)×(p−a) and n_q = (b−a)×(q−a) parallel
// (n_p × n_q = 0) and pointing the same way (n_p · n_q > 0).
inline bool same_half_plane(const double* a, const double* b, const double* p, const double* q) {
  const DefaultFpEnvironment environment;
  Q u[3], np[3], nq[3];
  {
    Q vp[3], vq[3];
    for (int k = 0; k < 3; ++k) {
      u[k] = Q(b[k]) - Q(a[k]);
      vp[k] = Q(p[k]) - Q(a[k]);
      vq[k] = Q(q[k]) - Q(a[k]);
    }
    for (int k = 0; k < 3; ++k) {
      const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      np[k] = u[k1] * vp[k2] - u[k2] * vp[k1];
      nq[k] = u[k1] * vq[k2] - u[k2] * vq[k1];
    }
  }
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    if (np[k1] * nq[k2] != np[k2] * nq[k1]) return false;
  }
  return np[0] * nq[0] + np[1] * nq[1] + np[2] * nq[2] > 0;
}
inline bool collinear(const double* a, const double* b, const double* c) {
  const DefaultFpEnvironment environment;
  Q u[3], v[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = Q(b[k]) - Q(a[k]);
    v[k] = Q(c[k]) - Q(a[k]);
  }
  return u[1] * v[2] == u[2] * v[1] && u[2] * v[0] == u[0] * v[2] && u[0] * v[1] == u[1] * v[0];
}
inline int enclosed_volume_sign(const double* xyz, const std::uint32_t* tris, std::size_t num_tris) {
  const DefaultFpEnvironment environment;
  Q sum = 0;
  for (std::size_t t = 0; t < num_tris; ++t) {
    Q m[9];
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) m[3 * i + k] = Q(xyz[3 * std::size_t(tris[3 * t + i]) + k]);
    const int cols[3] = {0, 1, 2};
    sum += laplace_det(m, 3, 3, cols);
  }
  return sign(sum);
}

// Naive double determinants (Shewchuk's fast expressions, no filter): the "what goes wrong" baseline.
inline double naive_orient2d(const double* a, const double* b, const double* c) {
  return (a[0] - c[0]) * (b[1] - c[1]) - (a[1] - c[1]) * (b[0] - c[0]);
}
inline double naive_orient3d(const double* a, const double* b, const double* c, const double* d) {
  const double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  const double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  const double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  return adz * (bdx * cdy - cdx * bdy) + bdz * (cdx * ady - adx * cdy) + cdz * (adx * bdy - bdx * ady);
}
inline double naive_incircle(const double* a, const double* b, const double* c, const double* d) {
  const double adx = a[0] - d[0], ady = a[1] - d[1], bdx = b[0] - d[0], bdy = b[1] - d[1];
  const double cdx = c[0] - d[0], cdy = c[1] - d[1];
  return (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) + (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy) +
         (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
}
inline double naive_insphere(const double* a, const double* b, const double* c, const double* d, const double* e) {
  double m[4][4];
  const double* p[4] = {a, b, c, d};
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 3; ++k) m[i][k] = p[i][k] - e[k];
    m[i][3] = m[i][0] * m[i][0] + m[i][1] * m[i][1] + m[i][2] * m[i][2];
  }
  auto det3 = [&](int r0, int r1, int r2) {
    return m[r0][0] * (m[r1][1] * m[r2][2] - m[r1][2] * m[r2][1]) - m[r0][1] * (m[r1][0] * m[r2][2] - m[r1][2] * m[r2][0]) +
           m[r0][2] * (m[r1][0] * m[r2][1] - m[r1][1] * m[r2][0]);
  };
  return -m[0][3] * det3(1, 2, 3) + m[1][3] * det3(0, 2, 3) - m[2][3] * det3(0, 1, 3) + m[3][3] * det3(0, 1, 2);
}
inline int naive_sign(double x) { return (x > 0) - (x < 0); }

// ---- hard-case generators -------------------------------------------------------------------

struct Point2 {
  double v[2];
};
struct Point3 {
  double v[3];
};

// Kettner et al. (CGTA 2008): p = (x0 + i·u, y0 + j·u) on a 256×256 ulp grid, q, r fixed.
inline std::vector<Point2> kettner_grid(double x0, double y0, int n = 256) {
  std::vector<Point2> pts;
  pts.reserve(std::size_t(n) * n);
  const double ux = std::nextafter(x0, 2 * x0 + 1) - x0, uy = std::nextafter(y0, 2 * y0 + 1) - y0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) pts.push_back({{x0 + i * ux, y0 + j * uy}});
  return pts;
}

// 3D analogue: far-away a, b, c on the plane z = x + y (exact), d on a ulp grid around a point of it.
inline std::vector<Point3> kettner_grid_3d(int n = 64) {
  std::vector<Point3> pts;
  const double x0 = 0.5, y0 = 0.25, z0 = 0.75;
  const double u = std::ldexp(1.0, -53);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) pts.push_back({{x0 + i * 2 * u, y0 + j * u, z0 + ((i + j) % 7 - 3) * 2 * u}});
  return pts;
}

// Near-coplanar: d = fl(a + s(b−a) + t(c−a)) for random a, b, c in [-1,1]^3, s, t in [0,1].
template <class Rng>
void near_coplanar(Rng& rng, double* a, double* b, double* c, double* d) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), w(0.0, 1.0);
  for (int k = 0; k < 3; ++k) {
    a[k] = u(rng);
    b[k] = u(rng);
    c[k] = u(rng);
  }
  const double s = w(rng), t = w(rng);
  for (int k = 0; k < 3; ++k) d[k] = a[k] + s * (b[k] - a[k]) + t * (c[k] - a[k]);
}

// Near-collinear (2D): c = fl(a + s(b−a)) for random a, b in [-1,1]^2, s in [-1,1].
template <class Rng>
void near_collinear(Rng& rng, double* a, double* b, double* c) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 2; ++k) a[k] = u(rng), b[k] = u(rng);
  const double s = u(rng);
  for (int k = 0; k < 2; ++k) c[k] = a[k] + s * (b[k] - a[k]);
}

// Near-cocircular (2D): d = rounded point on the circle through rounded a, b, c (center o, radius r).
template <class Rng>
void near_cocircular(Rng& rng, double* a, double* b, double* c, double* d) {
  std::uniform_real_distribution<double> ang(0.0, 6.283185307179586), u(-1.0, 1.0), rad(0.1, 2.0);
  const double ox = u(rng), oy = u(rng), r = rad(rng);
  double* p[4] = {a, b, c, d};
  double angles[4] = {ang(rng), ang(rng), ang(rng), ang(rng)};
  std::sort(angles, angles + 3);  // a, b, c counter-clockwise
  for (int i = 0; i < 4; ++i) {
    p[i][0] = ox + r * std::cos(angles[i]);
    p[i][1] = oy + r * std::sin(angles[i]);
  }
}

// Near-cospherical (3D).
template <class Rng>
void near_cospherical(Rng& rng, double* a, double* b, double* c, double* d, double* e) {
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> u(-1.0, 1.0), rad(0.1, 2.0);
  const double o[3] = {u(rng), u(rng), u(rng)};
  const double r = rad(rng);
  double* p[5] = {a, b, c, d, e};
  for (int i = 0; i < 5; ++i) {
    double v[3] = {g(rng), g(rng), g(rng)};
    const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; ++k) p[i][k] = o[k] + r * v[k] / n;
  }
}

// Indexed Kuhn grid for the batch orient3d_tets: n³ cubes, 6 tets per cube (paths corner to opposite
// corner along the axes in every order, conforming), vertex (i,j,k) at shift + spacing·(i,j,k) with id
// i + (n+1)(j + (n+1)k). Every tet is positive (orient3d > 0): the path along x, y, z in order is
// negative, so the even axis orders get v0 and v1 swapped (parity only, no predicate is called).
struct IndexedTets {
  std::vector<double> xyz;
  std::vector<std::uint32_t> tets;
};

inline IndexedTets kuhn_grid(int n, double spacing, double shift = 0.0) {
  IndexedTets g;
  const int m = n + 1;
  g.xyz.reserve(std::size_t(m) * m * m * 3);
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        g.xyz.push_back(shift + spacing * i);
        g.xyz.push_back(shift + spacing * j);
        g.xyz.push_back(shift + spacing * k);
      }
  auto id = [m](int i, int j, int k) { return std::uint32_t((k * m + j) * m + i); };
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  g.tets.reserve(std::size_t(n) * n * n * 24);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& p : perms) {
          int c[3] = {i, j, k};
          std::uint32_t v[4];
          v[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            c[p[s]] += 1;
            v[s + 1] = id(c[0], c[1], c[2]);
          }
          const bool even = (p[0] == 0 && p[1] == 1) || (p[0] == 1 && p[1] == 2) || (p[0] == 2 && p[1] == 0);
          if (even) std::swap(v[0], v[1]);
          g.tets.insert(g.tets.end(), v, v + 4);
        }
  return g;
}

}  // namespace volmap_oracle
