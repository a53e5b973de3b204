// tools/view_metrics_adapter.hpp — the per-tet figures volmap-view shows, as flat arrays, taken from
// the metrics module (volmap/metrics.hpp: VOLMAP's five clamped energies, quality 3r/R).
// Two things the metrics module does not do, done here:
//  * sources that are not VOLMAP-positive (e.g. the all-negative hand/max polycube pairs): J is
//    invariant under a relabelling applied to both meshes, so each negative source tet is given to
//    compute_metrics with v0<->v1 swapped in both; source tets of zero volume have no J and are
//    left out (their energies NaN, quality 0);
//  * the singular values of J per tet (metrics.hpp has no per-tet accessor): the largest eigenvalue of
//    JᵀJ in closed form (Smith), the two others from det J and ‖cof J‖² (no cancellation for flat
//    tets); J = F_out·F_in⁻¹ with F = [a1−a0 | a2−a0 | a3−a0] (volmap-reference.md §7).
// Display values only: validity flags never come from here (volmap-view uses exact predicates).
#pragma once

#include <volmap/mesh_data.hpp>
#include <volmap/metrics.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace volmap_view {

struct ViewMetrics {
  std::vector<double> sigma;                                 // 3 per tet, s1 >= s2 >= s3 >= 0
  std::array<std::vector<double>, volmap::kNumEnergies> energy;  // clamped (metrics module); NaN: no J
  std::vector<double> quality_in, quality_out;               // 3r/R (output signed by orientation)
};

namespace detail {

inline double det3(const double m[3][3]) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

// Eigenvalues of a symmetric 3x3 matrix, descending (Smith 1961, trigonometric closed form).
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
    const double r = std::min(1.0, std::max(-1.0, det3(b) / 2));
    const double phi = std::acos(r) / 3;
    out[0] = q + 2 * p * std::cos(phi);
    out[2] = q + 2 * p * std::cos(phi + 2 * M_PI / 3);
    out[1] = 3 * q - out[0] - out[2];
  }
  std::sort(out, out + 3, [](double x, double y) { return x > y; });
}

// Singular values of J = F_out·F_in⁻¹ for one tet (all zero when the source tet is flat).
inline void jacobian_singular_values(const double* xyz_in, const double* xyz_out, const std::uint32_t* tv, double s[3]) {
  double F0[3][3], F1[3][3];
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) {
      F0[r][c] = xyz_in[3 * tv[c + 1] + r] - xyz_in[3 * tv[0] + r];
      F1[r][c] = xyz_out[3 * tv[c + 1] + r] - xyz_out[3 * tv[0] + r];
    }
  s[0] = s[1] = s[2] = 0;
  const double d0 = det3(F0);
  if (!(d0 != 0) || !std::isfinite(d0)) return;
  double inv[3][3];  // adjugate / det
  inv[0][0] = (F0[1][1] * F0[2][2] - F0[1][2] * F0[2][1]) / d0;
  inv[0][1] = (F0[0][2] * F0[2][1] - F0[0][1] * F0[2][2]) / d0;
  inv[0][2] = (F0[0][1] * F0[1][2] - F0[0][2] * F0[1][1]) / d0;
  inv[1][0] = (F0[1][2] * F0[2][0] - F0[1][0] * F0[2][2]) / d0;
  inv[1][1] = (F0[0][0] * F0[2][2] - F0[0][2] * F0[2][0]) / d0;
  inv[1][2] = (F0[0][2] * F0[1][0] - F0[0][0] * F0[1][2]) / d0;
  inv[2][0] = (F0[1][0] * F0[2][1] - F0[1][1] * F0[2][0]) / d0;
  inv[2][1] = (F0[0][1] * F0[2][0] - F0[0][0] * F0[2][1]) / d0;
  inv[2][2] = (F0[0][0] * F0[1][1] - F0[0][1] * F0[1][0]) / d0;
  double J[3][3], C[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) J[i][j] = F1[i][0] * inv[0][j] + F1[i][1] * inv[1][j] + F1[i][2] * inv[2][j];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) C[i][j] = J[0][i] * J[0][j] + J[1][i] * J[1][j] + J[2][i] * J[2][j];
  double ev[3];
  sym_eigenvalues(C, ev);
  // λ1 (largest) from the closed form is accurate; λ2, λ3 are not when λ3 << λ1 (cancellation; flat
  // output tets). Recover them from invariants without cancellation: λ2λ3 = det(J)²/λ1 and
  // λ2+λ3 = (‖cof J‖² − λ2λ3)/λ1, then the stable quadratic roots.
  const double l1 = std::max(0.0, ev[0]);
  const double detJ = det3(F1) / d0;
  double cof2 = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int r0 = (i + 1) % 3, r1 = (i + 2) % 3, c0 = (j + 1) % 3, c1 = (j + 2) % 3;
      const double m = J[r0][c0] * J[r1][c1] - J[r0][c1] * J[r1][c0];
      cof2 += m * m;
    }
  if (!(l1 > 0)) return;
  const double p = detJ * detJ / l1;
  const double q = std::max(0.0, (cof2 - p) / l1);
  const double l2 = (q + std::sqrt(std::max(0.0, q * q - 4 * p))) / 2;
  const double l3 = l2 > 0 ? p / l2 : 0.0;
  s[0] = std::sqrt(l1);
  s[1] = std::sqrt(std::min(l1, l2));
  s[2] = std::sqrt(std::min(l2, std::max(0.0, l3)));
}

}  // namespace detail

