// tutte3d.cpp — Tutte 3D baseline: uniform Laplacian over unique edges, hard Dirichlet boundary,
// one sparse Cholesky factorisation of L_II (SimplicialLLT by default, as cinolib; or SimplicialLDLT)
// with three right-hand sides (mapping.md §2).
// L_II is assembled directly in compressed-column form (lower triangle): free vertices are numbered
// in increasing vertex id, so the sorted edge list (a<b) yields each column's rows already sorted.
#include <volmap/core/error.hpp>
#include <volmap/core/time_budget.hpp>
#include <volmap/volume/tutte3d.hpp>

#include <Eigen/Sparse>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <string>
#include <utility>

namespace volmap {

std::vector<std::uint32_t> unique_tet_edges(const TetMesh& mesh) {
  const Span<VertexId> ev = mesh.edge_vertex_array();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs(ev.size() / 2);
  for (std::size_t e = 0; e < pairs.size(); ++e) pairs[e] = std::minmax(ev[2 * e].idx(), ev[2 * e + 1].idx());
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());  // a pinched edge has one id per fan
  std::vector<std::uint32_t> out;
  out.reserve(2 * pairs.size());
  for (const auto& [a, b] : pairs) {
    out.push_back(a);
    out.push_back(b);
  }
  return out;
}

std::vector<std::uint32_t> unique_tet_edges(const TetMeshData& mesh) {
  // Counting sort of the 6 edges per tet by their smaller endpoint a, then a small sort + unique of
  // each a's bucket of larger endpoints b (buckets hold ~30 entries): O(#tets), no hashing, no maps.
  const std::size_t nt = mesh.num_tets();
  const std::size_t nv = mesh.num_vertices();
  static constexpr int kEdgeLocal[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  std::vector<std::uint32_t> offset(nv + 1, 0);
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint32_t* tet = &mesh.tets[4 * t];
    for (int k = 0; k < 4; ++k) {
      if (tet[k] >= nv) {
        throw_bad_input("", 0, "tet " + std::to_string(t) + " references vertex " + std::to_string(tet[k]) +
                                   " but the mesh has " + std::to_string(nv) + " vertices");
      }
    }
    for (int e = 0; e < 6; ++e) {
      const std::uint32_t a = tet[kEdgeLocal[e][0]], b = tet[kEdgeLocal[e][1]];
      if (a == b) throw_bad_input("", 0, "tet " + std::to_string(t) + " repeats vertex " + std::to_string(a));
      ++offset[std::min(a, b) + 1];
    }
  }
  for (std::size_t v = 0; v < nv; ++v) offset[v + 1] += offset[v];
  std::vector<std::uint32_t> larger(6 * nt);
  {
    std::vector<std::uint32_t> cursor(offset.begin(), offset.end() - 1);
    for (std::size_t t = 0; t < nt; ++t) {
      const std::uint32_t* tet = &mesh.tets[4 * t];
      for (int e = 0; e < 6; ++e) {
        const std::uint32_t a = tet[kEdgeLocal[e][0]], b = tet[kEdgeLocal[e][1]];
        larger[cursor[std::min(a, b)]++] = std::max(a, b);
      }
    }
  }
  // Sort + unique each bucket in place; count the unique entries per vertex.
  std::vector<std::uint32_t> unique_count(nv + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t v = r.begin(); v != r.end(); ++v) {
      std::uint32_t* first = larger.data() + offset[v];
      std::uint32_t* last = larger.data() + offset[v + 1];
      std::sort(first, last);
      unique_count[v + 1] = static_cast<std::uint32_t>(std::unique(first, last) - first);
    }
  });
  for (std::size_t v = 0; v < nv; ++v) unique_count[v + 1] += unique_count[v];
  std::vector<std::uint32_t> edges(2 * static_cast<std::size_t>(unique_count[nv]));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t v = r.begin(); v != r.end(); ++v) {
      std::size_t out = 2 * static_cast<std::size_t>(unique_count[v]);
      const std::uint32_t count = unique_count[v + 1] - unique_count[v];
      for (std::uint32_t k = 0; k < count; ++k) {
        edges[out++] = static_cast<std::uint32_t>(v);
        edges[out++] = larger[offset[v] + k];
      }
    }
  });
  return edges;
}

