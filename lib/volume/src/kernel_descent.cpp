// kernel_descent.cpp — bad-tet-driven local descent (docs/mapping.md §10; conventions in kernel_descent.hpp).
#include <volmap/volume/kernel_descent.hpp>

#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>
#include <volmap/volume/kernel_lp.hpp>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

namespace volmap {

namespace {

// Signed volume over (mean squared edge length)^(3/2): scale-free, > 0 for a positive tet (double).
double normalised_volume(const double* a, const double* b, const double* c, const double* d) {
  double u[3], v[3], w[3];
  for (int i = 0; i < 3; ++i) {
    u[i] = a[i] - d[i];
    v[i] = b[i] - d[i];
    w[i] = c[i] - d[i];
  }
  const double det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
  const double* p[4] = {a, b, c, d};
  double sq = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      for (int k = 0; k < 3; ++k) sq += (p[i][k] - p[j][k]) * (p[i][k] - p[j][k]);
  sq /= 6;
  return sq > 0 ? det / (sq * std::sqrt(sq)) : 0;
}

class Descent {
 public:
  Descent(const TetMesh& mesh, const std::vector<std::uint8_t>& locked, std::vector<double>& X)
      : mesh_(mesh), locked_(locked), X_(X), tv_(mesh.tet_vertex_array()), queued_(locked.size(), 0) {}

  KernelDescentResult run(std::size_t max_visits) {
    KernelDescentResult r;
    const std::size_t nt = mesh_.num_tet_slots();
    std::vector<std::int8_t> sign(nt);
    auto count = [&] {
      const TetSignCounts c = orient3d_tets(X_.data(), locked_.size(), tv_.data(), nt, sign.data());
      return c.zero + c.negative;
    };
    r.nonpositive_before = count();
    if (max_visits == 0) max_visits = std::max<std::size_t>(1000, 50 * r.nonpositive_before);
    for (std::size_t t = 0; t < nt; ++t)
      if (sign[t] <= 0) queue_free_vertices(t);
    while (!queue_.empty() && r.visits < max_visits) {
      const std::uint32_t v = queue_.front();
      queue_.pop_front();
      queued_[v] = 0;
      ++r.visits;
      if (try_move(v)) ++r.moves;
    }
    r.nonpositive_after = count();
    return r;
  }

 private:
  const TetMesh& mesh_;
  const std::vector<std::uint8_t>& locked_;
  std::vector<double>& X_;
  const std::vector<std::uint32_t>& tv_;
  std::vector<std::uint8_t> queued_;
  std::deque<std::uint32_t> queue_;
  std::vector<double> tri_;
  const FpEnvironmentScope fp_;

  const double* at(std::uint32_t v) const { return X_.data() + 3 * std::size_t(v); }

  void queue_free_vertices(std::size_t t) {
    for (int i = 0; i < 4; ++i) {
      const std::uint32_t v = tv_[4 * t + i];
      if (!locked_[v] && !queued_[v]) {
        queued_[v] = 1;
        queue_.push_back(v);
      }
    }
  }

  // Exact non-positive count and smallest normalised volume of v's star at the current X.
  std::pair<std::size_t, double> star_state(std::uint32_t v) const {
    std::size_t bad = 0;
    double worst = std::numeric_limits<double>::infinity();
    for (TetId t : mesh_.vertex_tets(VertexId(v))) {
      const std::uint32_t* q = &tv_[4 * std::size_t(t.idx())];
      if (fp_.orient3d(at(q[0]), at(q[1]), at(q[2]), at(q[3])) <= 0) ++bad;
      worst = std::min(worst, normalised_volume(at(q[0]), at(q[1]), at(q[2]), at(q[3])));
    }
    return {bad, worst};
  }

  bool try_move(std::uint32_t v) {
    tri_.clear();
    for (TetId t : mesh_.vertex_tets(VertexId(v))) {
      const auto face = mesh_.half_face_vertices(HalfFaceId(t, mesh_.tet_local_index(t, VertexId(v))));
      for (VertexId u : face) tri_.insert(tri_.end(), at(u.idx()), at(u.idx()) + 3);
    }
    double q[3], slack = 0;
    if (!chebyshev_point(tri_, q, &slack) || !std::isfinite(q[0]) || !std::isfinite(q[1]) || !std::isfinite(q[2])) return false;
    const auto before = star_state(v);
    double old[3];
    std::copy(at(v), at(v) + 3, old);
    std::copy(q, q + 3, X_.data() + 3 * std::size_t(v));
    const auto after = star_state(v);
    const bool better = after.first < before.first || (after.first == before.first && after.second > before.second);
    if (!better) {
      std::copy(old, old + 3, X_.data() + 3 * std::size_t(v));
      return false;
    }
    for (TetId t : mesh_.vertex_tets(VertexId(v))) {
      const std::uint32_t* w = &tv_[4 * std::size_t(t.idx())];
      if (fp_.orient3d(at(w[0]), at(w[1]), at(w[2]), at(w[3])) <= 0) queue_free_vertices(t.idx());
    }
    return true;
  }
};

}  // namespace

KernelDescentResult descend_into_link_kernels(const TetMesh& mesh, const std::vector<std::uint8_t>& locked,
                                              std::vector<double>& X, std::size_t max_visits) {
  const std::size_t nv = mesh.num_vertex_slots();
  if (mesh.num_free_tet_slots() != 0 || mesh.num_vertices() != nv)
    throw Error(ErrorKind::BadInput, "", 0, "descend_into_link_kernels: the mesh has tombstones (compact it first)");
  if (locked.size() != nv || X.size() != 3 * nv) throw Error(ErrorKind::BadInput, "", 0, "descend_into_link_kernels: inconsistent array sizes");
  return Descent(mesh, locked, X).run(max_visits);
}

}  // namespace volmap
