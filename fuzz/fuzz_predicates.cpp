// libFuzzer target: the batch orientation predicate on arbitrary bit patterns. Non-finite input must
// be reported (!ok), never signed; finite input must agree with the exact rational evaluation, and
// the Plücker side product of the lines (p0,p1) and (p2,p3) must have the opposite sign.
#include <volmap/predicates_rational.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  constexpr std::size_t kPoint = 3 * sizeof(double);
  const std::size_t points = size / kPoint;
  if (points < 4 || points > 64) return 0;
  double xyz[3 * 64];
  std::memcpy(xyz, data, points * kPoint);
  bool finite = true;
  for (std::size_t i = 0; i < 3 * points; ++i) finite = finite && std::isfinite(xyz[i]);
  // Tets over consecutive points (0,1,2,3), (1,2,3,4), ...
  std::uint32_t tets[4 * 61];
  const std::size_t num_tets = points - 3;
  for (std::size_t t = 0; t < num_tets; ++t)
    for (int k = 0; k < 4; ++k) tets[4 * t + k] = static_cast<std::uint32_t>(t + k);
  std::int8_t signs[61];
  const auto counts = volmap::orient3d_tets(xyz, points, tets, num_tets, signs);
  if (!finite) {
    if (counts.ok) __builtin_trap();
    return 0;
  }
  if (!counts.ok) __builtin_trap();
  for (std::size_t t = 0; t < num_tets; ++t) {
    volmap::Rational p[4][3];
    for (int k = 0; k < 4; ++k)
      for (int c = 0; c < 3; ++c) p[k][c] = volmap::Rational(xyz[3 * (t + k) + c]);
    if (volmap::orient3d(p[0], p[1], p[2], p[3]) != signs[t]) __builtin_trap();
    if (volmap::orient3d(&xyz[3 * t], &xyz[3 * t + 3], &xyz[3 * t + 6], &xyz[3 * t + 9]) != signs[t]) __builtin_trap();
    const volmap::Rational side = volmap::side(volmap::plucker_line(&xyz[3 * t], &xyz[3 * t + 3]),
                                               volmap::plucker_line(&xyz[3 * t + 6], &xyz[3 * t + 9]));
    if ((side > 0 ? 1 : side < 0 ? -1 : 0) != -signs[t]) __builtin_trap();
  }
  return 0;
}
