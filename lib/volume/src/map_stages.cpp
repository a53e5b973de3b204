// map_stages.cpp — each stage of the mapper as one call over the MapState (map_stages.hpp). The
// untanglers run on flat arrays of the compacted mesh: source positions and tets straight from the
// TetMesh, the locked mask from its property, the target copied out and back.
#include <volmap/volume/map_stages.hpp>

#include <volmap/volume/tutte3d.hpp>

#include <algorithm>

namespace volmap {

namespace {

// Runs `untangle(x)` on the state's target as a flat array x (compacted mesh) and stores it back.
template <class Untangle>
auto on_flat_target(MapState& s, Untangle&& untangle) {
  s.require_compact();
  std::vector<double> x = s.target_xyz();
  auto result = untangle(x);
  s.set_target_xyz(x);
  return result;
}

}  // namespace

FeasibilityReport analyze_feasibility(const MapState& s) {
  s.require_compact();
  return analyze_feasibility(s.source, s.locked.data(), s.target_xyz());
}

std::vector<InfeasibilityCertificate> find_local_infeasibility(const MapState& s) {
  s.require_compact();
  return find_local_infeasibility(s.source, s.locked.data(), s.target_xyz());
}

ChordSplitResult remove_blocking_chords(MapState& s, const FeasibilityReport& report) {
  s.require_compact();
  const ChordRules rules(s.source, s.locked.data(), s.target_xyz());
  ChordSplitResult r = remove_blocking_chords(s.source, rules, report.blocking_chord_edges, report.blocking_chord_faces);
  free_fixed_nonpositive_tets(s.source, rules, r);
  if (s.source.num_free_tet_slots() > 0) s.source.compact();  // a degree-3 removal frees a slot; vertex ids stay
  return r;
}

void place_by_tutte(MapState& s) {
  on_flat_target(s, [&](std::vector<double>& x) {
    return solve_uniform_laplacian(s.source.num_vertices(), unique_tet_edges(s.source), s.locked.data(), x);
  });
}

RadialStartResult place_by_radial_tutte(MapState& s) {
  return on_flat_target(s, [&](std::vector<double>& x) { return place_by_radial_tutte(s.source, s.locked.data(), x); });
}

bool boundary_image_is_convex(const MapState& s) {
  s.require_compact();
  return boundary_image_is_convex(s.source, s.target_xyz());
}

void place_new_vertices_by_laplacian(MapState& s, std::size_t keep) {
  s.require_compact();
  if (s.source.num_vertices() <= keep) return;
  std::vector<std::uint8_t> kept(s.source.num_vertices(), 0);
  std::fill(kept.begin(), kept.begin() + std::ptrdiff_t(keep), std::uint8_t(1));
  on_flat_target(s, [&](std::vector<double>& x) { return solve_uniform_laplacian(kept.size(), unique_tet_edges(s.source), kept, x); });
}


TlcResult run_tlc(MapState& s, const TlcOptions& options) {
  return on_flat_target(s, [&](std::vector<double>& x) {
    return tlc_untangle(s.source.positions(), s.source.tet_vertex_array(), s.locked.data(), x, options);
  });
}

RelocationResult run_link_kernel(MapState& s, int max_sweeps) {
  return on_flat_target(s, [&](std::vector<double>& x) { return relocate_into_link_kernels(s.source, s.locked.data(), x, max_sweeps); });
}

KernelDescentResult run_kernel_descent(MapState& s) {
  return on_flat_target(s, [&](std::vector<double>& x) { return descend_into_link_kernels(s.source, s.locked.data(), x); });
}

bool finish_by_link_kernels(const MapState& s, std::vector<double>& x) {
  s.require_compact();
  std::vector<double> trial = x;
  const RelocationResult r = relocate_into_link_kernels(s.source, s.locked.data(), trial, 50);
  if (r.nonpositive_after > 0 && descend_into_link_kernels(s.source, s.locked.data(), trial).nonpositive_after > 0) return false;
  x.swap(trial);
  return true;
}

FfmResult run_ffm(MapState& s, const FfmOptions& options) {
  return on_flat_target(s, [&](std::vector<double>& x) {
    return ffm_untangle(s.source.positions(), s.source.tet_vertex_array(), s.locked.data(), x, options);
  });
}

LocalUntangleResult run_local_ffm(MapState& s, const LocalUntangleOptions& options) {
  return on_flat_target(s, [&](std::vector<double>& x) {
    return ffm_local_untangle(s.source, s.locked.data(), x, options);
  });
}

QualityResult run_quality_pass(MapState& s, ReferenceShape reference, int max_iterations, double time_limit_seconds,
                               double relative_decrease) {
  return on_flat_target(s, [&](std::vector<double>& x) {
    return ffm_quality_pass(s.source.positions(), s.source.tet_vertex_array(), s.locked.data(), x, reference, max_iterations,
                            time_limit_seconds, relative_decrease);
  });
}

ConeRepairResult run_cone_repair(MapState& s, const ConeRepairOptions& options) {
  s.require_compact();
  const ConeRepairResult r = cone_repair(s.source, s.target, s.locked, options);
  // Patches delete no vertex: vertex ids stay, tets keep their relative order.
  if (s.source.num_free_tet_slots() > 0) s.source.compact();
  return r;
}

}  // namespace volmap
