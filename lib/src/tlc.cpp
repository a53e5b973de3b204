// tlc.cpp — Total Lifted Content (Du et al. 2020) from docs/mapping.md §6; see volmap/tlc.hpp.
// Edge matrices row-major: T[3*i+k] = coordinate i of edge k (x_{k+1} − x_0).
#include <volmap/tlc.hpp>

#include <volmap/error.hpp>
#include <volmap/predicates.hpp>

#include <LBFGS.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace volmap {

namespace {
using Clock = std::chrono::steady_clock;

std::size_t exact_nonpositive(const std::vector<double>& xyz, const std::vector<std::uint32_t>& tets) {
  const TetSignCounts c = orient3d_tets(xyz.data(), xyz.size() / 3, tets.data(), tets.size() / 4, nullptr);
  if (!c.ok) return tets.size() / 4;
  return c.zero + c.negative;
}

inline void edge_matrix(const double* x, const std::uint32_t* t, double* T) {
  const double* p0 = x + 3 * std::size_t(t[0]);
  for (int k = 0; k < 3; ++k) {
    const double* pk = x + 3 * std::size_t(t[k + 1]);
    for (int i = 0; i < 3; ++i) T[3 * i + k] = pk[i] - p0[i];
  }
}

struct CertifiedStop {};
struct TimeStop {};

struct TlcProblem {
  std::size_t nv = 0, nt = 0;
  const std::vector<std::uint32_t>& tets;
  std::vector<std::uint32_t> free_vertices;
  std::vector<std::int64_t> free_index;
  std::vector<double> rest_gram;  // 9 per tet (already multiplied by a)
  std::vector<double> x;          // scaled full coordinates
  std::vector<double> tet_grad;   // 12 per tet
  std::vector<double> tet_energy;
  std::vector<std::uint32_t> adj_offset, adj_slot;
  double center[3] = {0, 0, 0};
  double scale = 1;
  // Exact stop / time limit.
  const std::vector<std::uint8_t>* locked = nullptr;
  std::vector<double>* candidate = nullptr;
  Clock::time_point deadline;
  bool has_deadline = false;
  long evaluations = 0;
  long next_check = 0;
  Eigen::VectorXd stop_x;

  explicit TlcProblem(const std::vector<std::uint32_t>& t) : tets(t) {}

  void write_back(const double* vars, std::vector<double>& out) const {
    for (std::size_t b = 0; b < free_vertices.size(); ++b)
      for (int i = 0; i < 3; ++i) out[3 * std::size_t(free_vertices[b]) + i] = vars[3 * b + i] / scale + center[i];
  }

