// ffm.cpp — FFM untangler (Garanzha et al. 2021), re-implemented from docs/mapping.md §5.
// Hessian (Newton solver): with τ = tr(JᵀJ), φ = χ^{-2/3}, ψ = (1+D²)/χ, C = cof J = ∂D/∂J and
// H_D = ∂²D/∂J² (H_D[(i,j),(k,l)] = ε_{ikm} ε_{jln} J_mn), per tet and in J (9 variables):
//   ∇²f = 2φ I + 2φ'(J⊗C + C⊗J) + τφ'' C⊗C + τφ' H_D,   ∇²g = ψ'' C⊗C + ψ' H_D,
//   φ' = −(2/3)φχ'/χ, φ'' = (10/9)φχ'²/χ² − (2/3)φχ''/χ, ψ' = 2D/χ − (1+D²)χ'/χ²,
//   ψ'' = 2/χ − 4Dχ'/χ² + 2(1+D²)χ'²/χ³ − (1+D²)χ''/χ²,  χ'' = ε²/(2(ε²+D²)^{3/2});
// projected to PSD (eigenvalues clamped at 0) and pulled back through the linear map x ↦ J.
// Conventions: see volmap/ffm.hpp. Edge matrices are stored row-major: T[3*i+k] = coordinate i of
// edge k (edge k = x_{k+1} − x_0). J = T·M with M = R⁻¹. A VOLMAP-positive tet has det T < 0 and
// every reference R has det R < 0, hence D = det J > 0 for positive target tets.
#include <volmap/volume/ffm.hpp>

#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>

#include "local_region.hpp"
#include "untangle_support.hpp"

#include <LBFGS.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
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

// χ''(D,ε) = ε²/(2(ε²+D²)^{3/2}).
static double ffm_chi_second(double D, double eps) {
  const double s = std::sqrt(eps * eps + D * D);
  return eps * eps / (2.0 * s * s * s);
}

namespace {

using untangle::det3;
using untangle::edge_matrix;
using untangle::signed_volume_sum;

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

// A source tet's edge matrix T is a usable rest shape when det T < 0 (VOLMAP-positive) with a
// relative volume |det T| / (Σ|edge|²)^{3/2} above 1e-9: flatter tets (exactly positive slivers from
// refinement, or ones whose double determinant has the wrong sign) make M = T⁻¹ and the energy
// numerically meaningless, so they take the regular reference instead (docs/mapping.md §5).
inline bool rest_shape_usable(const double* T) {
  const double d = det3(T);
  double sq = 0;
  for (int k = 0; k < 9; ++k) sq += T[k] * T[k];
  return std::isfinite(d) && d < 0 && -d > 1e-9 * sq * std::sqrt(sq);
}

inline void matmul3(const double* A, const double* B, double* C) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
}

// Levi-Civita sign of the permutation (i, k, 3−i−k), i ≠ k.
inline double levi_civita(int i, int k) { return (k - i + 3) % 3 == 1 ? 1.0 : -1.0; }

}  // namespace
struct FfmEnergy::Impl {
  std::size_t nv = 0, nt = 0;
  std::vector<std::uint32_t> tets;
  untangle::FreeVertexLayout layout;
  untangle::BoxFrame frame;
  double theta = 0.5;
  std::vector<double> M;       // 9 per tet: R⁻¹
  std::vector<double> weight;  // per tet: vol_ref
  std::size_t unusable_rest_shapes = 0;  // source tets given the regular reference (RestShape only)
  // Work buffers (evaluation is not re-entrant).
  mutable std::vector<double> x;          // 3*nv scaled positions
  mutable std::vector<double> tet_grad;   // 12 per tet
  mutable std::vector<double> tet_energy; // per tet
  mutable std::vector<double> tet_det;    // per tet

