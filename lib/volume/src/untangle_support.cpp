// untangle_support.cpp — shared untangler machinery; see untangle_support.hpp for conventions.
#include "untangle_support.hpp"

#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace volmap::untangle {

void FreeVertexLayout::build(std::size_t nv, const std::vector<std::uint32_t>& tets, const std::vector<std::uint8_t>& locked) {
  free_index.assign(nv, -1);
  free_vertices.clear();
  for (std::size_t v = 0; v < nv; ++v)
    if (!locked[v]) {
      free_index[v] = std::int64_t(free_vertices.size());
      free_vertices.push_back(std::uint32_t(v));
    }
  const std::size_t nf = free_vertices.size();
  adj_offset.assign(nf + 1, 0);
  for (std::size_t s = 0; s < tets.size(); ++s)
    if (free_index[tets[s]] >= 0) ++adj_offset[std::size_t(free_index[tets[s]]) + 1];
  for (std::size_t b = 0; b < nf; ++b) adj_offset[b + 1] += adj_offset[b];
  adj_slot.resize(adj_offset[nf]);
  std::vector<std::uint32_t> fill(adj_offset.begin(), adj_offset.end() - 1);
  for (std::size_t s = 0; s < tets.size(); ++s)
    if (free_index[tets[s]] >= 0) adj_slot[fill[std::size_t(free_index[tets[s]])]++] = std::uint32_t(s);
}

void FreeVertexLayout::load(const double* vars, double* x) const {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, free_vertices.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t b = r.begin(); b < r.end(); ++b)
      for (int i = 0; i < 3; ++i) x[3 * std::size_t(free_vertices[b]) + i] = vars[3 * b + i];
  });
}

void FreeVertexLayout::extract(const double* x, double* vars) const {
  for (std::size_t b = 0; b < free_vertices.size(); ++b)
    for (int i = 0; i < 3; ++i) vars[3 * b + i] = x[3 * std::size_t(free_vertices[b]) + i];
}

void FreeVertexLayout::gather(const double* tet_grad, double* grad) const {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, free_vertices.size(), 2048), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t b = r.begin(); b < r.end(); ++b) {
      double g[3] = {0, 0, 0};
      for (std::uint32_t k = adj_offset[b]; k < adj_offset[b + 1]; ++k) {
        const std::uint32_t s = adj_slot[k];
        const double* src = tet_grad + 12 * std::size_t(s / 4) + 3 * std::size_t(s % 4);
        for (int i = 0; i < 3; ++i) g[i] += src[i];
      }
      for (int i = 0; i < 3; ++i) grad[3 * b + i] = g[i];
    }
  });
}

void BoxFrame::fit(const std::vector<double>& xyz, double side, const char* who) {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (std::size_t v = 0; v < xyz.size() / 3; ++v)
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], xyz[3 * v + i]);
      hi[i] = std::max(hi[i], xyz[3 * v + i]);
    }
  double extent = 0;
  for (int i = 0; i < 3; ++i) {
    center[i] = 0.5 * (lo[i] + hi[i]);
    extent = std::max(extent, hi[i] - lo[i]);
  }
  if (!(extent > 0) || !std::isfinite(extent))
    throw Error(ErrorKind::BadInput, "", 0, std::string(who) + ": degenerate or non-finite target");
  scale = side / extent;
}

std::vector<double> BoxFrame::to_scaled(const std::vector<double>& xyz) const {
  std::vector<double> x(xyz.size());
  for (std::size_t v = 0; v < xyz.size() / 3; ++v)
    for (int i = 0; i < 3; ++i) x[3 * v + i] = (xyz[3 * v + i] - center[i]) * scale;
  return x;
}

void BoxFrame::write_back(const FreeVertexLayout& layout, const double* vars, std::vector<double>& target_xyz) const {
  const double inv = 1.0 / scale;
  for (std::size_t b = 0; b < layout.free_vertices.size(); ++b)
    for (int i = 0; i < 3; ++i) target_xyz[3 * std::size_t(layout.free_vertices[b]) + i] = vars[3 * b + i] * inv + center[i];
}

LBFGSpp::LBFGSParam<double> lbfgs_param(int max_iterations, double gtol, double ftol, int linesearch) {
  LBFGSpp::LBFGSParam<double> p;
  p.linesearch = linesearch;
  p.m = 7;
  p.epsilon = gtol;
  p.epsilon_rel = 0;
  if (ftol > 0) {
    p.past = 1;
    p.delta = ftol;
  }
  p.max_iterations = max_iterations;
  p.max_linesearch = 40;
  return p;
}

bool GuardedObjective::exactly_certified(const double* vars) {
  frame->write_back(*layout, vars, *candidate);
  return count_nonpositive(*candidate, *tets) == 0;
}

bool GuardedObjective::stalled(const Eigen::VectorXd& x) {
  if (stall_evaluations <= 0) return false;
  if (double_nonpositive < fewest_nonpositive) {
    fewest_nonpositive = double_nonpositive;
    fewest_at = evaluations;
    fewest_x = x;
  }
  return fewest_nonpositive <= stall_max_bad && evaluations - fewest_at >= stall_evaluations;
}

bool GuardedObjective::finished(const Eigen::VectorXd& x) {
  if (!try_finish || double_nonpositive == 0 || double_nonpositive > finish_max_bad || double_nonpositive >= finish_tried_at) return false;
  finish_tried_at = double_nonpositive;
  return try_finish(x.data());
}

double GuardedObjective::operator()(const Eigen::VectorXd& x, Eigen::VectorXd& grad) {
  ++evaluations;
  if (past_deadline()) {
    last_x = x;
    throw TimeStop{};
  }
  bool all_positive = false;
  const double e = evaluate(x.data(), grad.data(), &all_positive);
  if (barrier && !all_positive) {
    grad.setZero();
    return std::numeric_limits<double>::infinity();
  }
  if (track_lowest && all_positive && e < lowest_energy) {
    lowest_energy = e;
    lowest_x = x;
  }
  if (stop_when_certified && all_positive && evaluations >= next_exact_check) {
    if (exactly_certified(x.data())) {
      last_x = x;
      throw CertifiedStop{};
    }
    next_exact_check = evaluations + check_period;
  }
  if (finished(x)) {
    last_x = x;
    throw FinishedStop{};
  }
  if (stalled(x)) {
    last_x = fewest_x;
    throw StallStop{};
  }
  return e;
}

}  // namespace volmap::untangle
