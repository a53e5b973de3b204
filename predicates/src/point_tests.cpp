// point_tests.cpp — exact point equality, 3D collinearity and half-planes about a line (see
// <volmap/predicates.hpp>).
// points_equal compares bit patterns, not doubles: under DAZ the hardware compares a subnormal as
// zero, so `p[k] == q[k]` would call distinct points equal. collinear is three exact orient2d
// (each public call guards the FP environment itself).
#include <volmap/predicates.hpp>

#include <cstdint>
#include <cstring>

namespace volmap {
namespace {

// Value equality of two doubles without FP arithmetic: same bits, or both ±0; NaN equals nothing.
bool same_value(double x, double y) {
  std::uint64_t u, v;
  std::memcpy(&u, &x, sizeof u);
  std::memcpy(&v, &y, sizeof v);
  constexpr std::uint64_t kInfShifted = 0x7ff0000000000000ull << 1;  // sign bit shifted out
  if (u != v) return ((u | v) << 1) == 0;                          // +0 and -0
  return (u << 1) <= kInfShifted;                                  // not NaN
}

}  // namespace

bool points_equal(const double* p, const double* q) {
  return same_value(p[0], q[0]) && same_value(p[1], q[1]) && same_value(p[2], q[2]);
}

// (b−a)×(c−a) has the three coordinate-plane orient2d values as components (up to sign), so it is
// zero iff all three are.
bool collinear(const double* a, const double* b, const double* c) {
  const double a_xy[2] = {a[0], a[1]}, b_xy[2] = {b[0], b[1]}, c_xy[2] = {c[0], c[1]};
  const double a_yz[2] = {a[1], a[2]}, b_yz[2] = {b[1], b[2]}, c_yz[2] = {c[1], c[2]};
  const double a_zx[2] = {a[2], a[0]}, b_zx[2] = {b[2], b[0]}, c_zx[2] = {c[2], c[0]};
  return orient2d(a_xy, b_xy, c_xy) == 0 && orient2d(a_yz, b_yz, c_yz) == 0 && orient2d(a_zx, b_zx, c_zx) == 0;
}

bool same_half_plane(const double* a, const double* b, const double* p, const double* q) {
  if (orient3d(a, b, p, q) != 0) return false;
  static constexpr int kAxes[3][2] = {{0, 1}, {1, 2}, {2, 0}};
  for (const auto& ax : kAxes) {
    const double a2[2] = {a[ax[0]], a[ax[1]]}, b2[2] = {b[ax[0]], b[ax[1]]};
    const double p2[2] = {p[ax[0]], p[ax[1]]}, q2[2] = {q[ax[0]], q[ax[1]]};
    const int sp = orient2d(a2, b2, p2);
    if (sp != 0) return orient2d(a2, b2, q2) == sp;
  }
  return false;  // (a, b, p) degenerate in every coordinate plane: p on the line ab
}

}  // namespace volmap