  // Energy of tet t at the loaded positions x; D into tet_det[t]. Writes the 12 vertex gradients into
  // g12 and the 12×12 Hessian (row-major, vertex-major xyz) into h144 when non-null.
  double tet_terms(std::size_t t, double eps, double* g12, double* h144, bool project) const;
  // fn(local, row, col) for every entry of tet t's 12×12 Hessian (local = index in h144) between free
  // vertices, with its row and column among the variables.
  template <class Fn>
  void for_each_hessian_entry(std::size_t t, Fn&& fn) const {
    for (int v = 0; v < 4; ++v) {
      const std::int64_t bv = layout.free_index[tets[4 * t + v]];
      if (bv < 0) continue;
      for (int u = 0; u < 4; ++u) {
        const std::int64_t bu = layout.free_index[tets[4 * t + u]];
        if (bu < 0) continue;
        for (int c = 0; c < 3; ++c)
          for (int c2 = 0; c2 < 3; ++c2) fn((3 * v + c) * 12 + 3 * u + c2, 3 * std::size_t(bv) + c, 3 * std::size_t(bu) + c2);
      }
    }
  }
  double min_tet_det() const {
    double d = std::numeric_limits<double>::infinity();
    for (double v : tet_det) d = std::min(d, v);
    return d;
  }
};

