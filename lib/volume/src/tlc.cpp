// tlc.cpp — Total Lifted Content (Du et al. 2020) from docs/mapping.md §6; see volmap/tlc.hpp.
// Edge matrices row-major: T[3*i+k] = coordinate i of edge k (x_{k+1} − x_0).
#include <volmap/volume/tlc.hpp>

#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>

#include "untangle_support.hpp"

#include <LBFGS.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Core>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>

namespace volmap {

namespace {
using untangle::det3;
using untangle::edge_matrix;
using untangle::signed_volume_sum;

constexpr double kSixth = 1.0 / 6.0;  // a multiply: the energy is a heuristic, not a sign

// A = √det G / 6 with G = TᵀT + a·G_rest (symmetric: six entries), ∂A/∂T = A·T·G⁻¹ = (A/det G)·T·C
// with C the (symmetric) cofactor matrix of G. dT = 0 where det G ≤ 0 (only at a = 0).
inline double lifted_content(const double* T, const double* R, double* dT) {
  const double g00 = T[0] * T[0] + T[3] * T[3] + T[6] * T[6] + R[0];
  const double g01 = T[0] * T[1] + T[3] * T[4] + T[6] * T[7] + R[1];
  const double g02 = T[0] * T[2] + T[3] * T[5] + T[6] * T[8] + R[2];
  const double g11 = T[1] * T[1] + T[4] * T[4] + T[7] * T[7] + R[4];
  const double g12 = T[1] * T[2] + T[4] * T[5] + T[7] * T[8] + R[5];
  const double g22 = T[2] * T[2] + T[5] * T[5] + T[8] * T[8] + R[8];
  const double c00 = g11 * g22 - g12 * g12, c01 = g12 * g02 - g01 * g22, c02 = g01 * g12 - g11 * g02;
  const double det = g00 * c00 + g01 * c01 + g02 * c02;
  const double A = std::sqrt(std::max(det, 0.0)) * kSixth;
  if (dT) {
    if (!(det > 0)) {
      std::fill(dT, dT + 9, 0.0);
      return A;
    }
    const double c11 = g00 * g22 - g02 * g02, c12 = g01 * g02 - g00 * g12, c22 = g00 * g11 - g01 * g01;
    const double s = A / det;
    for (int i = 0; i < 3; ++i) {
      const double t0 = T[3 * i], t1 = T[3 * i + 1], t2 = T[3 * i + 2];
      dT[3 * i] = s * (t0 * c00 + t1 * c01 + t2 * c02);
      dT[3 * i + 1] = s * (t0 * c01 + t1 * c11 + t2 * c12);
      dT[3 * i + 2] = s * (t0 * c02 + t1 * c12 + t2 * c22);
    }
  }
  return A;
}

// Energy term of one tet (lifted content + det T/6, a constant shift for a fixed boundary) and its
// ∂/∂T; *nonpositive is set when the double edge determinant is not negative (not VOLMAP-positive).
inline double tet_term(const double* x, const std::uint32_t* tet, const double* rest_gram, double* grad12, bool* nonpositive) {
  double T[9], dT[9];
  edge_matrix(x, tet, T);
  const double d = det3(T);
  *nonpositive = !(d < 0);
  const double e = lifted_content(T, rest_gram, dT) + d * kSixth;
  // + ∂(det T/6)/∂T via the cofactors of T.
  dT[0] += (T[4] * T[8] - T[5] * T[7]) * kSixth;
  dT[1] += (T[5] * T[6] - T[3] * T[8]) * kSixth;
  dT[2] += (T[3] * T[7] - T[4] * T[6]) * kSixth;
  dT[3] += (T[2] * T[7] - T[1] * T[8]) * kSixth;
  dT[4] += (T[0] * T[8] - T[2] * T[6]) * kSixth;
  dT[5] += (T[1] * T[6] - T[0] * T[7]) * kSixth;
  dT[6] += (T[1] * T[5] - T[2] * T[4]) * kSixth;
  dT[7] += (T[2] * T[3] - T[0] * T[5]) * kSixth;
  dT[8] += (T[0] * T[4] - T[1] * T[3]) * kSixth;
  untangle::edge_gradient_to_vertices(dT, grad12);
  return e;
}

// Per-tet data of the TLC energy in the scaled frame. The Tutte form's rest Gram is one matrix for
// every tet (rest_stride 0); the rest-shape form stores one per tet (rest_stride 9).
struct TlcProblem {
  std::size_t nt = 0;
  const std::vector<std::uint32_t>& tets;
  untangle::FreeVertexLayout layout;
  untangle::BoxFrame frame;
  std::vector<double> rest_gram;  // already multiplied by a
  std::size_t rest_stride = 9;
  std::vector<double> x;          // scaled full coordinates
  std::vector<double> tet_grad;   // 12 per tet (parallel evaluation only)
  std::vector<double> tet_energy;