Tutte3dTimings solve_uniform_laplacian(std::size_t num_vertices, const std::vector<std::uint32_t>& edges,
                                       const std::vector<std::uint8_t>& locked, std::vector<double>& xyz,
                                       SparseFactorization factorization) {
  if (locked.size() != num_vertices || xyz.size() != 3 * num_vertices || edges.size() % 2 != 0) {
    throw_bad_input("", 0, "solve_uniform_laplacian: size mismatch (locked mask, positions or edge list)");
  }
  Tutte3dTimings timings;
  TimeBudget phase;  // a stopwatch (no limit)

  // Free vertices numbered in increasing id: column[v] (or -1 when locked).
  constexpr std::int32_t kFixed = -1;
  std::vector<std::int32_t> column(num_vertices, kFixed);
  std::int32_t num_free = 0;
  for (std::size_t v = 0; v < num_vertices; ++v) {
    if (!locked[v]) column[v] = num_free++;
  }
  if (num_free == 0) return timings;

  const std::size_t num_edges = edges.size() / 2;
  std::vector<double> degree(num_free, 0.0);
  Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(num_free, 3);
  std::vector<std::int32_t> lower_count(num_free, 0);  // strictly-lower entries per column
  for (std::size_t e = 0; e < num_edges; ++e) {
    const std::uint32_t a = edges[2 * e], b = edges[2 * e + 1];
    if (a >= num_vertices || b >= num_vertices || a >= b) {
      throw_bad_input("", 0, "solve_uniform_laplacian: edge list not sorted unique pairs a<b in range");
    }
    const std::int32_t ca = column[a], cb = column[b];
    if (ca != kFixed) {
      degree[ca] += 1.0;
      if (cb != kFixed) {
        ++lower_count[ca];
      } else {
        rhs(ca, 0) += xyz[3 * b];
        rhs(ca, 1) += xyz[3 * b + 1];
        rhs(ca, 2) += xyz[3 * b + 2];
      }
    }
    if (cb != kFixed) {
      degree[cb] += 1.0;
      if (ca == kFixed) {
        rhs(cb, 0) += xyz[3 * a];
        rhs(cb, 1) += xyz[3 * a + 1];
        rhs(cb, 2) += xyz[3 * a + 2];
      }
    }
  }

  // Compressed columns of the lower triangle: diagonal first, then rows col[b] > col[a], sorted.
  Eigen::SparseMatrix<double, Eigen::ColMajor, int> matrix(num_free, num_free);
  std::size_t nnz = static_cast<std::size_t>(num_free);
  for (std::int32_t c = 0; c < num_free; ++c) nnz += static_cast<std::size_t>(lower_count[c]);
  matrix.resizeNonZeros(static_cast<Eigen::Index>(nnz));
  int* outer = matrix.outerIndexPtr();
  int* inner = matrix.innerIndexPtr();
  double* values = matrix.valuePtr();
  outer[0] = 0;
  for (std::int32_t c = 0; c < num_free; ++c) outer[c + 1] = outer[c] + 1 + lower_count[c];
  std::vector<int> cursor(outer, outer + num_free);
  for (std::int32_t c = 0; c < num_free; ++c) {
    inner[cursor[c]] = c;
    values[cursor[c]] = degree[c];
    ++cursor[c];
  }
  for (std::size_t e = 0; e < num_edges; ++e) {
    const std::int32_t ca = column[edges[2 * e]], cb = column[edges[2 * e + 1]];
    if (ca == kFixed || cb == kFixed) continue;
    inner[cursor[ca]] = cb;
    values[cursor[ca]] = -1.0;
    ++cursor[ca];
  }
  timings.assembly = phase.elapsed();

  using Matrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
  const char* singular = "uniform Laplacian is singular: a group of free vertices has no path to a locked vertex";
  Eigen::MatrixX3d solution;
  // SPD check: every pivot must be clearly positive (a free component without a locked vertex makes
  // the Laplacian singular: a pivot ~0, or a failed factorisation).
  constexpr double kMinPivot = 1e-12;
  if (factorization == SparseFactorization::LLT) {
    Eigen::SimplicialLLT<Matrix, Eigen::Lower, Eigen::AMDOrdering<int>> solver;
    phase = TimeBudget();
    solver.analyzePattern(matrix);
    solver.factorize(matrix);
    bool ok = solver.info() == Eigen::Success;
    if (ok) {
      const Matrix& l = solver.matrixL();
      // Column-major L: the first stored entry of each column is its diagonal.
      for (Eigen::Index c = 0; ok && c < l.outerSize(); ++c) {
        const double diagonal = l.valuePtr()[l.outerIndexPtr()[c]];
        ok = diagonal * diagonal > kMinPivot;
      }
    }
    if (!ok) throw Error(ErrorKind::Failed, "", 0, singular);
    timings.factorization = phase.elapsed();
    phase = TimeBudget();
    solution = solver.solve(rhs);
  } else if (factorization == SparseFactorization::ConjugateGradient) {
    Eigen::ConjugateGradient<Matrix, Eigen::Lower, Eigen::DiagonalPreconditioner<double>> solver;
    phase = TimeBudget();
    solver.setTolerance(1e-12);
    solver.setMaxIterations(std::max<Eigen::Index>(1000, 10 * static_cast<Eigen::Index>(num_free)));
    solver.compute(matrix);
    timings.factorization = phase.elapsed();
    phase = TimeBudget();
    solution = solver.solve(rhs);
    if (solver.info() != Eigen::Success) {
      throw Error(ErrorKind::Failed, "", 0, "conjugate gradient did not converge (singular Laplacian?)");
    }
  } else {
    Eigen::SimplicialLDLT<Matrix, Eigen::Lower, Eigen::AMDOrdering<int>> solver;
    phase = TimeBudget();
    solver.analyzePattern(matrix);
    solver.factorize(matrix);
    bool ok = solver.info() == Eigen::Success;
    const auto d = solver.vectorD();
    for (Eigen::Index i = 0; ok && i < d.size(); ++i) ok = d[i] > kMinPivot;
    if (!ok) throw Error(ErrorKind::Failed, "", 0, singular);
    timings.factorization = phase.elapsed();
    phase = TimeBudget();
    solution = solver.solve(rhs);
  }
  for (std::size_t v = 0; v < num_vertices; ++v) {
    const std::int32_t c = column[v];
    if (c == kFixed) continue;
    xyz[3 * v] = solution(c, 0);
    xyz[3 * v + 1] = solution(c, 1);
    xyz[3 * v + 2] = solution(c, 2);
  }
  timings.solve = phase.elapsed();
  return timings;
}