double FfmEnergy::Impl::tet_terms(std::size_t t, double eps, double* g12, double* h144, bool project) const {
  double T[9], J[9], C[9];
  const double* Mt = &M[9 * t];
  edge_matrix(x.data(), &tets[4 * t], T);
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
  const double w = weight[t];
  tet_det[t] = D;
  const double energy = w * ((1.0 - theta) * f + theta * g);
  if (!g12) return energy;
  // ∂E/∂J = a·J + b·C.
  const double a = w * (1.0 - theta) * 2.0 / chi23;
  const double b = w * ((1.0 - theta) * (-2.0 / 3.0) * f * chi_d / chi + theta * (2.0 * D - g * chi_d) / chi);
  // dM[v][j] = ∂J_ij/∂x_{v,i}: rows of M for v ≥ 1, minus their sum for v = 0.
  double dM[12];
  for (int j = 0; j < 3; ++j) {
    dM[3 + j] = Mt[j];
    dM[6 + j] = Mt[3 + j];
    dM[9 + j] = Mt[6 + j];
    dM[j] = -(Mt[j] + Mt[3 + j] + Mt[6 + j]);
  }
  double G[9];
  for (int i = 0; i < 9; ++i) G[i] = a * J[i] + b * C[i];
  for (int v = 0; v < 4; ++v)
    for (int c = 0; c < 3; ++c) g12[3 * v + c] = dM[3 * v] * G[3 * c] + dM[3 * v + 1] * G[3 * c + 1] + dM[3 * v + 2] * G[3 * c + 2];
  if (!h144) return energy;
  const double chi_dd = ffm_chi_second(D, eps);
  const double phi = 1.0 / chi23;
  const double dphi = -(2.0 / 3.0) * phi * chi_d / chi;
  const double ddphi = (10.0 / 9.0) * phi * chi_d * chi_d / (chi * chi) - (2.0 / 3.0) * phi * chi_dd / chi;
  const double q = 1.0 + D * D;
  const double dpsi = 2.0 * D / chi - q * chi_d / (chi * chi);
  const double ddpsi = 2.0 / chi - 4.0 * D * chi_d / (chi * chi) + 2.0 * q * chi_d * chi_d / (chi * chi * chi) - q * chi_dd / (chi * chi);
  const double wf = w * (1.0 - theta), wg = w * theta;
  const double c_id = wf * 2.0 * phi, c_jc = wf * 2.0 * dphi, c_cc = wf * trace * ddphi + wg * ddpsi, c_hd = wf * trace * dphi + wg * dpsi;
  Eigen::Matrix<double, 9, 9> H;
  for (int p = 0; p < 9; ++p)
    for (int r = 0; r < 9; ++r) H(p, r) = (p == r ? c_id : 0.0) + c_jc * (J[p] * C[r] + C[p] * J[r]) + c_cc * C[p] * C[r];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      if (i == k) continue;
      const int m = 3 - i - k;
      const double sik = levi_civita(i, k);
      for (int j = 0; j < 3; ++j)
        for (int l = 0; l < 3; ++l) {
          if (j == l) continue;
          const int n = 3 - j - l;
          H(3 * i + j, 3 * k + l) += c_hd * sik * levi_civita(j, l) * J[3 * m + n];
        }
    }
  if (project) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> es(H);
    Eigen::Matrix<double, 9, 1> lambda = es.eigenvalues();
    if (lambda.minCoeff() < 0) {
      for (int p = 0; p < 9; ++p) lambda[p] = std::max(lambda[p], 0.0);
      H = es.eigenvectors() * lambda.asDiagonal() * es.eigenvectors().transpose();
    }
  }
  // Pull back: h[(v,c),(u,c')] = Σ_{j,l} dM[v][j]·H[(c,j),(c',l)]·dM[u][l].
  for (int c = 0; c < 3; ++c)
    for (int c2 = 0; c2 < 3; ++c2) {
      double Q[12];  // Q[v][l] = Σ_j dM[v][j] H[(c,j),(c2,l)]
      for (int v = 0; v < 4; ++v)
        for (int l = 0; l < 3; ++l)
          Q[3 * v + l] = dM[3 * v] * H(3 * c, 3 * c2 + l) + dM[3 * v + 1] * H(3 * c + 1, 3 * c2 + l) + dM[3 * v + 2] * H(3 * c + 2, 3 * c2 + l);
      for (int v = 0; v < 4; ++v)
        for (int u = 0; u < 4; ++u)
          h144[(3 * v + c) * 12 + 3 * u + c2] = Q[3 * v] * dM[3 * u] + Q[3 * v + 1] * dM[3 * u + 1] + Q[3 * v + 2] * dM[3 * u + 2];
    }
  return energy;
}

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
  m.layout.build(m.nv, tets, locked);
  // Scale the target into a box of side 10.
  m.frame.fit(target_xyz, 10.0, "ffm");
  m.x = m.frame.to_scaled(target_xyz);

  // vol(D): with a fixed boundary, Σ signed target volume is the domain volume.
  const double domain_volume = signed_volume_sum(m.x.data(), tets);
  const double source_volume = signed_volume_sum(source_xyz.data(), tets);
  if (!(domain_volume > 0)) throw Error(ErrorKind::BadInput, "", 0, "ffm: the boundary map encloses a non-positive volume (mirrored map?)");
  if (!(source_volume > 0)) throw Error(ErrorKind::BadInput, "", 0, "ffm: the source mesh has non-positive total volume");

  m.M.resize(9 * m.nt);
  m.weight.resize(m.nt);
  // Mirrored regular tet (1,1,1),(1,−1,−1),(−1,1,−1),(−1,−1,1) of volume vol(D)/T: edge determinant
  // −16, like VOLMAP tets. The reference of every tet for RegularTet, and the stand-in for a source
  // tet whose rest shape is unusable in double precision for RestShape.
  const double mean_volume = domain_volume / double(m.nt);
  const double side = std::cbrt(6.0 * mean_volume / 16.0);
  const double regular[9] = {0, -2 * side, -2 * side, -2 * side, 0, -2 * side, -2 * side, -2 * side, 0};
  double regular_inverse[9];
  inverse3(regular, regular_inverse);
  const auto use_regular = [&](std::size_t t) {
    std::copy(regular_inverse, regular_inverse + 9, &m.M[9 * t]);
    m.weight[t] = mean_volume;
  };
  if (reference == ReferenceShape::RegularTet) {
    for (std::size_t t = 0; t < m.nt; ++t) use_regular(t);
  } else {
    const double c = std::cbrt(domain_volume / source_volume);
    double T[9];
    for (std::size_t t = 0; t < m.nt; ++t) {
      edge_matrix(source_xyz.data(), &tets[4 * t], T);
      for (double& e : T) e *= c;
      if (rest_shape_usable(T) && inverse3(T, &m.M[9 * t])) {
        m.weight[t] = -det3(T) / 6.0;
      } else {
        use_regular(t);
        ++m.unusable_rest_shapes;
      }
    }
  }
  m.tet_grad.resize(12 * m.nt);
  m.tet_energy.resize(m.nt);
  m.tet_det.resize(m.nt);
}

