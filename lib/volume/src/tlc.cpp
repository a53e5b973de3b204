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

// Per-tet data of the TLC energy in the scaled frame.
struct TlcProblem {
  std::size_t nt = 0;
  const std::vector<std::uint32_t>& tets;
  untangle::FreeVertexLayout layout;
  untangle::BoxFrame frame;
  std::vector<double> rest_gram;  // 9 per tet (already multiplied by a)
  std::vector<double> x;          // scaled full coordinates
  std::vector<double> tet_grad;   // 12 per tet
  std::vector<double> tet_energy;

  explicit TlcProblem(const std::vector<std::uint32_t>& t) : tets(t) {}

  // Lifted content minus signed content (a constant shift for a fixed boundary); returns in *bad the
  // number of tets whose double edge determinant is not negative (not VOLMAP-positive).
  double evaluate(const double* vars, double* grad, std::size_t* bad) {
    layout.load(vars, x.data());
    std::atomic<std::size_t> nonpositive{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nt, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
      double T[9], dT[9];
      std::size_t local_bad = 0;
      for (std::size_t t = r.begin(); t < r.end(); ++t) {
        edge_matrix(x.data(), &tets[4 * t], T);
        const double d = det3(T);
        if (!(d < 0)) ++local_bad;
        tet_energy[t] = tlc_lifted_content(T, &rest_gram[9 * t], dT) + d / 6.0;
        // + ∂(det T/6)/∂T via the cofactors of T.
        dT[0] += (T[4] * T[8] - T[5] * T[7]) / 6.0;
        dT[1] += (T[5] * T[6] - T[3] * T[8]) / 6.0;
        dT[2] += (T[3] * T[7] - T[4] * T[6]) / 6.0;
        dT[3] += (T[2] * T[7] - T[1] * T[8]) / 6.0;
        dT[4] += (T[0] * T[8] - T[2] * T[6]) / 6.0;
        dT[5] += (T[1] * T[6] - T[0] * T[7]) / 6.0;
        dT[6] += (T[1] * T[5] - T[2] * T[4]) / 6.0;
        dT[7] += (T[2] * T[3] - T[0] * T[5]) / 6.0;
        dT[8] += (T[0] * T[4] - T[1] * T[3]) / 6.0;
        untangle::edge_gradient_to_vertices(dT, &tet_grad[12 * t]);
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

double tlc_lifted_content(const double* T, const double* a_rest_gram, double* dT) {
  // G = TᵀT + a·G_rest; A = √det G / 6; ∂A/∂T = A·T·G⁻¹.
  double G[9];
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) G[3 * k + l] = T[k] * T[l] + T[3 + k] * T[3 + l] + T[6 + k] * T[6 + l] + a_rest_gram[3 * k + l];
  const double c00 = G[4] * G[8] - G[5] * G[7], c01 = G[5] * G[6] - G[3] * G[8], c02 = G[3] * G[7] - G[4] * G[6];
  const double det = G[0] * c00 + G[1] * c01 + G[2] * c02;
  const double A = std::sqrt(std::max(det, 0.0)) / 6.0;
  if (dT) {
    if (!(det > 0)) {
      std::fill(dT, dT + 9, 0.0);
      return A;
    }
    double Gi[9];
    const double id = 1.0 / det;
    Gi[0] = c00 * id;
    Gi[1] = (G[2] * G[7] - G[1] * G[8]) * id;
    Gi[2] = (G[1] * G[5] - G[2] * G[4]) * id;
    Gi[3] = c01 * id;
    Gi[4] = (G[0] * G[8] - G[2] * G[6]) * id;
    Gi[5] = (G[2] * G[3] - G[0] * G[5]) * id;
    Gi[6] = c02 * id;
    Gi[7] = (G[1] * G[6] - G[0] * G[7]) * id;
    Gi[8] = (G[0] * G[4] - G[1] * G[3]) * id;
    for (int i = 0; i < 3; ++i)
      for (int l = 0; l < 3; ++l) dT[3 * i + l] = A * (T[3 * i] * Gi[l] + T[3 * i + 1] * Gi[3 + l] + T[3 * i + 2] * Gi[6 + l]);
  }
  return A;
}

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
  auto finish = [&] {
    result.nonpositive = count_nonpositive(target_xyz, tets);
    result.certified = result.nonpositive == 0;
    result.evaluations = obj.evaluations;
    result.seconds = budget.elapsed();
    return result;
  };
  if (count_nonpositive(target_xyz, tets) == 0) return finish();
  p.layout.build(nv, tets, locked);
  if (p.layout.free_vertices.empty()) return finish();
  p.frame.fit(target_xyz, 10.0, "tlc");
  p.x = p.frame.to_scaled(target_xyz);
  const double signed_volume = signed_volume_sum(p.x.data(), tets);
  double rest_measure = 0;
  double T[9];
  p.rest_gram.resize(9 * p.nt);
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
  for (std::size_t t = 0; t < p.nt; ++t) {
    double* Gr = &p.rest_gram[9 * t];
    if (options.tutte_form) {
      // Unit regular simplex: Gram of edges from vertex 0: 1 on the diagonal, 1/2 off it.
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) Gr[3 * k + l] = a * (k == l ? 1.0 : 0.5);
    } else {
      edge_matrix(source_xyz.data(), &tets[4 * t], T);
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) Gr[3 * k + l] = a * (T[k] * T[l] + T[3 + k] * T[3 + l] + T[6 + k] * T[6 + l]);
    }
  }
  p.tet_grad.resize(12 * p.nt);
  p.tet_energy.resize(p.nt);
  std::vector<double> candidate = target_xyz;
  obj.evaluate = [&](const double* vars, double* grad, bool* all_positive) {
    const double e = p.evaluate(vars, grad, &obj.double_nonpositive);
    *all_positive = obj.double_nonpositive == 0;
    return e;
  };
  obj.stall_evaluations = options.stall_evaluations;
  obj.stall_max_bad = options.stall_max_bad;
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
  }
  p.frame.write_back(p.layout, vars.data(), target_xyz);
  return finish();
}

}  // namespace volmap
