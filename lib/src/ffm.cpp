// ffm.cpp — FFM untangler (Garanzha et al. 2021), re-implemented from docs/mapping.md §5.
// Conventions: see volmap/ffm.hpp. Edge matrices are stored row-major: T[3*i+k] = coordinate i of
// edge k (edge k = x_{k+1} − x_0). J = T·M with M = R⁻¹. A VOLMAP-positive tet has det T < 0 and
// every reference R has det R < 0, hence D = det J > 0 for positive target tets.
#include <volmap/ffm.hpp>

#include <volmap/error.hpp>
#include <volmap/predicates.hpp>

#include <LBFGS.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace volmap {

double ffm_chi(double D, double eps) {
  const double s = std::sqrt(eps * eps + D * D);
  if (D >= 0) return 0.5 * (D + s);
  return eps * eps / (2.0 * (s - D));  // = (D + s)/2 without cancellation
}

double ffm_chi_derivative(double D, double eps) {
  const double s = std::sqrt(eps * eps + D * D);
  if (D >= 0) return 0.5 + D / (2.0 * s);
  return eps * eps / (2.0 * s * (s - D));  // = (s + D)/(2s) without cancellation
}

namespace {

using Clock = std::chrono::steady_clock;

inline double det3(const double* A) {
  return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
         A[2] * (A[3] * A[7] - A[4] * A[6]);
}

// Inverse of a row-major 3x3 matrix; returns false when singular.
inline bool inverse3(const double* A, double* inv) {
  const double d = det3(A);
  if (!(std::abs(d) > 0) || !std::isfinite(d)) return false;
  const double id = 1.0 / d;
  inv[0] = (A[4] * A[8] - A[5] * A[7]) * id;
  inv[1] = (A[2] * A[7] - A[1] * A[8]) * id;
  inv[2] = (A[1] * A[5] - A[2] * A[4]) * id;
  inv[3] = (A[5] * A[6] - A[3] * A[8]) * id;
  inv[4] = (A[0] * A[8] - A[2] * A[6]) * id;
  inv[5] = (A[2] * A[3] - A[0] * A[5]) * id;
  inv[6] = (A[3] * A[7] - A[4] * A[6]) * id;
  inv[7] = (A[1] * A[6] - A[0] * A[7]) * id;
  inv[8] = (A[0] * A[4] - A[1] * A[3]) * id;
  return true;
}

inline void edge_matrix(const double* x, const std::uint32_t* t, double* T) {
  const double* p0 = x + 3 * std::size_t(t[0]);
  for (int k = 0; k < 3; ++k) {
    const double* pk = x + 3 * std::size_t(t[k + 1]);
    for (int i = 0; i < 3; ++i) T[3 * i + k] = pk[i] - p0[i];
  }
}

inline void matmul3(const double* A, const double* B, double* C) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
}

std::size_t exact_nonpositive(const std::vector<double>& xyz, const std::vector<std::uint32_t>& tets) {
  const TetSignCounts c = orient3d_tets(xyz.data(), xyz.size() / 3, tets.data(), tets.size() / 4, nullptr);
  if (!c.ok) return tets.size() / 4;
  return c.zero + c.negative;
}

}  // namespace

struct FfmEnergy::Impl {
  std::size_t nv = 0, nt = 0;
  std::vector<std::uint32_t> tets;
  std::vector<std::int64_t> free_index;      // per vertex: variable block or -1
  std::vector<std::uint32_t> free_vertices;  // variable block -> vertex
  double center[3] = {0, 0, 0};
  double scale = 1;
  double theta = 0.5;
  std::vector<double> M;       // 9 per tet: R⁻¹
  std::vector<double> weight;  // per tet: vol_ref
  // Work buffers (evaluation is not re-entrant).
  mutable std::vector<double> x;          // 3*nv scaled positions
  mutable std::vector<double> tet_grad;   // 12 per tet
  mutable std::vector<double> tet_energy; // per tet
  mutable std::vector<double> tet_det;    // per tet
  // CSR: free vertex block -> incident (tet*4+local) slots.
  std::vector<std::uint32_t> adj_offset;
  std::vector<std::uint32_t> adj_slot;

  void load(const double* vars) const {
    const std::size_t nf = free_vertices.size();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nf, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t b = r.begin(); b < r.end(); ++b) {
        double* p = &x[3 * std::size_t(free_vertices[b])];
        p[0] = vars[3 * b];
        p[1] = vars[3 * b + 1];
        p[2] = vars[3 * b + 2];
      }
    });
  }
};