FfmEnergy::~FfmEnergy() = default;

std::size_t FfmEnergy::unusable_rest_shapes() const { return impl_->unusable_rest_shapes; }

std::size_t FfmEnergy::num_variables() const { return impl_->layout.num_variables(); }

std::vector<double> FfmEnergy::initial_variables() const {
  std::vector<double> vars(num_variables());
  impl_->layout.extract(impl_->x.data(), vars.data());
  return vars;
}

void FfmEnergy::write_back(const double* vars, std::vector<double>& target_xyz) const {
  impl_->frame.write_back(impl_->layout, vars, target_xyz);
}

double FfmEnergy::min_det(const double* vars) const {
  const Impl& m = *impl_;
  m.layout.load(vars, m.x.data());
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
  m.layout.load(vars, m.x.data());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.nt, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t t = r.begin(); t < r.end(); ++t)
      m.tet_energy[t] = m.tet_terms(t, eps, grad ? &m.tet_grad[12 * t] : nullptr, nullptr, false);
  });
  double energy = 0;
  for (std::size_t t = 0; t < m.nt; ++t) energy += m.tet_energy[t];
  if (grad) m.layout.gather(m.tet_grad.data(), grad);
  return energy;
}

double FfmEnergy::evaluate_dense_hessian(const double* vars, double eps, bool spd_projection, double* hessian) const {
  const Impl& m = *impl_;
  m.layout.load(vars, m.x.data());
  const std::size_t n = num_variables();
  std::fill(hessian, hessian + n * n, 0.0);
  double energy = 0, g12[12], h144[144];
  for (std::size_t t = 0; t < m.nt; ++t) {
    energy += m.tet_terms(t, eps, g12, h144, spd_projection);
    m.for_each_hessian_entry(t, [&](int local, std::size_t row, std::size_t col) { hessian[row * n + col] += h144[local]; });
  }
  return energy;
}

// Newton inner solver: fixed sparsity pattern (lower triangle of the free-variable Hessian), one
// symbolic analysis, numeric LDLᵀ per step, Armijo backtracking on E_ε.
class FfmNewton {
 public:
  explicit FfmNewton(const FfmEnergy& energy) : e_(energy), m_(*energy.impl_) {
    const std::size_t n = e_.num_variables();
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(m_.nt * 78);
    // Lower triangle only.
    auto for_each_entry = [&](std::size_t t, auto&& fn) {
      m_.for_each_hessian_entry(t, [&](int local, std::size_t row, std::size_t col) {
        if (row >= col) fn(local, row, col);
      });
    };
    for (std::size_t t = 0; t < m_.nt; ++t)
      for_each_entry(t, [&](int, std::size_t row, std::size_t col) { trip.emplace_back(int(row), int(col), 0.0); });
    for (std::size_t i = 0; i < n; ++i) trip.emplace_back(int(i), int(i), 0.0);
    H_.resize(Eigen::Index(n), Eigen::Index(n));
    H_.setFromTriplets(trip.begin(), trip.end());
    H_.makeCompressed();
    auto index_of = [&](std::size_t row, std::size_t col) {
      const int* begin = H_.innerIndexPtr() + H_.outerIndexPtr()[col];
      const int* end = H_.innerIndexPtr() + H_.outerIndexPtr()[col + 1];
      return std::int32_t(std::lower_bound(begin, end, int(row)) - H_.innerIndexPtr());
    };
    slot_offset_.assign(m_.nt + 1, 0);
    for (std::size_t t = 0; t < m_.nt; ++t) {
      std::uint32_t k = 0;
      for_each_entry(t, [&](int, std::size_t, std::size_t) { ++k; });
      slot_offset_[t + 1] = slot_offset_[t] + k;
    }
    slot_local_.resize(slot_offset_[m_.nt]);
    slot_value_.resize(slot_offset_[m_.nt]);
    for (std::size_t t = 0; t < m_.nt; ++t) {
      std::uint32_t k = slot_offset_[t];
      for_each_entry(t, [&](int local, std::size_t row, std::size_t col) {
        slot_local_[k] = std::uint8_t(local);
        slot_value_[k] = index_of(row, col);
        ++k;
      });
    }
    diag_.resize(n);
    for (std::size_t i = 0; i < n; ++i) diag_[i] = index_of(i, i);
    ldlt_.analyzePattern(H_);
    h_.resize(144 * m_.nt);
  }

