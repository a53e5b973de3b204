// fp_env.hpp — the predicates' floating-point environment guard (internal).
// The double filters' error bounds assume IEEE binary64, round-to-nearest and gradual underflow. A
// caller may run with MXCSR flush-to-zero / denormals-are-zero (-ffast-math startup code, audio and
// game engines) or another rounding mode. Every public entry point therefore checks MXCSR (one
// stmxcsr, predicted branch) and, when it is not the default, re-enters itself under the default
// environment and restores the caller's afterwards, so results stay exact in every environment.
// Regression test: tests/predicates/test_predicates_ftz.cpp. Non-x86 targets: no check (no MXCSR).
#pragma once

#if defined(__SSE2__)
#include <xmmintrin.h>
#define VOLMAP_PREDICATES_HAVE_MXCSR 1
#endif

namespace volmap::detail {

#ifdef VOLMAP_PREDICATES_HAVE_MXCSR
// FTZ (bit 15), rounding control (bits 13-14), DAZ (bit 6).
constexpr unsigned kNonDefaultFpBits = 0xE040u;

inline bool fp_env_is_default() { return (_mm_getcsr() & kNonDefaultFpBits) == 0u; }

// Runs `f` with FTZ/DAZ cleared and round-to-nearest, restoring the caller's MXCSR (also on throw).
template <class F>
__attribute__((noinline, cold)) auto in_default_fp_env(F f) {
  struct Restore {
    unsigned saved = _mm_getcsr();
    Restore() { _mm_setcsr(saved & ~kNonDefaultFpBits); }
    ~Restore() { _mm_setcsr(saved); }
  } restore;
  return f();
}
#define VOLMAP_REQUIRE_DEFAULT_FP_ENV(call)                                                       \
  do {                                                                                            \
    if (__builtin_expect(!::volmap::detail::fp_env_is_default(), 0))                              \
      return ::volmap::detail::in_default_fp_env([&] { return call; });                           \
  } while (0)
#else
#define VOLMAP_REQUIRE_DEFAULT_FP_ENV(call) \
  do {                                      \
  } while (0)
#endif

}  // namespace volmap::detail
