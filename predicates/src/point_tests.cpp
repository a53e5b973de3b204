// point_tests.cpp — exact point equality and 3D collinearity (see <volmap/predicates.hpp>).
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

}  // namespace volmap