  // Newton on E_ε from x (in place). Stops after max_iterations, when ‖g‖ ≤ gtol, when the Newton
  // decrement is negligible or the line search fails. Exact stop / deadline via the guard.
  long minimize(Eigen::VectorXd& x, double eps, int max_iterations, double gtol, untangle::GuardedObjective& guard) {
    const Eigen::Index n = x.size();
    Eigen::VectorXd g(n), d(n), trial(n);
    long iterations = 0;
    for (int it = 0; it < max_iterations; ++it) {
      if (guard.past_deadline()) {
        guard.last_x = x;
        throw untangle::TimeStop{};
      }
      const double E = assemble(x.data(), eps, g.data());
      ++guard.evaluations;
      if (guard.stop_when_certified && m_.min_tet_det() > 0 && guard.exactly_certified(x.data())) {
        guard.last_x = x;
        throw untangle::CertifiedStop{};
      }
      if (g.norm() <= gtol) break;
      if (!solve(g, d)) d = -g;
      double slope = g.dot(d);
      if (!(slope < 0)) {
        d = -g;
        slope = -g.squaredNorm();
      }
      if (-slope < 1e-14 * std::max(1.0, std::abs(E))) break;
      double alpha = 1.0;
      bool accepted = false;
      for (int ls = 0; ls < 40; ++ls) {
        trial = x + alpha * d;
        const double Et = e_.evaluate(trial.data(), eps, nullptr);
        ++guard.evaluations;
        if (Et <= E + 1e-4 * alpha * slope) {
          accepted = true;
          break;
        }
        alpha *= 0.5;
      }
      ++iterations;
      if (!accepted) break;
      x = trial;
      if (alpha * d.norm() <= 1e-12 * std::max(1.0, x.norm())) break;
    }
    return iterations;
  }

 private:
  double assemble(const double* vars, double eps, double* grad) {
    m_.layout.load(vars, m_.x.data());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m_.nt, 256), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t t = r.begin(); t < r.end(); ++t)
        m_.tet_energy[t] = m_.tet_terms(t, eps, &m_.tet_grad[12 * t], &h_[144 * t], true);
    });
    double energy = 0;
    for (std::size_t t = 0; t < m_.nt; ++t) energy += m_.tet_energy[t];
    m_.layout.gather(m_.tet_grad.data(), grad);
    double* values = H_.valuePtr();
    std::fill(values, values + H_.nonZeros(), 0.0);
    for (std::size_t t = 0; t < m_.nt; ++t) {
      const double* h = &h_[144 * t];
      for (std::uint32_t k = slot_offset_[t]; k < slot_offset_[t + 1]; ++k) values[slot_value_[k]] += h[slot_local_[k]];
    }
    return energy;
  }

  bool solve(const Eigen::VectorXd& g, Eigen::VectorXd& d) {
    double* values = H_.valuePtr();
    double trace = 0;
    for (std::int32_t i : diag_) trace += values[i];
    double shift = 1e-10 * std::max(trace / double(std::max<std::size_t>(1, diag_.size())), 1e-300);
    for (int attempt = 0; attempt < 6; ++attempt) {
      for (std::int32_t i : diag_) values[i] += shift;
      ldlt_.factorize(H_);
      if (ldlt_.info() == Eigen::Success && ldlt_.vectorD().minCoeff() > 0) {
        d = ldlt_.solve(-g);
        if (d.allFinite()) return true;
      }
      shift *= 100.0;
    }
    return false;
  }

  const FfmEnergy& e_;
  FfmEnergy::Impl& m_;
  Eigen::SparseMatrix<double> H_;  // lower triangle
  std::vector<std::uint32_t> slot_offset_;
  std::vector<std::uint8_t> slot_local_;
  std::vector<std::int32_t> slot_value_;
  std::vector<std::int32_t> diag_;
  std::vector<double> h_;  // 144 per tet
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt_;
};

