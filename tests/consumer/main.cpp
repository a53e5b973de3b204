// Outside consumer of the installed volmap::predicates: Kettner's ulp grid must be exact.
// p = (0.5 + i*2^-53, 0.5 + j*2^-53), q = (12,12), r = (24,24): orient2d(p,q,r) is 0 exactly when
// i == j, +1 when the point is above the line y = x (j > i), -1 below.
#include <volmap/predicates.hpp>

#include <cmath>
#include <cstdio>

int main() {
  const double q[2] = {12, 12}, r[2] = {24, 24};
  const double ulp = std::ldexp(1.0, -53);
  int wrong = 0;
  for (int i = 0; i < 256; ++i)
    for (int j = 0; j < 256; ++j) {
      const double p[2] = {0.5 + i * ulp, 0.5 + j * ulp};
      const int expected = (j > i) - (j < i);
      if (volmap::orient2d(p, q, r) != expected) ++wrong;
    }
  std::printf("consumer: Kettner grid 256x256, %d wrong signs\n", wrong);
  return wrong == 0 ? 0 : 1;
}