  explicit TlcProblem(const std::vector<std::uint32_t>& t) : tets(t) {}

  // Lifted content minus signed content; returns in *bad the number of tets whose double edge
  // determinant is not negative. One thread: tets in order, gradients added straight into the
  // free vertices' entries. Several: per-tet terms in parallel, then each vertex gathers its tets
  // in the same ascending order — the same sums in the same order, so both give identical bits.
  double evaluate(const double* vars, double* grad, std::size_t* bad) {
    layout.load(vars, x.data());
    if (untangle::single_thread()) return evaluate_in_order(grad, bad);
    return evaluate_in_parallel(grad, bad);
  }

  double evaluate_in_order(double* grad, std::size_t* bad) {
    if (grad) std::fill(grad, grad + layout.num_variables(), 0.0);
    double e = 0, g[12];
    std::size_t nonpositive = 0;
    for (std::size_t t = 0; t < nt; ++t) {
      const std::uint32_t* tet = &tets[4 * t];
      bool np = false;
      e += tet_term(x.data(), tet, &rest_gram[rest_stride * t], g, &np);
      nonpositive += np;
      if (!grad) continue;
      for (int j = 0; j < 4; ++j) {
        const std::int64_t b = layout.free_index[tet[j]];
        if (b < 0) continue;
        for (int i = 0; i < 3; ++i) grad[3 * b + i] += g[3 * j + i];
      }
    }
    *bad = nonpositive;
    return e;
  }

  double evaluate_in_parallel(double* grad, std::size_t* bad) {
    tet_grad.resize(12 * nt);
    tet_energy.resize(nt);
    std::atomic<std::size_t> nonpositive{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nt, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
      std::size_t local_bad = 0;
      for (std::size_t t = r.begin(); t < r.end(); ++t) {
        bool np = false;
        tet_energy[t] = tet_term(x.data(), &tets[4 * t], &rest_gram[rest_stride * t], &tet_grad[12 * t], &np);
        local_bad += np;
      }
      if (local_bad > 0) nonpositive.fetch_add(local_bad, std::memory_order_relaxed);
    });
    double e = 0;
    for (std::size_t t = 0; t < nt; ++t) e += tet_energy[t];
    if (grad) layout.gather(tet_grad.data(), grad);
    *bad = nonpositive.load(std::memory_order_relaxed);
    return e;
  }
};

}  // namespace

double tlc_lifted_content(const double* T, const double* a_rest_gram, double* dT) { return lifted_content(T, a_rest_gram, dT); }