namespace {

// Guard around an FfmEnergy: evaluation reports whether every double determinant is positive.
untangle::GuardedObjective make_guard(const FfmEnergy::Impl& m, const std::vector<std::uint32_t>& tets, std::vector<double>& candidate) {
  untangle::GuardedObjective g;
  g.layout = &m.layout;
  g.frame = &m.frame;
  g.tets = &tets;
  g.candidate = &candidate;
  return g;
}

// Mean length of the tets' edges from their first vertex (a scale for trial moves).
double mean_edge_length(const std::vector<double>& xyz, const std::vector<std::uint32_t>& tets) {
  double sum = 0;
  for (std::size_t s = 0; s < tets.size(); s += 4)
    for (int k = 1; k < 4; ++k) {
      double d2 = 0;
      for (int i = 0; i < 3; ++i) {
        const double d = xyz[3 * std::size_t(tets[s + k]) + i] - xyz[3 * std::size_t(tets[s]) + i];
        d2 += d * d;
      }
      sum += std::sqrt(d2);
    }
  return tets.empty() ? 0 : sum / double(3 * (tets.size() / 4));
}

std::size_t count_nonpositive_det(const std::vector<double>& dets) {
  std::size_t k = 0;
  for (double d : dets) k += !(d > 0);
  return k;
}

}  // namespace

