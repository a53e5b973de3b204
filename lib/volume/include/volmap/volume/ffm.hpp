// volmap/volume/ffm.hpp — the foldover-free map untangler (FFM) and its validity-preserving quality pass.
//
// Method: Garanzha, Kaporin, Kudryavtseva, Protais, Ray, Sokolov, "Foldover-free maps in 50 lines
// of code", ACM ToG 40(4), 2021 — re-implemented from the formulas of docs/mapping.md §5 (no code
// taken from the AGPL reference). Per tet J = T·R⁻¹ (T, R: target and reference edge matrices
// [x1−x0 | x2−x0 | x3−x0]), D = det J, χ(D,ε) = (D + √(ε²+D²))/2 (cancellation-free for D ≤ 0),
// E_ε = Σ vol_ref · [(1−θ)·tr(JᵀJ)/χ^{2/3} + θ·(1+D²)/χ], θ = 1/2, minimised by L-BFGS (LBFGSpp)
// over the free (unlocked) vertices with the ε schedule of the paper — or by Newton's method with
// per-tet SPD-projected Hessians (9×9 in J, eigenvalues clamped at 0, pulled back to 12×12) and a
// sparse Cholesky (Eigen SimplicialLDLT), Armijo line search on E_ε.
//
// Orientation: VOLMAP-positive tets (orient3d(v0,v1,v2,v3) > 0) have a NEGATIVE edge-matrix
// determinant. Reference tets are built with the same handedness as the input, so D > 0 ⇔ the
// target tet is VOLMAP-positive. Coordinates: flat xyz arrays (3 doubles per vertex), tets as 4
// 0-based ids. Locked vertices are never written (bit-exact boundary).
//
// Exact stop: whenever every double determinant is positive, the unscaled candidate coordinates are
// checked with volmap::count_nonpositive; the untangler stops as soon as that exact check passes.
#pragma once

#include <volmap/core/tet_mesh.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace volmap {

enum class ReferenceShape {
  RegularTet,  // regular tet of volume vol(D)/T for every element (isotropic, "Tutte form")
  RestShape    // the source tet, scaled so that Σ vol_src = vol(D); a tet too flat to invert in double
               // precision (exactly positive slivers the mapper's refinement may create) takes the
               // regular reference instead, so every valid source mesh is a usable rest shape
};

enum class FfmSolver {
  Lbfgs,  // LBFGSpp, memory 7, backtracking line search (Wolfe)
  Newton  // SPD-projected per-tet Hessians + sparse LDLᵀ, Armijo backtracking
};

struct FfmOptions {
  ReferenceShape reference = ReferenceShape::RegularTet;
  FfmSolver solver = FfmSolver::Lbfgs;
  double theta = 0.5;
  int max_outer_iterations = 10000;
  int max_lbfgs_iterations = 200;  // per outer (ε) step; the reference uses 3000, fewer update ε more often
  int max_newton_iterations = 30;  // Newton steps per outer (ε) step
  double gradient_tolerance = 1e-4;
  double time_limit_seconds = 0;  // 0 = no limit
  bool stop_when_certified = true;
  // Stall detection: stop when the double count of tets with D <= 0 has not reached a new minimum in
  // this many outer (ε) steps, so that a stuck stage hands over early. 0 = off (the paper's rule only).
  int stall_outer_iterations = 0;
  // Starting ε: the paper uses 1. A value <= 0 picks a warm start for nearly valid maps,
  // ε₀ = clamp(2·max(0, −D_min), 1e-3, 1) at the starting map, so that a map with few, slightly
  // inverted tets is not first smoothed out by a large ε (used by the local stage).
  double initial_epsilon = 1.0;
};

