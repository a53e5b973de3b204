// untangle_support.hpp — machinery shared by the per-tet untanglers (FFM in ffm.cpp, TLC in tlc.cpp):
// edge matrices, the free-variable layout (3 doubles per unlocked vertex,
// in increasing vertex id) with its CSR gather of per-tet gradients, the box-of-side-10 frame of
// mapping.md §5, and the L-BFGS objective guard (time limit + exact stop).
// Conventions: flat xyz arrays (3 doubles per vertex), tets as 4 0-based ids; edge matrices row-major,
// T[3*i+k] = coordinate i of edge k (edge k = x_{k+1} − x_0). A VOLMAP-positive tet (orient3d > 0)
// has det T < 0. Internal header (lib/src): not part of the public API.
#pragma once

#include <volmap/core/time_budget.hpp>

#include <Eigen/Core>
#include <LBFGS.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

namespace volmap::untangle {

// True when TBB may run one thread only (a global_control limit of 1, or an arena of one): loops
// can then take their in-order form.
inline bool single_thread() {
  return tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) == 1 || tbb::this_task_arena::max_concurrency() == 1;
}

// The double determinants and volumes below drive the optimisers (energies, step guards, scaling,
// input sanity); they never certify: validity is the exact volmap::count_nonpositive.
inline double det3(const double* A) {
  return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) + A[2] * (A[3] * A[7] - A[4] * A[6]);
}

inline void edge_matrix(const double* x, const std::uint32_t* t, double* T) {
  const double* p0 = x + 3 * std::size_t(t[0]);
  for (int k = 0; k < 3; ++k) {
    const double* pk = x + 3 * std::size_t(t[k + 1]);
    for (int i = 0; i < 3; ++i) T[3 * i + k] = pk[i] - p0[i];
  }
}

// Σ of the VOLMAP-signed tet volumes (−det(edge matrix)/6: positive for orient3d > 0), in double.
// With a fixed boundary map this is the enclosed domain volume, whatever the interior does.
inline double signed_volume_sum(const double* xyz, const std::vector<std::uint32_t>& tets) {
  double sum = 0, T[9];
  for (std::size_t t = 0; t < tets.size() / 4; ++t) {
    edge_matrix(xyz, &tets[4 * t], T);
    sum += -det3(T) / 6.0;
  }
  return sum;
}

// Chain rule from ∂E/∂T (row-major 3x3) to the 12 vertex gradients of the tet (vertex-major xyz).
inline void edge_gradient_to_vertices(const double* dT, double* out12) {
  for (int i = 0; i < 3; ++i) {
    out12[i] = -(dT[3 * i] + dT[3 * i + 1] + dT[3 * i + 2]);
    for (int k = 0; k < 3; ++k) out12[3 * (k + 1) + i] = dT[3 * i + k];
  }
}

// Free vertices as optimisation variables, and the vertex → incident (tet*4+local) slots they gather from.
struct FreeVertexLayout {
  std::vector<std::int64_t> free_index;      // per vertex: variable block or -1 (locked)
  std::vector<std::uint32_t> free_vertices;  // variable block -> vertex
  std::vector<std::uint32_t> adj_offset;     // CSR over free blocks
  std::vector<std::uint32_t> adj_slot;

  void build(std::size_t num_vertices, const std::vector<std::uint32_t>& tets, const std::vector<std::uint8_t>& locked);
  std::size_t num_variables() const { return 3 * free_vertices.size(); }
  // x[free vertices] = vars (parallel).
  void load(const double* vars, double* x) const;
  // vars = x[free vertices].
  void extract(const double* x, double* vars) const;
  // grad[block] = Σ of the tet gradients (12 per tet) over the block's incident slots (parallel).
  void gather(const double* tet_grad, double* grad) const;
};

// Affine frame: scaled = (x − center)·scale, with the bounding box of the fitted points of side `side`.
struct BoxFrame {
  double center[3] = {0, 0, 0};
  double scale = 1;
  // Throws Error(BadInput) (prefixed by `who`) when the points are degenerate or not finite.
  void fit(const std::vector<double>& xyz, double side, const char* who);
  std::vector<double> to_scaled(const std::vector<double>& xyz) const;
  // target_xyz[free vertices] = vars mapped back to the unscaled frame (locked vertices untouched).
  void write_back(const FreeVertexLayout& layout, const double* vars, std::vector<double>& target_xyz) const;
};

struct CertifiedStop {};
struct TimeStop {};
struct StallStop {};
struct FinishedStop {};