FfmResult ffm_untangle(const std::vector<double>& source_xyz, const std::vector<std::uint32_t>& tets,
                       const std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                       const FfmOptions& options) {
  const TimeBudget budget(options.time_limit_seconds);
  FfmResult result;
  FfmEnergy energy(source_xyz, tets, locked, target_xyz, options.reference, options.theta);
  const FfmEnergy::Impl& m = energy.impl();
  std::vector<double> candidate = target_xyz;
  auto finish = [&](const Eigen::VectorXd& x, double eps) {
    energy.write_back(x.data(), target_xyz);
    result.nonpositive = count_nonpositive(target_xyz, tets);
    result.certified = result.nonpositive == 0;
    result.final_epsilon = eps;
    result.min_det = energy.min_det(x.data());
    result.seconds = budget.elapsed();
    return result;
  };
  const std::vector<double> x0 = energy.initial_variables();
  Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(x0.data(), Eigen::Index(x0.size()));
  if (options.stop_when_certified && count_nonpositive(target_xyz, tets) == 0) return finish(x, 0);
  if (x.size() == 0) return finish(x, 0);

  untangle::GuardedObjective obj = make_guard(m, tets, candidate);
  double eps = options.initial_epsilon;
  if (!(eps > 0)) eps = std::clamp(2.0 * std::max(0.0, -energy.min_det(x.data())), 1e-3, 1.0);
  obj.evaluate = [&](const double* vars, double* grad, bool* all_positive) {
    const double e = energy.evaluate(vars, eps, grad);
    *all_positive = m.min_tet_det() > 0;
    return e;
  };
  obj.stop_when_certified = options.stop_when_certified;
  obj.budget = budget;
  // LBFGSpp keeps a reference to its parameters: they must outlive the solver.
  const LBFGSpp::LBFGSParam<double> param =
      untangle::lbfgs_param(options.max_lbfgs_iterations, options.gradient_tolerance, 0, LBFGSpp::LBFGS_LINESEARCH_BACKTRACKING_WOLFE);
  LBFGSpp::LBFGSSolver<double, LBFGSpp::LineSearchBacktracking> solver(param);
  std::unique_ptr<FfmNewton> newton;
  if (options.solver == FfmSolver::Newton) newton = std::make_unique<FfmNewton>(energy);
  std::size_t best_double_bad = std::size_t(-1);
  int since_best = 0;
  try {
    for (int outer = 0; outer < options.max_outer_iterations; ++outer) {
      result.outer_iterations = outer + 1;
      const double E_prev = energy.evaluate(x.data(), eps, nullptr);
      if (newton) {
        result.lbfgs_iterations += newton->minimize(x, eps, options.max_newton_iterations, options.gradient_tolerance, obj);
      } else {
        const Eigen::VectorXd x_before = x;
        const long it = untangle::run_lbfgs(solver, obj, x);
        if (it >= 0) {
          result.lbfgs_iterations += it;
        } else {
          // Line search gave up: keep the better of the start point and the current point.
          ++result.line_search_failures;
          if (!(energy.evaluate(x.data(), eps, nullptr) <= E_prev)) x = x_before;
        }
      }
      const double E = energy.evaluate(x.data(), eps, nullptr);
      const double dmin = m.min_tet_det();
      const std::size_t double_bad = count_nonpositive_det(m.tet_det);
      // ε update of the paper: σ = max(1 − E/E_prev, 0.1), μ = (1−σ)·χ(D_min, ε).
      const double sigma = std::max(1.0 - E / E_prev, 0.1);
      const double mu = (1.0 - sigma) * ffm_chi(dmin, eps);
      if (dmin < mu)
        eps = 2.0 * std::sqrt(mu * (mu - dmin));
      else
        eps = 1e-10;
      if (!std::isfinite(eps)) eps = 1e-10;
      if (dmin > 0) {
        if (options.stop_when_certified && obj.exactly_certified(x.data())) break;
        if (std::abs(E_prev - E) / E < 1e-5) break;
      }
      if (double_bad < best_double_bad) {
        best_double_bad = double_bad;
        since_best = 0;
      } else if (options.stall_outer_iterations > 0 && ++since_best >= options.stall_outer_iterations) {
        result.stalled = true;
        break;
      }
    }
  } catch (const untangle::CertifiedStop&) {
    x = obj.last_x;
  } catch (const untangle::TimeStop&) {
    x = obj.last_x;
    result.timed_out = true;
  }
  result.evaluations = obj.evaluations;
  return finish(x, eps);
}

LocalUntangleResult ffm_local_untangle(const TetMesh& source, const std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                                       const LocalUntangleOptions& options) {
  const TimeBudget budget(options.time_limit_seconds);
  LocalUntangleResult result;
  const std::size_t nv = source.num_vertex_slots();
  if (source.num_free_tet_slots() != 0 || source.num_vertices() != nv)
    throw Error(ErrorKind::BadInput, "", 0, "ffm_local_untangle: the mesh has tombstones (compact it first)");
  if (target_xyz.size() != 3 * nv || locked.size() != nv) throw Error(ErrorKind::BadInput, "", 0, "ffm_local_untangle: inconsistent array sizes");
  const std::vector<std::uint32_t>& tets = source.tet_vertex_array();
  std::vector<std::uint32_t> bad = nonpositive_tets(target_xyz, tets);
  result.nonpositive_before = result.nonpositive_after = bad.size();
  if (bad.empty()) return result;
  int rings = options.rings;
  bool other_reference_tried = false, rings_grown = false;
  std::size_t failed_region_tets = 0;  // the region both references last failed on
  ReferenceShape reference = options.reference;
  for (int round = 0; round < options.max_rounds && !bad.empty(); ++round) {
    if (budget.expired()) break;
    LocalRegion region = extract_local_region(source, locked, target_xyz, bad, rings);
    // More rings that add no tet give the same region both references just failed on.
    if (rings_grown && region.num_tets() == failed_region_tets) break;
    rings_grown = false;
    result.rounds = round + 1;
    result.largest_region_tets = std::max(result.largest_region_tets, region.num_tets());
    const std::size_t sub_before = count_nonpositive(region.target, region.tets);
    std::size_t sub_after = sub_before;
    std::vector<double> trial = region.target;
    if (region.num_tets() > 0) {
      FfmOptions fo;
      fo.reference = reference;
      fo.solver = FfmSolver::Newton;
      fo.stall_outer_iterations = options.stall_outer_iterations;
      fo.initial_epsilon = 0;  // warm start: the map is nearly valid
      fo.time_limit_seconds = budget.option_seconds();
      try {
        ffm_untangle(region.source, region.tets, region.locked, trial, fo);
        sub_after = count_nonpositive(trial, region.tets);
      } catch (const Error&) {
        sub_after = sub_before;  // e.g. the region's boundary encloses a non-positive volume: grow it
      }
    }
    if (sub_after < sub_before) {
      region.target.swap(trial);
      region.write_back(target_xyz);
      other_reference_tried = false;
      reference = options.reference;
    } else if (!other_reference_tried) {
      other_reference_tried = true;
      reference = reference == ReferenceShape::RegularTet ? ReferenceShape::RestShape : ReferenceShape::RegularTet;
    } else {
      other_reference_tried = false;
      reference = options.reference;
      rings += options.ring_step;
      rings_grown = true;
      failed_region_tets = region.num_tets();
      if (rings > options.max_rings) break;
    }
    bad = nonpositive_tets(target_xyz, tets);
  }
  result.nonpositive_after = bad.size();
  result.seconds = budget.elapsed();
  return result;
}

