// cone_repair.cpp — B1 of docs/mapping.md §7: strict-kernel LP and the vertex-star pre-step.
// Orientation: for an outward face (a,b,c) (kTetFaceLocal order of a VOLMAP-positive tet), a point q
// is on the tet's side iff orient3d(a,b,c,q) > 0, i.e. n·(q − a) > 0 with n = (c−a)×(b−a).
// The LP is a dense condensed-tableau simplex (Bland's rule) in 4 variables (q, s): maximise s
// subject to n̂_F·(q − a_F) ≥ s for every face and q in the faces' bounding box; solved in double,
// the point is then verified with exact orient3d.
#include <volmap/cone_repair.hpp>

#include <volmap/boundary_faces.hpp>
#include <volmap/predicates.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace volmap {

namespace {

// maximise c·x s.t. A x <= b, x >= 0 with b >= 0 (origin feasible). A is m×n row-major.
// Returns false when unbounded or out of iterations; x receives the solution.
bool simplex_max(int m, int n, std::vector<double>& A, std::vector<double>& b, std::vector<double> c, double* x) {
  std::vector<int> row_label(m), col_label(n);  // labels: 0..n-1 original vars, n.. slacks
  for (int j = 0; j < n; ++j) col_label[j] = j;
  for (int i = 0; i < m; ++i) row_label[i] = n + i;
  const double eps = 1e-12;
  for (int iter = 0; iter < 50 * (m + n); ++iter) {
    int e = -1;
    for (int j = 0; j < n; ++j)
      if (c[j] > eps && (e < 0 || col_label[j] < col_label[e])) e = j;
    if (e < 0) break;  // optimal
    int r = -1;
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < m; ++i) {
      const double a = A[std::size_t(i) * n + e];
      if (a > eps) {
        const double ratio = b[i] / a;
        if (ratio < best - 1e-15 || (ratio <= best + 1e-15 && r >= 0 && row_label[i] < row_label[r])) {
          best = ratio;
          r = i;
        }
      }
    }
    if (r < 0) return false;  // unbounded
    const double piv = A[std::size_t(r) * n + e];
    // Row r.
    for (int j = 0; j < n; ++j)
      if (j != e) A[std::size_t(r) * n + j] /= piv;
    b[r] /= piv;
    A[std::size_t(r) * n + e] = 1.0 / piv;
    for (int i = 0; i < m; ++i) {
      if (i == r) continue;
      const double aie = A[std::size_t(i) * n + e];
      if (aie == 0) continue;
      for (int j = 0; j < n; ++j)
        if (j != e) A[std::size_t(i) * n + j] -= aie * A[std::size_t(r) * n + j];
      b[i] -= aie * b[r];
      A[std::size_t(i) * n + e] = -aie / piv;
    }
    const double ce = c[e];
    for (int j = 0; j < n; ++j)
      if (j != e) c[j] -= ce * A[std::size_t(r) * n + j];
    c[e] = -ce / piv;
    std::swap(row_label[r], col_label[e]);
  }
  for (int j = 0; j < n; ++j) x[j] = 0;
  for (int i = 0; i < m; ++i)
    if (row_label[i] < n) x[row_label[i]] = b[i];
  return true;
}

}  // namespace

