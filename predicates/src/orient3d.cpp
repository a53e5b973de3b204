// orient3d.cpp — the scalar orient3d fast path: a semi-static filter that is valid in EVERY
// floating-point environment, so the common call reads no MXCSR (stmxcsr alone costs more than the
// filter on current AMD cores); only inputs it cannot decide pay the environment check and go on to
// the layers of predicates.cpp (detail::orient3d_guarded). Conventions: <volmap/predicates.hpp>.
//
// Filter (our derivation). With m_x, m_y, m_z the largest |difference| per column (abs and max are
// exact), each of the six monomials of det[a−d; b−d; c−d] is ≤ P = m_x·m_y·m_z and carries at most 8
// rounded operations (3 differences, the product, the minor, the product by the third column, two
// sums), so |computed − exact| ≤ 6·γ8·P, γ8 = 8u/(1 − 8u). u = 2^-53 under round-to-nearest but 2^-52
// under a directed rounding mode, and 6·γ8(2^-52) = 1.0658e-14 < kSemiStatic = 1.1e-14 (the bound is
// itself rounded by at most 3 operations: inside the 3 % margin). Guard: every m in [2^-300, 2^300].
//   * ≤ 2^300: no intermediate exceeds 2^903, so nothing overflows (under a directed mode an overflow
//     would round to ±DBL_MAX, not inf, and could cancel: a finite det proves nothing);
//   * ≥ 2^-300: flush-to-zero / denormals-are-zero (inputs or results below 2^-1022 read or written
//     as 0) then change the result by at most ~2^-120·P, also inside the margin;
//   * NaN: det is NaN and fails the comparison; ±inf: its column maximum fails the guard.
// Decide when |det| > kSemiStatic·P. The SSE2 build expands along the z column, the AVX2 build along
// a's row; both bounds hold, both return the exact sign, they may only differ in which rare inputs
// they leave to the guarded layers.
// Dispatch: volmap::orient3d (inline in the header) calls through detail::orient3d_impl, a function
// pointer that the first call sets to the AVX2 build when the CPU has it
// (__builtin_cpu_supports("avx2")), else the SSE2/baseline build. (Not an ifunc: an ifunc resolver
// runs before sanitizer runtimes are initialised and clang rejects C++ resolvers.)
#include <volmap/predicates.hpp>

#include "layers.hpp"

#include <atomic>
#include <cmath>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace volmap {
namespace {

constexpr double kSemiStatic = 1.1e-14;
constexpr double kSemiStaticMin = 0x1p-300, kSemiStaticMax = 0x1p300;

}  // namespace