struct FfmResult {
  bool certified = false;           // exact orient3d > 0 on every tet of the returned target
  std::size_t nonpositive = 0;      // exact count of tets with orient3d <= 0 at the end
  int outer_iterations = 0;
  long lbfgs_iterations = 0;        // inner iterations (L-BFGS or Newton)
  long evaluations = 0;
  long line_search_failures = 0;   // L-BFGS line searches that gave up (the better point is kept)
  double final_epsilon = 0;
  double min_det = 0;               // min D over tets (scaled space) at the end
  double seconds = 0;
  bool timed_out = false;
  bool stalled = false;             // stopped by stall detection
};

// Untangles target_xyz in place (free vertices only). source_xyz: rest positions (VOLMAP-positive).
// locked[v] != 0 for vertices that must not move (the boundary). Returns the best map found: the
// certified one when certified, else the last iterate.
FfmResult ffm_untangle(const std::vector<double>& source_xyz, const std::vector<std::uint32_t>& tets,
                       const std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                       const FfmOptions& options = {});

// Local untangling of what remains: the free vertices of the exactly non-positive tets, grown by
// `rings` vertex rings (through shared tets), are optimised by FFM (Newton) with every other vertex
// frozen; the region grows by `ring_step` rings when a round makes no progress. A round's result is
// kept only when the exact count of the region's tets (hence the global count) decreases, so the
// exact non-positive count never increases.
struct LocalUntangleOptions {
  ReferenceShape reference = ReferenceShape::RegularTet;
  int rings = 2;
  int ring_step = 2;
  int max_rings = 12;
  int max_rounds = 12;
  int stall_outer_iterations = 15;  // per region solve (FfmOptions::stall_outer_iterations)
  double time_limit_seconds = 0;  // 0 = no limit
};

struct LocalUntangleResult {
  std::size_t nonpositive_before = 0, nonpositive_after = 0;
  int rounds = 0;
  std::size_t largest_region_tets = 0;
  double seconds = 0;
};

// `source`: the rest mesh without tombstones (its stars give the rings); target_xyz and locked hold
// 3 doubles and 1 flag per vertex.
LocalUntangleResult ffm_local_untangle(const TetMesh& source, const std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                                       const LocalUntangleOptions& options = {});

struct QualityResult {
  bool improved = false;     // a certified lower-energy map replaced the input
  double energy_before = 0;  // FFM energy at ε→0 (scaled space)
  double energy_after = 0;
  int rounds = 0;
};

// Quality pass that never breaks validity: minimises the FFM energy at ε = 1e-10 with a line search
// that rejects any step making a double determinant non-positive, and keeps a result only when the
// exact check passes on it (otherwise the input is kept). Requires a certified target on entry.
// Stops after max_iterations L-BFGS iterations, at the time limit, or (relative_decrease > 0) at the
// first iteration that lowers the energy by less than relative_decrease × its value.
QualityResult ffm_quality_pass(const std::vector<double>& source_xyz, const std::vector<std::uint32_t>& tets,
                               const std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                               ReferenceShape reference, int max_iterations, double time_limit_seconds,
                               double relative_decrease = 0);

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
  // E_ε(vars) and its Hessian as a dense symmetric num_variables² matrix (row-major), either exact
  // or with every per-tet term SPD-projected (as Newton uses it). For tests of small problems only.
  double evaluate_dense_hessian(const double* vars, double epsilon, bool spd_projection, double* hessian) const;
  // How many source tets took the regular reference because their rest shape was unusable (RestShape).
  std::size_t unusable_rest_shapes() const;
  // Minimum D over tets for vars (scaled frame), computed in double.
  double min_det(const double* vars) const;
  // Writes vars back to unscaled coordinates of the free vertices of target_xyz.
  void write_back(const double* vars, std::vector<double>& target_xyz) const;

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  friend class FfmNewton;  // ffm.cpp: Newton inner solver (Hessian assembly on Impl)
  std::unique_ptr<Impl> impl_;
};

// χ(D,ε) and χ'(D,ε) (exposed for tests): cancellation-free for D ≤ 0.
double ffm_chi(double D, double epsilon);
double ffm_chi_derivative(double D, double epsilon);

}  // namespace volmap