FfmEnergy::FfmEnergy(const std::vector<double>& source_xyz, const std::vector<std::uint32_t>& tets,
                     const std::vector<std::uint8_t>& locked, const std::vector<double>& target_xyz,
                     ReferenceShape reference, double theta)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.nv = target_xyz.size() / 3;
  m.nt = tets.size() / 4;
  m.theta = theta;
  if (source_xyz.size() != target_xyz.size() || locked.size() != m.nv || tets.size() % 4 != 0)
    throw Error(ErrorKind::BadInput, "", 0, "ffm: inconsistent array sizes");
  for (std::uint32_t v : tets)
    if (v >= m.nv) throw Error(ErrorKind::BadInput, "", 0, "ffm: tet vertex id out of range");
  m.tets = tets;
  m.free_index.assign(m.nv, -1);
  for (std::size_t v = 0; v < m.nv; ++v)
    if (!locked[v]) {
      m.free_index[v] = std::int64_t(m.free_vertices.size());
      m.free_vertices.push_back(std::uint32_t(v));
    }
  // Scale the target into a box of side 10.
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (std::size_t v = 0; v < m.nv; ++v)
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], target_xyz[3 * v + i]);
      hi[i] = std::max(hi[i], target_xyz[3 * v + i]);
    }
  double extent = 0;
  for (int i = 0; i < 3; ++i) {
    m.center[i] = 0.5 * (lo[i] + hi[i]);
    extent = std::max(extent, hi[i] - lo[i]);
  }
  if (!(extent > 0) || !std::isfinite(extent)) throw Error(ErrorKind::BadInput, "", 0, "ffm: degenerate or non-finite target");
  m.scale = 10.0 / extent;
  m.x.resize(3 * m.nv);
  for (std::size_t v = 0; v < m.nv; ++v)
    for (int i = 0; i < 3; ++i) m.x[3 * v + i] = (target_xyz[3 * v + i] - m.center[i]) * m.scale;

  // vol(D): with a fixed boundary, Σ signed target volume is the domain volume.
  double domain_volume = 0, source_volume = 0;
  double T[9];
  for (std::size_t t = 0; t < m.nt; ++t) {
    edge_matrix(m.x.data(), &tets[4 * t], T);
    domain_volume += -det3(T) / 6.0;
    edge_matrix(source_xyz.data(), &tets[4 * t], T);
    source_volume += -det3(T) / 6.0;
  }
  if (!(domain_volume > 0)) throw Error(ErrorKind::BadInput, "", 0, "ffm: the boundary map encloses a non-positive volume (mirrored map?)");
  if (!(source_volume > 0)) throw Error(ErrorKind::BadInput, "", 0, "ffm: the source mesh has non-positive total volume");

  m.M.resize(9 * m.nt);
  m.weight.resize(m.nt);
  if (reference == ReferenceShape::RegularTet) {
    // Mirrored regular tet (1,1,1),(1,−1,−1),(−1,1,−1),(−1,−1,1): edge determinant −16, like VOLMAP tets.
    const double v = domain_volume / double(m.nt);
    const double s = std::cbrt(6.0 * v / 16.0);
    const double R[9] = {0, -2 * s, -2 * s, -2 * s, 0, -2 * s, -2 * s, -2 * s, 0};
    double Minv[9];
    inverse3(R, Minv);
    for (std::size_t t = 0; t < m.nt; ++t) {
      std::copy(Minv, Minv + 9, &m.M[9 * t]);
      m.weight[t] = v;
    }
  } else {
    const double c = std::cbrt(domain_volume / source_volume);
    for (std::size_t t = 0; t < m.nt; ++t) {
      edge_matrix(source_xyz.data(), &tets[4 * t], T);
      for (double& e : T) e *= c;
      const double d = det3(T);
      if (!(d < 0) || !inverse3(T, &m.M[9 * t]))
        throw Error(ErrorKind::BadInput, "", 0, "ffm: source tet " + std::to_string(t) + " is degenerate or inverted (rest shape unusable)");
      m.weight[t] = -d / 6.0;
    }
  }

  // Adjacency of free vertices.
  const std::size_t nf = m.free_vertices.size();
  m.adj_offset.assign(nf + 1, 0);
  for (std::size_t s = 0; s < 4 * m.nt; ++s) {
    const std::int64_t b = m.free_index[tets[s]];
    if (b >= 0) ++m.adj_offset[std::size_t(b) + 1];
  }
  for (std::size_t b = 0; b < nf; ++b) m.adj_offset[b + 1] += m.adj_offset[b];
  m.adj_slot.resize(m.adj_offset[nf]);
  std::vector<std::uint32_t> fill(m.adj_offset.begin(), m.adj_offset.end() - 1);
  for (std::size_t s = 0; s < 4 * m.nt; ++s) {
    const std::int64_t b = m.free_index[tets[s]];
    if (b >= 0) m.adj_slot[fill[std::size_t(b)]++] = std::uint32_t(s);
  }
  m.tet_grad.resize(12 * m.nt);
  m.tet_energy.resize(m.nt);
  m.tet_det.resize(m.nt);
}

