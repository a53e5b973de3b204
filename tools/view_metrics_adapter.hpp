// tools/view_metrics_adapter.hpp — the per-tet figures volmap-view shows, in the shape the viewer
// wants (flat arrays). INTERIM: until volmap/metrics.hpp (wip-vmap) lands, this computes them itself
// with the formulas of volmap-reference.md §7 (J = F1·F0⁻¹ input→output, singular values from the
// eigenvalues of JᵀJ, VOLMAP's five energies, radius ratio 3r/R). Once the metrics module lands this
// file becomes a thin adapter over it. Display values only: validity flags never come from here.
#pragma once

#include <volmap/mesh_data.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace volmap_view {

struct ViewMetrics {
  std::vector<double> sigma;  // 3 per tet, s1 >= s2 >= s3 >= 0
  std::vector<double> conformal, dirichlet, symmetric_dirichlet, arap, mips3d;  // raw (inf allowed)
  std::vector<double> quality_in, quality_out;  // 3r/R in [0,1]
};

namespace detail {

inline void edge_matrix(const double* xyz, const std::uint32_t* tv, double m[3][3]) {
  // Columns a1-a0, a2-a0, a3-a0.
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) m[r][c] = xyz[3 * tv[c + 1] + r] - xyz[3 * tv[0] + r];
}

inline double det3(const double m[3][3]) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

// Eigenvalues of a symmetric 3x3 matrix, descending (Smith's closed form).
inline void sym_eigenvalues(const double a[3][3], double out[3]) {
  const double p1 = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
  const double q = (a[0][0] + a[1][1] + a[2][2]) / 3;
  if (p1 == 0) {
    out[0] = a[0][0]; out[1] = a[1][1]; out[2] = a[2][2];
  } else {
    const double p2 = (a[0][0] - q) * (a[0][0] - q) + (a[1][1] - q) * (a[1][1] - q) + (a[2][2] - q) * (a[2][2] - q) + 2 * p1;
    const double p = std::sqrt(p2 / 6);
    double b[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) b[i][j] = (a[i][j] - (i == j ? q : 0)) / p;
    double r = det3(b) / 2;
    r = std::min(1.0, std::max(-1.0, r));
    const double phi = std::acos(r) / 3;
    out[0] = q + 2 * p * std::cos(phi);
    out[2] = q + 2 * p * std::cos(phi + 2 * M_PI / 3);
    out[1] = 3 * q - out[0] - out[2];
  }
  std::sort(out, out + 3, [](double x, double y) { return x > y; });
}

// Normalised radius ratio 3r/R (Verdict §6.11 as in volmap-reference.md §7), 0 when degenerate.
inline double radius_ratio(const double* p0, const double* p1, const double* p2, const double* p3) {
  double L0[3], L2[3], L3[3];
  for (int i = 0; i < 3; ++i) { L0[i] = p1[i] - p0[i]; L2[i] = p0[i] - p2[i]; L3[i] = p3[i] - p0[i]; }
  auto cross = [](const double* u, const double* v, double* w) {
    w[0] = u[1] * v[2] - u[2] * v[1]; w[1] = u[2] * v[0] - u[0] * v[2]; w[2] = u[0] * v[1] - u[1] * v[0];
  };
  auto dot = [](const double* u, const double* v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  auto norm = [&](const double* u) { return std::sqrt(dot(u, u)); };
  double c20[3], c30[3], c32[3];
  cross(L2, L0, c20);
  cross(L3, L0, c30);
  cross(L3, L2, c32);
  const double V = dot(c20, L3) / 6;
  if (!(std::fabs(V) > 0)) return 0;
  auto tri_area = [&](const double* a, const double* b, const double* c) {
    double u[3], v[3], w[3];
    for (int i = 0; i < 3; ++i) { u[i] = b[i] - a[i]; v[i] = c[i] - a[i]; }
    cross(u, v, w);
    return norm(w) / 2;
  };
  const double A = tri_area(p0, p1, p2) + tri_area(p0, p1, p3) + tri_area(p0, p2, p3) + tri_area(p1, p2, p3);
  const double r = 3 * std::fabs(V) / A;
  double num[3];
  const double l3 = dot(L3, L3), l2 = dot(L2, L2), l0 = dot(L0, L0);
  for (int i = 0; i < 3; ++i) num[i] = l3 * c20[i] + l2 * c30[i] + l0 * c32[i];
  const double R = norm(num) / (12 * std::fabs(V));
  const double q = 3 * r / R;
  return std::isfinite(q) ? std::min(1.0, q) : 0;
}

}  // namespace detail