namespace detail {

#if defined(__SSE2__)
int orient3d_sse2(const double* a, const double* b, const double* c, const double* d) {
  const __m128d dxy = _mm_loadu_pd(d);
  const __m128d A = _mm_sub_pd(_mm_loadu_pd(a), dxy);  // (adx, ady)
  const __m128d B = _mm_sub_pd(_mm_loadu_pd(b), dxy);  // (bdx, bdy)
  const __m128d C = _mm_sub_pd(_mm_loadu_pd(c), dxy);  // (cdx, cdy)
  const __m128d dz = _mm_load1_pd(d + 2);
  const __m128d Z = _mm_sub_pd(_mm_loadh_pd(_mm_load_sd(a + 2), b + 2), dz);  // (adz, bdz)
  const __m128d cz = _mm_sub_sd(_mm_load_sd(c + 2), dz);                       // cdz
  const __m128d P1 = _mm_mul_pd(B, _mm_shuffle_pd(C, C, 1));  // (bdx·cdy, bdy·cdx)
  const __m128d P2 = _mm_mul_pd(C, _mm_shuffle_pd(A, A, 1));  // (cdx·ady, cdy·adx)
  const __m128d P3 = _mm_mul_pd(A, _mm_shuffle_pd(B, B, 1));  // (adx·bdy, ady·bdx)
  const __m128d M = _mm_sub_pd(_mm_unpacklo_pd(P1, P2), _mm_unpackhi_pd(P1, P2));  // (m1, m2)
  const __m128d m3 = _mm_sub_sd(P3, _mm_unpackhi_pd(P3, P3));
  const __m128d T = _mm_mul_pd(Z, M);  // (adz·m1, bdz·m2)
  const __m128d det = _mm_add_sd(_mm_add_sd(T, _mm_unpackhi_pd(T, T)), _mm_mul_sd(cz, m3));
  const __m128d sign_bit = _mm_set1_pd(-0.0);
  const __m128d mxy = _mm_max_pd(_mm_max_pd(_mm_andnot_pd(sign_bit, A), _mm_andnot_pd(sign_bit, B)),
                                 _mm_andnot_pd(sign_bit, C));  // (m_x, m_y)
  const __m128d Za = _mm_andnot_pd(sign_bit, Z);
  const __m128d mz = _mm_max_sd(_mm_max_sd(Za, _mm_unpackhi_pd(Za, Za)), _mm_andnot_pd(sign_bit, cz));
  const __m128d my = _mm_unpackhi_pd(mxy, mxy);
  const __m128d smallest = _mm_min_sd(_mm_min_sd(mxy, my), mz), largest = _mm_max_sd(_mm_max_sd(mxy, my), mz);
  const __m128d bound = _mm_mul_sd(_mm_mul_sd(_mm_mul_sd(_mm_set_sd(kSemiStatic), mxy), my), mz);
  const __m128d abs_det = _mm_andnot_pd(sign_bit, det);
  const bool decided = _mm_comige_sd(smallest, _mm_set_sd(kSemiStaticMin)) &
                       _mm_comile_sd(largest, _mm_set_sd(kSemiStaticMax)) & _mm_comigt_sd(abs_det, bound);
  if (__builtin_expect(decided, 1)) return _mm_comigt_sd(det, _mm_setzero_pd()) ? 1 : -1;
  return orient3d_guarded(a, b, c, d);
}
#else
int orient3d_sse2(const double* a, const double* b, const double* c, const double* d) {  // portable
  const double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  const double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  const double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  const double det = (adz * (bdx * cdy - cdx * bdy) + bdz * (cdx * ady - adx * cdy)) + cdz * (adx * bdy - bdx * ady);
  auto max3 = [](double x, double y, double z) {
    const double ax = std::fabs(x), ay = std::fabs(y), az = std::fabs(z);
    const double m = ax > ay ? ax : ay;
    return m > az ? m : az;
  };
  const double mx = max3(adx, bdx, cdx), my = max3(ady, bdy, cdy), mz = max3(adz, bdz, cdz);
  const double abs_det = std::fabs(det);
  auto in_range = [](double m) { return (m >= kSemiStaticMin) & (m <= kSemiStaticMax); };
  if (in_range(mx) & in_range(my) & in_range(mz) & (abs_det > kSemiStatic * mx * my * mz))
    return det > 0 ? 1 : -1;
  return orient3d_guarded(a, b, c, d);
}
#endif

#if defined(__x86_64__)
// Rows as (x, y, z, z): the z lane doubled so that no load reads past p[2].
__attribute__((target("avx2"), always_inline)) inline __m256d load_xyzz(const double* p) {
  return _mm256_blend_pd(_mm256_broadcast_sd(p + 2), _mm256_castpd128_pd256(_mm_loadu_pd(p)), 0x3);
}

__attribute__((target("avx2"))) int orient3d_avx2(const double* a, const double* b, const double* c, const double* d) {
  const __m256d D = load_xyzz(d);
  const __m256d A = _mm256_sub_pd(load_xyzz(a), D);  // (adx, ady, adz, adz)
  const __m256d B = _mm256_sub_pd(load_xyzz(b), D);
  const __m256d C = _mm256_sub_pd(load_xyzz(c), D);
  // W = B∘C.yzx − B.yzx∘C = ((b×c)_z, (b×c)_x, (b×c)_y, 0) (lane 3: a product minus itself, exactly 0),
  // T = A.zxy∘W, det = (T0 + T2) + T1 = a·(b×c): every monomial through at most 8 rounded operations.
  const __m256d Cyzx = _mm256_permute4x64_pd(C, 0xC9), Byzx = _mm256_permute4x64_pd(B, 0xC9);
  const __m256d Azxy = _mm256_permute4x64_pd(A, 0xD2);
  const __m256d T = _mm256_mul_pd(Azxy, _mm256_sub_pd(_mm256_mul_pd(B, Cyzx), _mm256_mul_pd(Byzx, C)));
  const __m128d Tl = _mm256_castpd256_pd128(T), Th = _mm256_extractf128_pd(T, 1);
  const __m128d s2 = _mm_add_pd(Tl, Th);
  const __m128d det = _mm_add_sd(s2, _mm_unpackhi_pd(s2, s2));
  const __m256d sign_bit = _mm256_set1_pd(-0.0);
  const __m256d M = _mm256_max_pd(_mm256_max_pd(_mm256_andnot_pd(sign_bit, A), _mm256_andnot_pd(sign_bit, B)),
                                  _mm256_andnot_pd(sign_bit, C));  // (m_x, m_y, m_z, m_z)
  const int in_range = _mm256_movemask_pd(_mm256_and_pd(_mm256_cmp_pd(M, _mm256_set1_pd(kSemiStaticMin), _CMP_GE_OQ),
                                                        _mm256_cmp_pd(M, _mm256_set1_pd(kSemiStaticMax), _CMP_LE_OQ)));
  const __m128d Ml = _mm256_castpd256_pd128(M), Mh = _mm256_extractf128_pd(M, 1);
  const __m128d bound = _mm_mul_sd(_mm_mul_sd(_mm_mul_sd(_mm_set_sd(kSemiStatic), Ml), _mm_unpackhi_pd(Ml, Ml)), Mh);
  const __m128d abs_det = _mm_andnot_pd(_mm256_castpd256_pd128(sign_bit), det);
  const bool decided = (in_range == 15) & _mm_comigt_sd(abs_det, bound);
  if (__builtin_expect(decided, 1)) return _mm_comigt_sd(det, _mm_setzero_pd()) ? 1 : -1;
  return orient3d_guarded(a, b, c, d);
}

bool cpu_has_avx2() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2");
}
#else
int orient3d_avx2(const double* a, const double* b, const double* c, const double* d) {
  return orient3d_sse2(a, b, c, d);
}
bool cpu_has_avx2() { return false; }
#endif

}  // namespace detail

namespace {

int orient3d_first_call(const double* a, const double* b, const double* c, const double* d);

}  // namespace

// Constant-initialised, so a call from any static initialiser sees a usable pointer; the first call
// stores the build this CPU supports (every thread stores the same value).
std::atomic<detail::Orient3dImpl> detail::orient3d_impl{orient3d_first_call};

namespace {

int orient3d_first_call(const double* a, const double* b, const double* c, const double* d) {
  const detail::Orient3dImpl impl = detail::cpu_has_avx2() ? detail::orient3d_avx2 : detail::orient3d_sse2;
  detail::orient3d_impl.store(impl, std::memory_order_relaxed);
  return impl(a, b, c, d);
}

}  // namespace

}  // namespace volmap