FfmEnergy::~FfmEnergy() = default;

std::size_t FfmEnergy::num_variables() const { return 3 * impl_->free_vertices.size(); }

std::vector<double> FfmEnergy::initial_variables() const {
  const Impl& m = *impl_;
  std::vector<double> vars(num_variables());
  for (std::size_t b = 0; b < m.free_vertices.size(); ++b)
    for (int i = 0; i < 3; ++i) vars[3 * b + i] = m.x[3 * std::size_t(m.free_vertices[b]) + i];
  return vars;
}

void FfmEnergy::write_back(const double* vars, std::vector<double>& target_xyz) const {
  const Impl& m = *impl_;
  const double inv = 1.0 / m.scale;
  for (std::size_t b = 0; b < m.free_vertices.size(); ++b)
    for (int i = 0; i < 3; ++i) target_xyz[3 * std::size_t(m.free_vertices[b]) + i] = vars[3 * b + i] * inv + m.center[i];
}

double FfmEnergy::min_det(const double* vars) const {
  const Impl& m = *impl_;
  m.load(vars);
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, m.nt, 2048), std::numeric_limits<double>::infinity(),
      [&](const tbb::blocked_range<std::size_t>& r, double acc) {
        double T[9], J[9];
        for (std::size_t t = r.begin(); t < r.end(); ++t) {
          edge_matrix(m.x.data(), &m.tets[4 * t], T);
          matmul3(T, &m.M[9 * t], J);
          acc = std::min(acc, det3(J));
        }
        return acc;
      },
      [](double a, double b) { return std::min(a, b); });
}

double FfmEnergy::evaluate(const double* vars, double eps, double* grad) const {
  const Impl& m = *impl_;
  m.load(vars);
  const double theta = m.theta;
  const bool want_grad = grad != nullptr;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.nt, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    double T[9], J[9], C[9], G[9], GT[9];
    for (std::size_t t = r.begin(); t < r.end(); ++t) {
      const double* Mt = &m.M[9 * t];
      edge_matrix(m.x.data(), &m.tets[4 * t], T);
      matmul3(T, Mt, J);
      // Cofactor matrix C = ∂D/∂J: columns b×c, c×a, a×b for J = [a|b|c].
      C[0] = J[4] * J[8] - J[7] * J[5];
      C[3] = J[7] * J[2] - J[1] * J[8];
      C[6] = J[1] * J[5] - J[4] * J[2];
      C[1] = J[5] * J[6] - J[8] * J[3];
      C[4] = J[8] * J[0] - J[2] * J[6];
      C[7] = J[2] * J[3] - J[5] * J[0];
      C[2] = J[3] * J[7] - J[6] * J[4];
      C[5] = J[6] * J[1] - J[0] * J[7];
      C[8] = J[0] * J[4] - J[3] * J[1];
      const double D = J[0] * C[0] + J[3] * C[3] + J[6] * C[6];
      const double chi = ffm_chi(D, eps);
      const double chi_d = ffm_chi_derivative(D, eps);
      const double chi23 = std::cbrt(chi * chi);
      double trace = 0;
      for (int i = 0; i < 9; ++i) trace += J[i] * J[i];
      const double f = trace / chi23;
      const double g = (1.0 + D * D) / chi;
      const double w = m.weight[t];
      m.tet_energy[t] = w * ((1.0 - theta) * f + theta * g);
      m.tet_det[t] = D;
      if (!want_grad) continue;
      const double a = w * (1.0 - theta) * 2.0 / chi23;
      const double b = w * ((1.0 - theta) * (-2.0 / 3.0) * f * chi_d / chi + theta * (2.0 * D - g * chi_d) / chi);
      for (int i = 0; i < 9; ++i) G[i] = a * J[i] + b * C[i];
      // ∂E/∂T = G·Mᵀ.
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) GT[3 * i + k] = G[3 * i] * Mt[3 * k] + G[3 * i + 1] * Mt[3 * k + 1] + G[3 * i + 2] * Mt[3 * k + 2];
      double* out = &m.tet_grad[12 * t];
      for (int i = 0; i < 3; ++i) {
        out[i] = -(GT[3 * i] + GT[3 * i + 1] + GT[3 * i + 2]);
        for (int k = 0; k < 3; ++k) out[3 * (k + 1) + i] = GT[3 * i + k];
      }
    }
  });
  double energy = 0;
  for (std::size_t t = 0; t < m.nt; ++t) energy += m.tet_energy[t];
  if (want_grad) {
    const std::size_t nf = m.free_vertices.size();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nf, 2048), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t b = r.begin(); b < r.end(); ++b) {
        double gx = 0, gy = 0, gz = 0;
        for (std::uint32_t k = m.adj_offset[b]; k < m.adj_offset[b + 1]; ++k) {
          const std::uint32_t s = m.adj_slot[k];
          const double* src = &m.tet_grad[12 * std::size_t(s / 4) + 3 * std::size_t(s % 4)];
          gx += src[0];
          gy += src[1];
          gz += src[2];
        }
        grad[3 * b] = gx;
        grad[3 * b + 1] = gy;
        grad[3 * b + 2] = gz;
      }
    });
  }
  return energy;
}

