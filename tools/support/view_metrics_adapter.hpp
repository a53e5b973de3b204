// tools/view_metrics_adapter.hpp — the per-tet figures volmap-view shows, as flat arrays, taken from
// the metrics module (volmap/metrics.hpp: VOLMAP's five clamped energies, quality 3r/R).
// Per-tet singular values come from the metrics module too (MetricsReport::per_tet.singular_values:
// VOLMAP's path, J = F_out·F_in⁻¹ with Eigen's inverse and JacobiSVD, volmap-reference.md §7).
// One thing the metrics module does not do, done here:
//  * sources that are not VOLMAP-positive (e.g. the all-negative hand/max polycube pairs): J is
//    invariant under a relabelling applied to both meshes, so each negative source tet is given to
//    compute_metrics with v0<->v1 swapped in both; source tets of zero volume have no J and are
//    left out (their energies NaN, quality 0, singular values 0). The relabelling permutes the
//    columns of F_in and F_out alike, so J and its singular values are unchanged.
// Display values only: validity flags never come from here (volmap-view uses exact predicates).
#pragma once

#include <volmap/core/mesh_data.hpp>
#include <volmap/check/metrics.hpp>

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
  m.sigma.assign(3 * nt, 0.0);
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
      for (int i = 0; i < 3; ++i) m.sigma[3 * t + i] = report.per_tet.singular_values[3 * k + i];
    }
  }
  return m;
}

}  // namespace volmap_view