// 3r/R of every tet (unsigned), from the metrics module's compat radius ratio −R/(3r).
inline std::vector<double> tet_quality(const volmap::TetMeshData& mesh, const std::vector<double>& xyz) {
  std::vector<double> q(mesh.num_tets());
  for (std::size_t t = 0; t < mesh.num_tets(); ++t) {
    const std::uint32_t* tv = &mesh.tets[4 * t];
    const double compat = volmap::tet_radius_ratio_compat(&xyz[3 * tv[0]], &xyz[3 * tv[1]], &xyz[3 * tv[2]], &xyz[3 * tv[3]]);
    const double v = -1.0 / compat;
    q[t] = std::isfinite(v) ? std::min(1.0, std::fabs(v)) : 0.0;
  }
  return q;
}

// source_signs: exact orient3d of every source tet. upper: VOLMAP clamp (>= 6).
inline ViewMetrics compute_view_metrics(const volmap::TetMeshData& source, const std::vector<double>& target_xyz,
                                        const std::vector<std::int8_t>& source_signs, double upper) {
  const std::size_t nt = source.num_tets();
  ViewMetrics m;
  // Tets with a J, made VOLMAP-positive in the source by an odd relabelling of both meshes.
  volmap::TetMeshData in, out;
  in.xyz = source.xyz;
  out.xyz = target_xyz;
  std::vector<std::size_t> kept;
  kept.reserve(nt);
  in.tets.reserve(source.tets.size());
  for (std::size_t t = 0; t < nt; ++t) {
    if (source_signs[t] == 0) continue;
    const std::uint32_t* tv = &source.tets[4 * t];
    if (source_signs[t] > 0) in.tets.insert(in.tets.end(), {tv[0], tv[1], tv[2], tv[3]});
    else in.tets.insert(in.tets.end(), {tv[1], tv[0], tv[2], tv[3]});
    kept.push_back(t);
  }
  out.tets = in.tets;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (auto& e : m.energy) e.assign(nt, nan);
  m.quality_in.assign(nt, 0.0);
  m.quality_out.assign(nt, 0.0);
  if (!kept.empty()) {
    volmap::MetricsOptions options;
    options.upper = upper;
    options.keep_per_tet = true;
    const volmap::MetricsReport report = volmap::compute_metrics(in, out, options);
    for (std::size_t k = 0; k < kept.size(); ++k) {
      const std::size_t t = kept[k];
      for (int e = 0; e < volmap::kNumEnergies; ++e) m.energy[e][t] = report.per_tet.energy[e][k];
      m.quality_in[t] = report.per_tet.quality_in[k];
      m.quality_out[t] = report.per_tet.quality_out[k];
    }
  }
  m.sigma.resize(3 * nt);
  for (std::size_t t = 0; t < nt; ++t)
    detail::jacobian_singular_values(source.xyz.data(), target_xyz.data(), &source.tets[4 * t], &m.sigma[3 * t]);
  return m;
}

}  // namespace volmap_view
