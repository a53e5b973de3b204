// collinear.hpp — exact collinearity of three points in 3D (internal header of the volume wing):
// collinear iff the projections on the three coordinate planes are collinear (exact orient2d).
#pragma once

#include <volmap/predicates.hpp>

namespace volmap {

inline bool collinear_exact(const double* a, const double* b, const double* c) {
  const double a_xy[2] = {a[0], a[1]}, b_xy[2] = {b[0], b[1]}, c_xy[2] = {c[0], c[1]};
  const double a_yz[2] = {a[1], a[2]}, b_yz[2] = {b[1], b[2]}, c_yz[2] = {c[1], c[2]};
  const double a_zx[2] = {a[2], a[0]}, b_zx[2] = {b[2], b[0]}, c_zx[2] = {c[2], c[0]};
  return orient2d(a_xy, b_xy, c_xy) == 0 && orient2d(a_yz, b_yz, c_yz) == 0 && orient2d(a_zx, b_zx, c_zx) == 0;
}

}  // namespace volmap