inline std::vector<double> tet_quality(const volmap::TetMeshData& mesh, const std::vector<double>& xyz) {
  std::vector<double> q(mesh.num_tets());
  for (std::size_t t = 0; t < mesh.num_tets(); ++t) {
    const std::uint32_t* tv = &mesh.tets[4 * t];
    q[t] = detail::radius_ratio(&xyz[3 * tv[0]], &xyz[3 * tv[1]], &xyz[3 * tv[2]], &xyz[3 * tv[3]]);
  }
  return q;
}

inline ViewMetrics compute_view_metrics(const volmap::TetMeshData& source, const std::vector<double>& target_xyz) {
  const std::size_t nt = source.num_tets();
  const double inf = std::numeric_limits<double>::infinity();
  ViewMetrics m;
  m.sigma.resize(3 * nt);
  m.conformal.resize(nt);
  m.dirichlet.resize(nt);
  m.symmetric_dirichlet.resize(nt);
  m.arap.resize(nt);
  m.mips3d.resize(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint32_t* tv = &source.tets[4 * t];
    double F0[3][3], F1[3][3];
    detail::edge_matrix(source.xyz.data(), tv, F0);
    detail::edge_matrix(target_xyz.data(), tv, F1);
    const double d0 = detail::det3(F0);
    double s[3] = {0, 0, 0};
    if (d0 != 0) {
      // inv(F0) by the adjugate; J = F1 * inv(F0); JᵀJ.
      double inv[3][3];
      inv[0][0] = (F0[1][1] * F0[2][2] - F0[1][2] * F0[2][1]) / d0;
      inv[0][1] = (F0[0][2] * F0[2][1] - F0[0][1] * F0[2][2]) / d0;
      inv[0][2] = (F0[0][1] * F0[1][2] - F0[0][2] * F0[1][1]) / d0;
      inv[1][0] = (F0[1][2] * F0[2][0] - F0[1][0] * F0[2][2]) / d0;
      inv[1][1] = (F0[0][0] * F0[2][2] - F0[0][2] * F0[2][0]) / d0;
      inv[1][2] = (F0[0][2] * F0[1][0] - F0[0][0] * F0[1][2]) / d0;
      inv[2][0] = (F0[1][0] * F0[2][1] - F0[1][1] * F0[2][0]) / d0;
      inv[2][1] = (F0[0][1] * F0[2][0] - F0[0][0] * F0[2][1]) / d0;
      inv[2][2] = (F0[0][0] * F0[1][1] - F0[0][1] * F0[1][0]) / d0;
      double J[3][3], JtJ[3][3];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) J[i][j] = F1[i][0] * inv[0][j] + F1[i][1] * inv[1][j] + F1[i][2] * inv[2][j];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) JtJ[i][j] = J[0][i] * J[0][j] + J[1][i] * J[1][j] + J[2][i] * J[2][j];
      double ev[3];
      detail::sym_eigenvalues(JtJ, ev);
      for (int i = 0; i < 3; ++i) s[i] = std::sqrt(std::max(0.0, ev[i]));
    }
    const double s1 = s[0], s2 = s[1], s3 = s[2];
    m.sigma[3 * t] = s1;
    m.sigma[3 * t + 1] = s2;
    m.sigma[3 * t + 2] = s3;
    const double sq = s1 * s1 + s2 * s2 + s3 * s3;
    const double prod = s1 * s2 * s3;
    m.dirichlet[t] = sq;
    m.arap[t] = (s1 - 1) * (s1 - 1) + (s2 - 1) * (s2 - 1) + (s3 - 1) * (s3 - 1);
    if (s3 > 0) {
      m.conformal[t] = sq / (3 * std::cbrt(prod * prod));
      m.symmetric_dirichlet[t] = sq + 1 / (s1 * s1) + 1 / (s2 * s2) + 1 / (s3 * s3);
      m.mips3d[t] = (s1 / s2 + s2 / s1) * (s3 / s1 + s1 / s3) * (s2 / s3 + s3 / s2) / 8;
    } else {
      m.conformal[t] = m.symmetric_dirichlet[t] = m.mips3d[t] = inf;
    }
  }
  m.quality_in = tet_quality(source, source.xyz);
  m.quality_out = tet_quality(source, target_xyz);
  return m;
}

}  // namespace volmap_view
