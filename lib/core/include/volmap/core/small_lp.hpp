// volmap/core/small_lp.hpp — a dense simplex for small linear programs in double (a few variables,
// tens to hundreds of rows): the kernel LP of docs/mapping.md §7 and the sphere map's balancing
// steps. Never trusted alone: every caller verifies what it does with the result exactly.
// Form: maximise c·x subject to A x <= b, x >= 0, with b >= 0 (the origin feasible); A is m×n
// row-major, edited in place (as b). Entering column: Bland's rule (smallest label). Leaving row:
// Harris's two-pass ratio test — the step bound with every row relaxed by a feasibility tolerance
// (1e-12), then the largest pivot among the rows whose ratio is within it; entries at most 1e-9
// never pivot. Without both, rows that are (nearly) repeated pivot on round-off and the returned
// point can miss rows by far more than round-off (docs/mapping.md §7).
#pragma once

#include <vector>

namespace volmap {

// Returns false when the LP is unbounded; otherwise x (n doubles) receives the solution (the basis
// reached after at most 50 (m + n) pivots) and, when given, `duals` (m doubles) the optimal dual
// values of the rows (>= 0, zero for a row with slack).
bool simplex_max(int m, int n, std::vector<double>& A, std::vector<double>& b, std::vector<double> c, double* x,
                 double* duals = nullptr);

}  // namespace volmap