Tutte3dResult tutte3d(const TetMeshData& mesh, const BoundaryMap& map, const Tutte3dOptions& options) {
  const std::size_t nv = mesh.num_vertices();
  if (mesh.xyz.size() != 3 * nv || mesh.tets.size() % 4 != 0) {
    throw_bad_input("", 0, "tutte3d: malformed mesh arrays");
  }
  if (map.xyz.size() != 3 * map.vids.size()) throw_bad_input("", 0, "tutte3d: malformed boundary map arrays");

  Tutte3dResult result;
  TimeBudget phase;  // a stopwatch (no limit)
  const std::vector<std::uint32_t> edges = unique_tet_edges(mesh);
  result.timings.edges = phase.elapsed();
  result.num_edges = edges.size() / 2;

  std::vector<std::uint8_t> locked(nv, 0);
  result.xyz.assign(3 * nv, 0.0);
  for (std::size_t k = 0; k < map.vids.size(); ++k) {
    const std::uint32_t v = map.vids[k];
    if (v >= nv) {
      throw_bad_input("", 0, "boundary map vertex id " + std::to_string(v) + " is out of range (mesh has " +
                                 std::to_string(nv) + " vertices)");
    }
    if (locked[v]) throw_bad_input("", 0, "boundary map lists vertex id " + std::to_string(v) + " twice");
    locked[v] = 1;
    for (int i = 0; i < 3; ++i) result.xyz[3 * v + i] = map.xyz[3 * k + i];
  }
  result.num_fixed = map.vids.size();
  result.num_free = nv - result.num_fixed;

  const Tutte3dTimings solve_timings = solve_uniform_laplacian(nv, edges, locked, result.xyz, options.factorization);
  result.timings.assembly = solve_timings.assembly;
  result.timings.factorization = solve_timings.factorization;
  result.timings.solve = solve_timings.solve;
  return result;
}

}  // namespace volmap
