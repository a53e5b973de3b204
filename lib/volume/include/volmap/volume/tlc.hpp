// volmap/volume/tlc.hpp — Total Lifted Content (Du, Aigerman, Zhou, Kovalsky, Yan, Kaufman, Ju, "Lifting
// Simplices to Find Injectivity", ACM ToG 39(4), 2020), re-implemented from docs/mapping.md §6:
// E = Σ_t A_α(t), the 3-volume of tet t lifted with squared edge lengths |x_i − x_j|² + a·d_ij,
// a = α^{2/3}, Tutte form d_ij = 1 (or rest-shape |r_i − r_j|²), α = alphaRatio · vol(D) / rest
// measure. Computed as A = √det(G)/6 with G = TᵀT + a·G_rest (T: target edge matrix), so
// ∂A/∂T = A·T·G⁻¹. L-BFGS (LBFGSpp) over the free vertices, parallel per tet (TBB).
// Unlike the original (plain double `all_good` test), success is the EXACT check on the returned
// doubles (orient3d > 0 on every tet, VOLMAP convention); it stops as soon as that passes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace volmap {

struct TlcOptions {
  bool tutte_form = true;       // d_ij = 1 (default) or the rest shape's squared lengths
  double alpha_ratio = 1e-6;
  int max_evaluations = 10000;
  double ftol = 1e-8;           // relative energy decrease test
  double time_limit_seconds = 0;
  // Hand-over: stop when the double count of non-positive tets is at most stall_max_bad and has not
  // reached a new minimum for stall_evaluations energy evaluations (0 = run to convergence); the map
  // is left at the point of that minimum. For a caller with a cheaper repair of a few tets.
  long stall_evaluations = 0;
  std::size_t stall_max_bad = 0;
  // Early finish: each time the double count of non-positive tets reaches a new minimum within
  // 1..finish_max_bad, `finish` is called with a copy of the map at that point (unscaled, all
  // vertices). When it returns true it has made that copy exactly positive everywhere (e.g. by exact
  // local moves); TLC ends with it (result.finished). When false, TLC goes on as if not called.
  std::size_t finish_max_bad = 0;
  std::function<bool(std::vector<double>& target_xyz)> finish;
};

struct TlcResult {
  bool certified = false;
  std::size_t nonpositive = 0;
  long evaluations = 0;
  double seconds = 0;
  bool timed_out = false;
  bool stalled = false;
  bool finished = false;  // ended by `finish`
};

TlcResult tlc_untangle(const std::vector<double>& source_xyz, const std::vector<std::uint32_t>& tets,
                       const std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                       const TlcOptions& options = {});

// Lifted content of one tet and its gradient (exposed for tests): T = target edge matrix
// (row-major, 9), G_rest = a·rest Gram matrix (row-major, 9). Writes ∂A/∂T into dT when non-null.
double tlc_lifted_content(const double* T, const double* a_rest_gram, double* dT);

}  // namespace volmap