// LBFGSpp objective around an energy: checks the deadline (throws TimeStop), optionally acts as a
// barrier (+∞ when a double determinant is not positive) and, when every double determinant is
// positive, runs the exact check on the unscaled candidate every `check_period` evaluations and
// throws CertifiedStop when it passes. With stall_evaluations > 0 it throws StallStop once the
// double count of non-positive tets (reported by the energy in `double_nonpositive`) has stayed
// at most stall_max_bad without a new minimum for stall_evaluations evaluations.
// With try_finish set, each time the double count reaches a new minimum within 1..finish_max_bad
// it is called at that point; when it returns true (it finished the map exactly, kept by the
// caller) FinishedStop is thrown.
// `last_x` holds the point at which a stop was thrown (for a stall: the point of the minimum).
// With track_lowest, `lowest_x` holds the lowest-energy evaluated point whose double determinants
// are all positive (a line search that gives up leaves the solver at a worse trial point).
struct GuardedObjective {
  // E(vars); writes the gradient when grad != nullptr and sets *all_positive (double test).
  std::function<double(const double* vars, double* grad, bool* all_positive)> evaluate;
  const FreeVertexLayout* layout = nullptr;
  const BoxFrame* frame = nullptr;
  const std::vector<std::uint32_t>* tets = nullptr;
  std::vector<double>* candidate = nullptr;  // unscaled full coordinates (locked vertices exact)
  bool stop_when_certified = true;
  bool barrier = false;
  TimeBudget budget;  // unlimited unless set
  long evaluations = 0;
  long next_exact_check = 0;
  int check_period = 10;
  long stall_evaluations = 0;           // 0: never stop on a stall
  std::size_t stall_max_bad = 0;
  double max_move = 0;                  // CappedBacktracking: largest trial move of a variable (0: none)
  std::function<bool(const double* vars)> try_finish;
  std::size_t finish_max_bad = 0;
  std::size_t finish_tried_at = std::numeric_limits<std::size_t>::max();  // count of the last try
  std::size_t double_nonpositive = 0;   // set by `evaluate` when stalls or finishes are used
  std::size_t fewest_nonpositive = std::size_t(-1);
  long fewest_at = 0;                   // evaluation that reached fewest_nonpositive
  Eigen::VectorXd fewest_x;             // its point: where a StallStop leaves the run
  Eigen::VectorXd last_x;
  bool track_lowest = false;
  double lowest_energy = std::numeric_limits<double>::infinity();
  Eigen::VectorXd lowest_x;

  bool past_deadline() const { return budget.expired(); }
  // Records the count of this evaluation at x; true when the run has stalled (see above).
  bool stalled(const Eigen::VectorXd& x);
  // Calls try_finish at x when the count is a new low within 1..finish_max_bad; its verdict.
  bool finished(const Eigen::VectorXd& x);
  // Writes vars into the candidate and returns true when its exact count is 0.
  bool exactly_certified(const double* vars);
  double operator()(const Eigen::VectorXd& x, Eigen::VectorXd& grad);
};

// L-BFGS parameters shared by the untanglers: memory 7, gradient test ‖g‖ ≤ gtol (absolute),
// relative energy-decrease test over one iteration when ftol > 0, at most 40 line-search steps.
LBFGSpp::LBFGSParam<double> lbfgs_param(int max_iterations, double gtol, double ftol, int linesearch);

// LBFGSpp's backtracking (Armijo) line search whose trial step first moves no variable farther than
// the objective's max_move (0: no cap). L-BFGS starts every run with a step of unit length; on a
// barrier energy (+∞ outside the positive set) the search then spends its first evaluations halving
// it back to the scale of the mesh's edges.
template <typename Scalar>
class CappedBacktracking {
 public:
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  template <typename Foo>
  static void LineSearch(Foo& f, Scalar& fx, Vector& x, Vector& grad, Scalar& step, const Vector& drt, const Vector& xp,
                         const LBFGSpp::LBFGSParam<Scalar>& param) {
    const Scalar largest = drt.cwiseAbs().maxCoeff();
    if (f.max_move > 0 && largest * step > f.max_move) step = f.max_move / largest;
    LBFGSpp::LineSearchBacktracking<Scalar>::LineSearch(f, fx, x, grad, step, drt, xp, param);
  }
};

// Runs one LBFGSpp minimisation from x; returns the iterations done, or -1 when the line search gave
// up (LBFGSpp throws std::runtime_error / std::logic_error): x is then the solver's last iterate.
// CertifiedStop, TimeStop, StallStop and FinishedStop propagate.
template <class Solver>
long run_lbfgs(Solver& solver, GuardedObjective& objective, Eigen::VectorXd& x) {
  double fx = 0;
  try {
    return solver.minimize(objective, x, fx);
  } catch (const CertifiedStop&) {
    throw;
  } catch (const TimeStop&) {
    throw;
  } catch (const StallStop&) {
    throw;
  } catch (const FinishedStop&) {
    throw;
  } catch (const std::exception&) {
    return -1;
  }
}

}  // namespace volmap::untangle