TlcResult tlc_untangle(const std::vector<double>& source_xyz, const std::vector<std::uint32_t>& tets,
                       const std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                       const TlcOptions& options) {
  const TimeBudget budget(options.time_limit_seconds);
  TlcResult result;
  TlcProblem p(tets);
  const std::size_t nv = target_xyz.size() / 3;
  p.nt = tets.size() / 4;
  if (source_xyz.size() != target_xyz.size() || locked.size() != nv) throw Error(ErrorKind::BadInput, "", 0, "tlc: inconsistent array sizes");
  untangle::GuardedObjective obj;
  auto done = [&] {
    result.nonpositive = count_nonpositive(target_xyz, tets);
    result.certified = result.nonpositive == 0;
    result.evaluations = obj.evaluations;
    result.seconds = budget.elapsed();
    return result;
  };
  if (count_nonpositive(target_xyz, tets) == 0) return done();
  p.layout.build(nv, tets, locked);
  if (p.layout.free_vertices.empty()) return done();
  p.frame.fit(target_xyz, 10.0, "tlc");
  p.x = p.frame.to_scaled(target_xyz);
  const double signed_volume = signed_volume_sum(p.x.data(), tets);
  double rest_measure = 0;
  double T[9];
  p.rest_stride = options.tutte_form ? 0 : 9;
  p.rest_gram.resize(options.tutte_form ? 9 : 9 * p.nt);
  if (options.tutte_form) {
    rest_measure = double(p.nt) * std::sqrt(2.0) / 12.0;
  } else {
    for (std::size_t t = 0; t < p.nt; ++t) {
      edge_matrix(source_xyz.data(), &tets[4 * t], T);
      rest_measure += std::abs(det3(T)) / 6.0;
    }
  }
  const double alpha = options.alpha_ratio * std::abs(signed_volume) / rest_measure;
  const double a = std::cbrt(alpha * alpha);
  if (options.tutte_form) {
    // Unit regular simplex: Gram of edges from vertex 0: 1 on the diagonal, 1/2 off it.
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l) p.rest_gram[3 * k + l] = a * (k == l ? 1.0 : 0.5);
  } else {
    for (std::size_t t = 0; t < p.nt; ++t) {
      double* Gr = &p.rest_gram[9 * t];
      edge_matrix(source_xyz.data(), &tets[4 * t], T);
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) Gr[3 * k + l] = a * (T[k] * T[l] + T[3 + k] * T[3 + l] + T[6 + k] * T[6 + l]);
    }
  }
  std::vector<double> candidate = target_xyz;
  obj.evaluate = [&](const double* vars, double* grad, bool* all_positive) {
    const double e = p.evaluate(vars, grad, &obj.double_nonpositive);
    *all_positive = obj.double_nonpositive == 0;
    return e;
  };
  obj.stall_evaluations = options.stall_evaluations;
  obj.stall_max_bad = options.stall_max_bad;
  std::vector<double> finished_map;
  if (options.finish && options.finish_max_bad > 0) {
    obj.finish_max_bad = options.finish_max_bad;
    obj.try_finish = [&](const double* vars) {
      finished_map = target_xyz;
      p.frame.write_back(p.layout, vars, finished_map);
      return options.finish(finished_map);
    };
  }
  obj.layout = &p.layout;
  obj.frame = &p.frame;
  obj.tets = &tets;
  obj.candidate = &candidate;
  obj.budget = budget;
  Eigen::VectorXd vars(Eigen::Index(p.layout.num_variables()));
  p.layout.extract(p.x.data(), vars.data());
  LBFGSpp::LBFGSParam<double> param = untangle::lbfgs_param(1, 1e-8, options.ftol, LBFGSpp::LBFGS_LINESEARCH_BACKTRACKING_STRONG_WOLFE);
  param.epsilon_rel = 1e-8;
  try {
    // Restart L-BFGS after line-search failures until the evaluation budget is spent.
    while (obj.evaluations < options.max_evaluations) {
      param.max_iterations = int(std::max<long>(1, options.max_evaluations - obj.evaluations));
      const long before = obj.evaluations;
      LBFGSpp::LBFGSSolver<double, LBFGSpp::LineSearchNocedalWright> solver(param);
      if (untangle::run_lbfgs(solver, obj, vars) >= 0) break;  // converged (relative energy test) without certification
      if (obj.evaluations - before <= 2) break;
    }
  } catch (const untangle::CertifiedStop&) {
    vars = obj.last_x;
  } catch (const untangle::TimeStop&) {
    vars = obj.last_x;
    result.timed_out = true;
  } catch (const untangle::StallStop&) {
    vars = obj.last_x;
    result.stalled = true;
  } catch (const untangle::FinishedStop&) {
    target_xyz.swap(finished_map);
    result.finished = true;
    return done();
  }
  p.frame.write_back(p.layout, vars.data(), target_xyz);
  return done();
}

}  // namespace volmap