namespace {

struct CertifiedStop {};
struct TimeStop {};

// LBFGSpp objective wrapping FfmEnergy with the exact stop and the time limit.
struct Objective {
  const FfmEnergy& energy;
  const std::vector<std::uint32_t>& tets;
  std::vector<double>& candidate;  // unscaled full coordinates (locked vertices already exact)
  double eps = 1;
  bool barrier = false;            // quality pass: +inf when any D <= 0
  bool stop_when_certified = true;
  Clock::time_point deadline;
  bool has_deadline = false;
  long evaluations = 0;
  long next_exact_check = 0;
  Eigen::VectorXd last_x;

  double operator()(const Eigen::VectorXd& x, Eigen::VectorXd& grad) {
    ++evaluations;
    if (has_deadline && Clock::now() > deadline) {
      last_x = x;
      throw TimeStop{};
    }
    if (barrier) {
      const double dmin = energy.min_det(x.data());
      if (!(dmin > 0)) {
        grad.setZero();
        return std::numeric_limits<double>::infinity();
      }
    }
    const double e = energy.evaluate(x.data(), eps, grad.data());
    if (stop_when_certified && evaluations >= next_exact_check) {
      const double dmin = energy.min_det(x.data());
      if (dmin > 0) {
        energy.write_back(x.data(), candidate);
        if (exact_nonpositive(candidate, tets) == 0) {
          last_x = x;
          throw CertifiedStop{};
        }
        next_exact_check = evaluations + 10;
      }
    }
    return e;
  }
};

LBFGSpp::LBFGSParam<double> lbfgs_param(int max_iterations, double gtol, int linesearch) {
  LBFGSpp::LBFGSParam<double> p;
  p.linesearch = linesearch;
  p.m = 7;
  p.epsilon = gtol;
  p.epsilon_rel = 0;
  p.max_iterations = max_iterations;
  p.max_linesearch = 40;
  return p;
}

}  // namespace

