// volmap/volume/kernel_lp.hpp — strict kernel points of oriented triangle sets (docs/mapping.md §7):
// the Chebyshev-centre LP in double, verified with exact orient3d.
// Orientation: a triangle (a,b,c) is given in the outward order of a VOLMAP-positive tet's face
// (kTetFace); a point q is on the tet's (inner) side iff orient3d(a,b,c,q) > 0, i.e. n·(q − a) > 0
// with n = (c − a) × (b − a). Triangles are 9 doubles each (three positions).
// The LP maximises s subject to n̂_F·(q − a_F) >= s for every triangle F and q in the triangles'
// bounding box, in a frame centred at the box corner and scaled by 1/diagonal: 4 variables, a dense
// condensed-tableau simplex (Bland's entering rule, Harris's ratio test). A double result is never
// trusted alone: a kernel point is returned only after the exact check. The same simplex also
// solves the homogeneous max-min LP of max_min_slack_in_box (any dimension), used to pick rows for
// exact certificates.
#pragma once

#include <volmap/predicates.hpp>

#include <vector>

namespace volmap {

// n = ((c − a)·scale) × ((b − a)·scale): points to the inner side of the outward triangle (a,b,c).
// Returns |n| (0 for a triangle degenerate in double).
double inward_face_normal(const double* a, const double* b, const double* c, double scale, double* n);

// Chebyshev centre of the kernel LP, in double. Triangles whose normal vanishes in double are left
// out (the exact verification rejects them). Returns false when the LP could not be set up or solved;
// otherwise q is the max-min point and *slack the optimal s in the normalised frame (> 0 iff the
// double LP found an interior point).
bool chebyshev_point(const std::vector<double>& triangles, double* q, double* slack);

// The same LP with q in the box [lo, hi] (3 doubles each) instead of the triangles' bounding box,
// the frame scaled by the box's diagonal. Every triangle vertex must lie in the box (the origin of
// the frame is then feasible). For part of a closed surface whose other vertices lie in the box
// too: a kernel point of the whole surface lies in its hull, hence in the box, so a clearly
// negative slack here rules one out. A box with a zero diagonal returns false.
bool chebyshev_point_in_box(const std::vector<double>& triangles, const double* lo, const double* hi, double* q, double* slack);

// Exact: q strictly on the inner side of every triangle (fp: the caller's environment scope).
bool verified_inside(const FpEnvironmentScope& fp, const std::vector<double>& triangles, const double* q);

// A strict kernel point: the Chebyshev centre when its slack is positive and the exact check passes.
// Returns false when no verified point was found.
bool strict_kernel_point(const FpEnvironmentScope& fp, const std::vector<double>& triangles, double* q);
bool strict_kernel_point(const std::vector<double>& triangles, double* q);

// The same simplex on a homogeneous system: maximise s subject to r_i·x >= s for every row r_i
// (`rows`: dim doubles each, best normalised by the caller) and −1 <= x_j <= 1, s <= 1. Returns
// false when the LP could not be solved; otherwise x (dim doubles) and *slack = s (> 0 iff the
// double LP found an x strictly on the positive side of every row), and, when given, the rows'
// optimal dual values in *row_weights (>= 0). When the optimum is s = 0 with x inside the box, the
// rows with positive weight are a nonnegative combination near zero (Gordan): the rows to try first.
bool max_min_slack_in_box(const std::vector<double>& rows, int dim, double* x, double* slack,
                          std::vector<double>* row_weights = nullptr);

}  // namespace volmap