  double operator()(const Eigen::VectorXd& vars, Eigen::VectorXd& grad) {
    ++evaluations;
    if (has_deadline && Clock::now() > deadline) {
      stop_x = vars;
      throw TimeStop{};
    }
    for (std::size_t b = 0; b < free_vertices.size(); ++b)
      for (int i = 0; i < 3; ++i) x[3 * std::size_t(free_vertices[b]) + i] = vars[Eigen::Index(3 * b + i)];
    bool all_positive = true;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nt, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
      double T[9], dT[9];
      bool local_pos = true;
      for (std::size_t t = r.begin(); t < r.end(); ++t) {
        edge_matrix(x.data(), &tets[4 * t], T);
        const double d = T[0] * (T[4] * T[8] - T[5] * T[7]) - T[1] * (T[3] * T[8] - T[5] * T[6]) + T[2] * (T[3] * T[7] - T[4] * T[6]);
        if (!(d < 0)) local_pos = false;
        // Lifted content minus signed content (constant shift for a fixed boundary).
        tet_energy[t] = tlc_lifted_content(T, &rest_gram[9 * t], dT) + d / 6.0;
        double* out = &tet_grad[12 * t];
        for (int i = 0; i < 3; ++i) {
          out[i] = -(dT[3 * i] + dT[3 * i + 1] + dT[3 * i + 2]);
          for (int k = 0; k < 3; ++k) out[3 * (k + 1) + i] = dT[3 * i + k];
        }
        // + ∂(det T/6)/∂x via the cofactors of T.
        double C[9];
        C[0] = T[4] * T[8] - T[5] * T[7];
        C[1] = T[5] * T[6] - T[3] * T[8];
        C[2] = T[3] * T[7] - T[4] * T[6];
        C[3] = T[2] * T[7] - T[1] * T[8];
        C[4] = T[0] * T[8] - T[2] * T[6];
        C[5] = T[1] * T[6] - T[0] * T[7];
        C[6] = T[1] * T[5] - T[2] * T[4];
        C[7] = T[2] * T[3] - T[0] * T[5];
        C[8] = T[0] * T[4] - T[1] * T[3];
        for (int i = 0; i < 3; ++i)
          for (int k = 0; k < 3; ++k) {
            const double c = C[3 * i + k] / 6.0;  // ∂det/∂T_ik
            out[3 * (k + 1) + i] += c;
            out[i] -= c;
          }
      }
      if (!local_pos) all_positive = false;  // benign race: only ever set to false
    });
    double e = 0;
    for (std::size_t t = 0; t < nt; ++t) e += tet_energy[t];
    for (std::size_t b = 0; b < free_vertices.size(); ++b) {
      double g[3] = {0, 0, 0};
      for (std::uint32_t k = adj_offset[b]; k < adj_offset[b + 1]; ++k) {
        const std::uint32_t s = adj_slot[k];
        const double* src = &tet_grad[12 * std::size_t(s / 4) + 3 * std::size_t(s % 4)];
        for (int i = 0; i < 3; ++i) g[i] += src[i];
      }
      for (int i = 0; i < 3; ++i) grad[Eigen::Index(3 * b + i)] = g[i];
    }
    if (all_positive && evaluations >= next_check) {
      write_back(vars.data(), *candidate);
      if (exact_nonpositive(*candidate, tets) == 0) {
        stop_x = vars;
        throw CertifiedStop{};
      }
      next_check = evaluations + 10;
    }
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
  const auto start = Clock::now();
  TlcResult result;
  TlcProblem p(tets);
  p.nv = target_xyz.size() / 3;
  p.nt = tets.size() / 4;
  if (source_xyz.size() != target_xyz.size() || locked.size() != p.nv) throw Error(ErrorKind::BadInput, "", 0, "tlc: inconsistent array sizes");
  auto finish = [&] {
    result.nonpositive = exact_nonpositive(target_xyz, tets);
    result.certified = result.nonpositive == 0;
    result.evaluations = p.evaluations;
    result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return result;
  };
  if (exact_nonpositive(target_xyz, tets) == 0) return finish();
  p.free_index.assign(p.nv, -1);
  for (std::size_t v = 0; v < p.nv; ++v)
    if (!locked[v]) {
      p.free_index[v] = std::int64_t(p.free_vertices.size());
      p.free_vertices.push_back(std::uint32_t(v));
    }
  if (p.free_vertices.empty()) return finish();
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (std::size_t v = 0; v < p.nv; ++v)
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], target_xyz[3 * v + i]);
      hi[i] = std::max(hi[i], target_xyz[3 * v + i]);
    }
  double extent = 0;
  for (int i = 0; i < 3; ++i) {
    p.center[i] = 0.5 * (lo[i] + hi[i]);
    extent = std::max(extent, hi[i] - lo[i]);
  }
  if (!(extent > 0)) throw Error(ErrorKind::BadInput, "", 0, "tlc: degenerate target");
  p.scale = 10.0 / extent;
  p.x.resize(3 * p.nv);
  for (std::size_t v = 0; v < p.nv; ++v)
    for (int i = 0; i < 3; ++i) p.x[3 * v + i] = (target_xyz[3 * v + i] - p.center[i]) * p.scale;
  double signed_volume = 0, rest_measure = 0;
  double T[9];
  for (std::size_t t = 0; t < p.nt; ++t) {
    edge_matrix(p.x.data(), &tets[4 * t], T);
    signed_volume += -(T[0] * (T[4] * T[8] - T[5] * T[7]) - T[1] * (T[3] * T[8] - T[5] * T[6]) + T[2] * (T[3] * T[7] - T[4] * T[6])) / 6.0;
  }
  p.rest_gram.resize(9 * p.nt);
  if (options.tutte_form) {
    rest_measure = double(p.nt) * std::sqrt(2.0) / 12.0;
  } else {
    for (std::size_t t = 0; t < p.nt; ++t) {
      edge_matrix(source_xyz.data(), &tets[4 * t], T);
      rest_measure += std::abs(T[0] * (T[4] * T[8] - T[5] * T[7]) - T[1] * (T[3] * T[8] - T[5] * T[6]) + T[2] * (T[3] * T[7] - T[4] * T[6])) / 6.0;
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
  const std::size_t nf = p.free_vertices.size();
  p.adj_offset.assign(nf + 1, 0);
  for (std::size_t s = 0; s < 4 * p.nt; ++s)
    if (p.free_index[tets[s]] >= 0) ++p.adj_offset[std::size_t(p.free_index[tets[s]]) + 1];
  for (std::size_t b = 0; b < nf; ++b) p.adj_offset[b + 1] += p.adj_offset[b];
  p.adj_slot.resize(p.adj_offset[nf]);
  {
    std::vector<std::uint32_t> fill(p.adj_offset.begin(), p.adj_offset.end() - 1);
    for (std::size_t s = 0; s < 4 * p.nt; ++s)
      if (p.free_index[tets[s]] >= 0) p.adj_slot[fill[std::size_t(p.free_index[tets[s]])]++] = std::uint32_t(s);
  }
  p.tet_grad.resize(12 * p.nt);
  p.tet_energy.resize(p.nt);
  std::vector<double> candidate = target_xyz;
  p.candidate = &candidate;
  if (options.time_limit_seconds > 0) {
    p.has_deadline = true;
    p.deadline = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(options.time_limit_seconds));
  }
  Eigen::VectorXd vars(Eigen::Index(3 * nf));
  for (std::size_t b = 0; b < nf; ++b)
    for (int i = 0; i < 3; ++i) vars[Eigen::Index(3 * b + i)] = p.x[3 * std::size_t(p.free_vertices[b]) + i];
  LBFGSpp::LBFGSParam<double> param;
  param.m = 7;
  param.epsilon = 1e-8;
  param.epsilon_rel = 1e-8;
  param.past = 1;
  param.delta = options.ftol;
  param.max_linesearch = 40;
  param.linesearch = LBFGSpp::LBFGS_LINESEARCH_BACKTRACKING_STRONG_WOLFE;
  try {
    // Restart L-BFGS after line-search failures until the evaluation budget is spent.
    while (p.evaluations < options.max_evaluations) {
      param.max_iterations = int(std::max<long>(1, options.max_evaluations - p.evaluations));
      double fx = 0;
      const long before = p.evaluations;
      LBFGSpp::LBFGSSolver<double, LBFGSpp::LineSearchNocedalWright> solver(param);
      try {
        solver.minimize(p, vars, fx);
        break;  // converged (relative energy test) without certification
      } catch (const std::runtime_error&) {
      } catch (const std::logic_error&) {
      }
      if (p.evaluations - before <= 2) break;
    }
  } catch (const CertifiedStop&) {
    vars = p.stop_x;
  } catch (const TimeStop&) {
    vars = p.stop_x;
    result.timed_out = true;
  }
  p.write_back(vars.data(), target_xyz);
  return finish();
}

}  // namespace volmap
