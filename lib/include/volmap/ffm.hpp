// volmap/ffm.hpp — the foldover-free map untangler (FFM) and its validity-preserving quality pass.
//
// Method: Garanzha, Kaporin, Kudryavtseva, Protais, Ray, Sokolov, "Foldover-free maps in 50 lines
// of code", ACM ToG 40(4), 2021 — re-implemented from the formulas of docs/mapping.md §5 (no code
// taken from the AGPL reference). Per tet J = T·R⁻¹ (T, R: target and reference edge matrices
// [x1−x0 | x2−x0 | x3−x0]), D = det J, χ(D,ε) = (D + √(ε²+D²))/2 (cancellation-free for D ≤ 0),
// E_ε = Σ vol_ref · [(1−θ)·tr(JᵀJ)/χ^{2/3} + θ·(1+D²)/χ], θ = 1/2, minimised by L-BFGS (LBFGSpp)
// over the free (unlocked) vertices with the ε schedule of the paper.
//
// Orientation: VOLMAP-positive tets (orient3d(v0,v1,v2,v3) > 0) have a NEGATIVE edge-matrix
// determinant. Reference tets are built with the same handedness as the input, so D > 0 ⇔ the
// target tet is VOLMAP-positive. Coordinates: flat xyz arrays (3 doubles per vertex), tets as 4
// 0-based ids. Locked vertices are never written (bit-exact boundary).
//
// Exact stop: whenever every double determinant is positive, the unscaled candidate coordinates are
// checked with volmap::orient3d_tets; the untangler stops as soon as that exact check passes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace volmap {

enum class ReferenceShape {
  RegularTet,  // regular tet of volume vol(D)/T for every element (isotropic, "Tutte form")
  RestShape    // the source tet, scaled so that Σ vol_src = vol(D)
};

struct FfmOptions {
  ReferenceShape reference = ReferenceShape::RegularTet;
  double theta = 0.5;
  int max_outer_iterations = 10000;
  int max_lbfgs_iterations = 3000;
  double gradient_tolerance = 1e-4;
  double time_limit_seconds = 0;  // 0 = no limit
  bool stop_when_certified = true;
};

struct FfmResult {
  bool certified = false;           // exact orient3d > 0 on every tet of the returned target
  std::size_t nonpositive = 0;      // exact count of tets with orient3d <= 0 at the end
  int outer_iterations = 0;
  long lbfgs_iterations = 0;
  long evaluations = 0;
  double final_epsilon = 0;
  double min_det = 0;               // min D over tets (scaled space) at the end
  double seconds = 0;
  bool timed_out = false;
};

// Untangles target_xyz in place (free vertices only). source_xyz: rest positions (VOLMAP-positive).
// locked[v] != 0 for vertices that must not move (the boundary). Returns the best map found: the
// certified one when certified, else the last iterate.
FfmResult ffm_untangle(const std::vector<double>& source_xyz, const std::vector<std::uint32_t>& tets,
                       const std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                       const FfmOptions& options = {});

struct QualityResult {
  bool improved = false;     // a certified lower-energy map replaced the input
  double energy_before = 0;  // FFM energy at ε→0 (scaled space)
  double energy_after = 0;
  int rounds = 0;
};

// Quality pass that never breaks validity: minimises the FFM energy at ε = 1e-10 with a line search
// that rejects any step making a double determinant non-positive, and keeps a result only when the
// exact check passes on it (otherwise the input is kept). Requires a certified target on entry.
QualityResult ffm_quality_pass(const std::vector<double>& source_xyz, const std::vector<std::uint32_t>& tets,
                               const std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                               ReferenceShape reference, int max_iterations, double time_limit_seconds);

// The FFM energy on the free variables (exposed for tests and benchmarks).
// Variables: 3 doubles per free vertex, in increasing vertex id, in the scaled frame (target box
// side 10). Evaluation is parallel over tets (TBB) and allocation-free after construction.
class FfmEnergy {
 public:
  FfmEnergy(const std::vector<double>& source_xyz, const std::vector<std::uint32_t>& tets,
            const std::vector<std::uint8_t>& locked, const std::vector<double>& target_xyz,
            ReferenceShape reference, double theta = 0.5);
  ~FfmEnergy();
  FfmEnergy(const FfmEnergy&) = delete;
  FfmEnergy& operator=(const FfmEnergy&) = delete;

  std::size_t num_variables() const;
  // Current free coordinates (scaled frame) taken from the constructor's target.
  std::vector<double> initial_variables() const;
  // E_ε(vars); writes ∂E/∂vars into grad (num_variables doubles) when grad != nullptr.
  double evaluate(const double* vars, double epsilon, double* grad) const;
  // Minimum D over tets for vars (scaled frame), computed in double.
  double min_det(const double* vars) const;
  // Writes vars back to unscaled coordinates of the free vertices of target_xyz.
  void write_back(const double* vars, std::vector<double>& target_xyz) const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// χ(D,ε) and χ'(D,ε) (exposed for tests): cancellation-free for D ≤ 0.
double ffm_chi(double D, double epsilon);
double ffm_chi_derivative(double D, double epsilon);

}  // namespace volmap