FfmResult ffm_untangle(const std::vector<double>& source_xyz, const std::vector<std::uint32_t>& tets,
                       const std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                       const FfmOptions& options) {
  const auto start = Clock::now();
  FfmResult result;
  FfmEnergy energy(source_xyz, tets, locked, target_xyz, options.reference, options.theta);
  std::vector<double> candidate = target_xyz;
  auto finish = [&](const Eigen::VectorXd& x, double eps) {
    energy.write_back(x.data(), target_xyz);
    result.nonpositive = exact_nonpositive(target_xyz, tets);
    result.certified = result.nonpositive == 0;
    result.final_epsilon = eps;
    result.min_det = energy.min_det(x.data());
    result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return result;
  };
  Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(energy.initial_variables().data(), Eigen::Index(energy.num_variables()));
  if (options.stop_when_certified && exact_nonpositive(target_xyz, tets) == 0) return finish(x, 0);
  if (x.size() == 0) return finish(x, 0);

  Objective obj{energy, tets, candidate, 1.0, false, true, Clock::time_point{}, false, 0, 0, Eigen::VectorXd()};
  obj.stop_when_certified = options.stop_when_certified;
  if (options.time_limit_seconds > 0) {
    obj.has_deadline = true;
    obj.deadline = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(options.time_limit_seconds));
  }
  // LBFGSpp keeps a reference to its parameters: they must outlive the solver.
  const LBFGSpp::LBFGSParam<double> param = lbfgs_param(options.max_lbfgs_iterations, options.gradient_tolerance, LBFGSpp::LBFGS_LINESEARCH_BACKTRACKING_STRONG_WOLFE);
  LBFGSpp::LBFGSSolver<double, LBFGSpp::LineSearchNocedalWright> solver(param);
  double eps = 1.0;
  Eigen::VectorXd grad(x.size());
  try {
    for (int outer = 0; outer < options.max_outer_iterations; ++outer) {
      result.outer_iterations = outer + 1;
      obj.eps = eps;
      const double E_prev = energy.evaluate(x.data(), eps, nullptr);
      double fx = 0;
      Eigen::VectorXd x_before = x;
      try {
        result.lbfgs_iterations += solver.minimize(obj, x, fx);
      } catch (const std::runtime_error& e) {
        if (getenv("VOLMAP_FFM_DEBUG")) fprintf(stderr, "lbfgs: %s\n", e.what());
        // Line search gave up: keep the better of the start point and the current point.
        if (!(energy.evaluate(x.data(), eps, nullptr) <= E_prev)) x = x_before;
      } catch (const std::logic_error& e) {
        if (getenv("VOLMAP_FFM_DEBUG")) fprintf(stderr, "lbfgs: %s\n", e.what());
        if (!(energy.evaluate(x.data(), eps, nullptr) <= E_prev)) x = x_before;
      }
      const double E = energy.evaluate(x.data(), eps, nullptr);
      const double dmin = energy.min_det(x.data());
      const double sigma = std::max(1.0 - E / E_prev, 0.1);
      const double mu = (1.0 - sigma) * ffm_chi(dmin, eps);
      if (dmin < mu)
        eps = 2.0 * std::sqrt(mu * (mu - dmin));
      else
        eps = 1e-10;
      if (!std::isfinite(eps)) eps = 1e-10;
      if (dmin > 0) {
        energy.write_back(x.data(), candidate);
        if (exact_nonpositive(candidate, tets) == 0 && options.stop_when_certified) break;
        if (std::abs(E_prev - E) / E < 1e-5) break;
      }
    }
  } catch (const CertifiedStop&) {
    x = obj.last_x;
  } catch (const TimeStop&) {
    x = obj.last_x;
    result.timed_out = true;
  }
  result.evaluations = obj.evaluations;
  return finish(x, eps);
}

QualityResult ffm_quality_pass(const std::vector<double>& source_xyz, const std::vector<std::uint32_t>& tets,
                               const std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                               ReferenceShape reference, int max_iterations, double time_limit_seconds) {
  QualityResult result;
  if (exact_nonpositive(target_xyz, tets) != 0) return result;
  FfmEnergy energy(source_xyz, tets, locked, target_xyz, reference, 0.5);
  if (energy.num_variables() == 0) return result;
  std::vector<double> candidate = target_xyz;
  Objective obj{energy, tets, candidate, 1.0, false, true, Clock::time_point{}, false, 0, 0, Eigen::VectorXd()};
  obj.eps = 1e-10;
  obj.barrier = true;
  obj.stop_when_certified = false;
  if (time_limit_seconds > 0) {
    obj.has_deadline = true;
    obj.deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(time_limit_seconds));
  }
  Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(energy.initial_variables().data(), Eigen::Index(energy.num_variables()));
  result.energy_before = energy.evaluate(x.data(), obj.eps, nullptr);
  Eigen::VectorXd best = x;
  double best_energy = result.energy_before;
  auto consider = [&](const Eigen::VectorXd& y) {
    if (!(energy.min_det(y.data()) > 0)) return;
    const double e = energy.evaluate(y.data(), obj.eps, nullptr);
    if (e < best_energy) {
      best = y;
      best_energy = e;
    }
  };
  const LBFGSpp::LBFGSParam<double> param = lbfgs_param(max_iterations, 1e-6, LBFGSpp::LBFGS_LINESEARCH_BACKTRACKING_ARMIJO);
  LBFGSpp::LBFGSSolver<double, LBFGSpp::LineSearchBacktracking> solver(param);
  double fx = 0;
  try {
    result.rounds = solver.minimize(obj, x, fx);
    consider(x);
  } catch (const TimeStop&) {
    consider(obj.last_x);
  } catch (const std::exception&) {
    consider(x);
  }
  if (best_energy < result.energy_before) {
    energy.write_back(best.data(), candidate);
    if (exact_nonpositive(candidate, tets) == 0) {
      target_xyz = candidate;
      result.improved = true;
      result.energy_after = best_energy;
      return result;
    }
  }
  result.energy_after = result.energy_before;
  return result;
}

}  // namespace volmap
