// The one doctest main shared by every test executable.
// VOLMAP_TEST_FTZ_DAZ=1 runs the suite with the x86 MXCSR flush-to-zero and denormals-are-zero bits
// set (threads created later inherit them): scripts/test.sh uses it for the predicate tests, which
// must stay exact in that environment.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstdlib>
#include <cstring>

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

int main(int argc, char** argv) {
  const char* ftz = std::getenv("VOLMAP_TEST_FTZ_DAZ");
  if (ftz && std::strcmp(ftz, "1") == 0) {
#if defined(__SSE2__)
    _mm_setcsr(_mm_getcsr() | 0x8040u);  // FTZ (bit 15) | DAZ (bit 6)
#endif
  }
  doctest::Context context(argc, argv);
  return context.run();
}