bool strict_kernel_point(const std::vector<double>& tri, double* q) {
  const std::size_t nf = tri.size() / 9;
  if (nf == 0) return false;
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (std::size_t k = 0; k < 3 * nf; ++k)
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], tri[3 * k + i]);
      hi[i] = std::max(hi[i], tri[3 * k + i]);
    }
  const double diag = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
  if (!(diag > 0)) return false;
  // Work in a frame centred at lo and scaled by 1/diag (conditioning).
  const double inv = 1.0 / diag;
  const double S0 = 2.0;
  const int n = 4, m = int(nf) + 4;
  std::vector<double> A(std::size_t(m) * n, 0.0), b(m, 0.0);
  for (std::size_t f = 0; f < nf; ++f) {
    const double* a = &tri[9 * f];
    const double* bb = a + 3;
    const double* c = a + 6;
    double u[3], v[3], nn[3];
    for (int i = 0; i < 3; ++i) {
      u[i] = (c[i] - a[i]) * inv;
      v[i] = (bb[i] - a[i]) * inv;
    }
    nn[0] = u[1] * v[2] - u[2] * v[1];
    nn[1] = u[2] * v[0] - u[0] * v[2];
    nn[2] = u[0] * v[1] - u[1] * v[0];
    const double len = std::sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
    if (!(len > 0)) return false;  // degenerate face: no strict kernel
    // n̂·(q' − a') ≥ s  ⇔  −n̂·q' + s' ≤ −n̂·a' + S0   (q' = (q − lo)/diag, s' = s + S0)
    double rhs = S0;
    for (int i = 0; i < 3; ++i) {
      const double ni = nn[i] / len;
      A[f * n + i] = -ni;
      rhs -= ni * (a[i] - lo[i]) * inv;
    }
    A[f * n + 3] = 1.0;
    b[f] = rhs;
    if (b[f] < 0) return false;
  }
  for (int i = 0; i < 3; ++i) {
    A[(nf + i) * n + i] = 1.0;
    b[nf + i] = (hi[i] - lo[i]) * inv;
  }
  A[(nf + 3) * n + 3] = 1.0;
  b[nf + 3] = S0 + 1.0;
  double x[4];
  if (!simplex_max(m, n, A, b, {0, 0, 0, 1}, x)) return false;
  if (!(x[3] - S0 > 0)) return false;
  for (int i = 0; i < 3; ++i) q[i] = lo[i] + x[i] * diag;
  for (std::size_t f = 0; f < nf; ++f)
    if (orient3d(&tri[9 * f], &tri[9 * f + 3], &tri[9 * f + 6], q) <= 0) return false;
  return true;
}

ConeRepairResult cone_repair(TetMeshData& source, std::vector<std::uint8_t>&, std::vector<double>&, const ConeRepairOptions&) {
  ConeRepairResult r;
  r.tets_before = r.tets_after = source.num_tets();
  return r;  // patch replacement not implemented yet
}

RelocationResult relocate_into_link_kernels(const std::vector<std::uint32_t>& tets, const std::vector<std::uint8_t>& locked,
                                            std::vector<double>& X, int max_sweeps) {
  RelocationResult res;
  const std::size_t nv = X.size() / 3, nt = tets.size() / 4;
  std::vector<std::uint32_t> off(nv + 1, 0), slot(4 * nt);
  for (std::uint32_t v : tets) ++off[v + 1];
  for (std::size_t v = 0; v < nv; ++v) off[v + 1] += off[v];
  {
    std::vector<std::uint32_t> fill(off.begin(), off.end() - 1);
    for (std::size_t s = 0; s < 4 * nt; ++s) slot[fill[tets[s]]++] = std::uint32_t(s);
  }
  std::vector<std::int8_t> sign(nt);
  auto count_bad = [&] {
    const TetSignCounts c = orient3d_tets(X.data(), nv, tets.data(), nt, sign.data());
    return c.zero + c.negative;
  };
  res.nonpositive_before = count_bad();
  std::size_t bad = res.nonpositive_before;
  std::vector<double> tri;
  std::vector<std::uint8_t> mark(nv, 0);
  for (int sweep = 0; sweep < max_sweeps && bad > 0; ++sweep) {
    res.sweeps = sweep + 1;
    std::vector<std::uint32_t> cand;
    for (std::size_t t = 0; t < nt; ++t)
      if (sign[t] <= 0)
        for (int i = 0; i < 4; ++i) {
          const std::uint32_t v = tets[4 * t + i];
          if (!locked[v] && !mark[v]) {
            mark[v] = 1;
            cand.push_back(v);
          }
        }
    for (auto v : cand) mark[v] = 0;
    std::size_t moved = 0;
    for (std::uint32_t v : cand) {
      tri.clear();
      for (std::uint32_t k = off[v]; k < off[v + 1]; ++k) {
        const std::uint32_t s = slot[k];
        const std::uint32_t* tv = &tets[4 * std::size_t(s / 4)];
        const std::uint8_t* fl = kTetFaceLocal[s % 4];
        for (int j = 0; j < 3; ++j)
          for (int i = 0; i < 3; ++i) tri.push_back(X[3 * std::size_t(tv[fl[j]]) + i]);
      }
      double q[3];
      if (!strict_kernel_point(tri, q)) continue;
      for (int i = 0; i < 3; ++i) X[3 * std::size_t(v) + i] = q[i];
      ++moved;
    }
    res.moved += moved;
    const std::size_t now = count_bad();
    bad = now;
    if (moved == 0) break;
  }
  res.nonpositive_after = bad;
  return res;
}

}  // namespace volmap