QualityResult ffm_quality_pass(const std::vector<double>& source_xyz, const std::vector<std::uint32_t>& tets,
                               const std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                               ReferenceShape reference, int max_iterations, double time_limit_seconds,
                               double relative_decrease) {
  QualityResult result;
  if (count_nonpositive(target_xyz, tets) != 0) return result;
  FfmEnergy energy(source_xyz, tets, locked, target_xyz, reference, 0.5);
  if (energy.num_variables() == 0) return result;
  const FfmEnergy::Impl& m = energy.impl();
  std::vector<double> candidate = target_xyz;
  const double eps = 1e-10;
  untangle::GuardedObjective obj = make_guard(m, tets, candidate);
  obj.evaluate = [&](const double* vars, double* grad, bool* all_positive) {
    const double e = energy.evaluate(vars, eps, grad);
    *all_positive = m.min_tet_det() > 0;
    return e;
  };
  obj.barrier = true;
  obj.stop_when_certified = false;
  obj.budget = TimeBudget(time_limit_seconds);
  obj.track_lowest = true;
  const std::vector<double> x0 = energy.initial_variables();
  Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(x0.data(), Eigen::Index(x0.size()));
  result.energy_before = energy.evaluate(x.data(), eps, nullptr);
  Eigen::VectorXd best = x;
  double best_energy = result.energy_before;
  auto consider = [&](const Eigen::VectorXd& y) {
    if (!(energy.min_det(y.data()) > 0)) return;
    const double e = energy.evaluate(y.data(), eps, nullptr);
    if (e < best_energy) {
      best = y;
      best_energy = e;
    }
  };
  obj.max_move = 0.5 * mean_edge_length(target_xyz, tets) * m.frame.scale;
  const LBFGSpp::LBFGSParam<double> param = untangle::lbfgs_param(max_iterations, 1e-6, relative_decrease, LBFGSpp::LBFGS_LINESEARCH_BACKTRACKING_ARMIJO);
  LBFGSpp::LBFGSSolver<double, untangle::CappedBacktracking> solver(param);
  try {
    result.rounds = int(std::max<long>(0, untangle::run_lbfgs(solver, obj, x)));
    consider(x);
  } catch (const untangle::TimeStop&) {
    consider(obj.last_x);
  }
  if (obj.lowest_x.size() == x.size()) consider(obj.lowest_x);
  if (best_energy < result.energy_before) {
    energy.write_back(best.data(), candidate);
    if (count_nonpositive(candidate, tets) == 0) {
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
