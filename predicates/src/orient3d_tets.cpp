// orient3d_tets.cpp — the batch orient3d over an indexed tet mesh (map checks, certification counts).
// Conventions: <volmap/predicates.hpp>. Layers as in predicates.cpp, plus the batch-only L0/L1:
//   L0 once: finiteness, per-axis extents Δ_k = fl(max_k − min_k) (rounding is monotone, so every
//      rounded coordinate difference satisfies |fl(p−q)| ≤ Δ_k), and the exponent census (all nonzero
//      |coordinates| in [2^-142, 2^201] ⇒ "safe": L1–L3 are valid for every tet without guards).
//   Per tet: L1 static filter (one compare), then stage A, zero-column shortcut, L3. No allocation.
// Pass 1 (bare determinant + L1) runs four tets per step with AVX2 when the CPU has it (decided once
// per process), else one tet per step; both evaluate the same expression in the same order.
#include <volmap/predicates.hpp>

#include "fp_env.hpp"
#include "layers.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#if defined(__x86_64__)
#include <immintrin.h>
#elif defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace volmap {

namespace {

// L1 static filter constant (CGAL Static_filters/Orientation_3, geogram PCK, TetGen/HXT).
constexpr double kO3Static = 5.1107127829973299e-15;

struct MeshCensus {
  bool finite = true;
  bool safe = true;
  double extent[3] = {0, 0, 0};
};

MeshCensus census_portable(const double* xyz, std::size_t num_vertices) {
  MeshCensus c;
  if (num_vertices == 0) return c;
  // Branch-free reductions over kLanes independent accumulator sets (vertex v goes to lane v mod
  // kLanes), so the min/max dependency chains overlap instead of serialising the loop on their
  // latency (without -ffast-math the compiler may not reassociate them itself). Magnitudes are compared
  // as integers: with the sign bit cleared, the bit pattern of a double orders like its value, and the
  // inf/NaN patterns lie above every finite one, so one integer maximum yields both finiteness and
  // max |x|; zeros map to ~0 for the smallest nonzero magnitude. min/max are exact in any order.
  constexpr int kLanes = 4;
  constexpr std::uint64_t kAbsMask = 0x7fffffffffffffffull, kInfBits = 0x7ff0000000000000ull;
  double lo[kLanes][3], hi[kLanes][3];
  std::uint64_t max_bits[kLanes], min_nz_bits[kLanes];
  for (int j = 0; j < kLanes; ++j) {
    for (int k = 0; k < 3; ++k) {
      lo[j][k] = HUGE_VAL;
      hi[j][k] = -HUGE_VAL;
    }
    max_bits[j] = 0;
    min_nz_bits[j] = ~std::uint64_t(0);
  }
  auto update = [&](int j, const double* p) {
    for (int k = 0; k < 3; ++k) {
      const double x = p[k];
      std::uint64_t bits;
      std::memcpy(&bits, &x, sizeof bits);
      bits &= kAbsMask;
      lo[j][k] = x < lo[j][k] ? x : lo[j][k];
      hi[j][k] = x > hi[j][k] ? x : hi[j][k];
      max_bits[j] = bits > max_bits[j] ? bits : max_bits[j];
      const std::uint64_t nz = bits == 0 ? ~std::uint64_t(0) : bits;
      min_nz_bits[j] = nz < min_nz_bits[j] ? nz : min_nz_bits[j];
    }
  };
  const std::size_t whole = num_vertices / kLanes * kLanes;
  for (std::size_t v = 0; v < whole; v += kLanes)
    for (int j = 0; j < kLanes; ++j) update(j, xyz + 3 * (v + j));
  for (std::size_t v = whole; v < num_vertices; ++v) update(0, xyz + 3 * v);
  for (int j = 1; j < kLanes; ++j) {
    for (int k = 0; k < 3; ++k) {
      lo[0][k] = lo[j][k] < lo[0][k] ? lo[j][k] : lo[0][k];
      hi[0][k] = hi[j][k] > hi[0][k] ? hi[j][k] : hi[0][k];
    }
    max_bits[0] = max_bits[j] > max_bits[0] ? max_bits[j] : max_bits[0];
    min_nz_bits[0] = min_nz_bits[j] < min_nz_bits[0] ? min_nz_bits[j] : min_nz_bits[0];
  }
  auto bits_of = [](double x) {
    std::uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
  };
  c.finite = max_bits[0] < kInfBits;
  c.safe = c.finite && max_bits[0] <= bits_of(0x1p201) && min_nz_bits[0] >= bits_of(0x1p-142);
  for (int k = 0; k < 3; ++k) c.extent[k] = hi[0][k] - lo[0][k];
  return c;
}

#if defined(__SSE2__)
// SSE2 census: the coordinates are read as consecutive pairs, so with a stride of 6 doubles (two
// vertices) the pairs are (x,y), (z,x), (y,z) and three lo/hi accumulator pairs track fixed axes.
// Finiteness: x − x is NaN exactly for ±inf/NaN (cmpunord mask OR-ed up). With finite input, FP max of
// |x| and min of the nonzero |x| (zeros replaced by +inf) are exact.
MeshCensus census(const double* xyz, std::size_t num_vertices) {
  if (num_vertices < 8) return census_portable(xyz, num_vertices);
  const std::size_t pairs6 = num_vertices / 2;  // groups of 2 vertices = 6 doubles = 3 pairs
  const __m128d inf = _mm_set1_pd(HUGE_VAL), abs_mask = _mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffffLL));
  const __m128d zero = _mm_setzero_pd();
  const __m128d minus_inf = _mm_set1_pd(-HUGE_VAL);
  __m128d lo[3] = {inf, inf, inf}, hi[3] = {minus_inf, minus_inf, minus_inf};
  __m128d max_abs[3] = {zero, zero, zero}, min_nz[3] = {inf, inf, inf}, bad[3] = {zero, zero, zero};
  for (std::size_t g = 0; g < pairs6; ++g) {
    const double* p = xyz + 6 * g;
    for (int j = 0; j < 3; ++j) {
      const __m128d x = _mm_loadu_pd(p + 2 * j);
      lo[j] = _mm_min_pd(x, lo[j]);
      hi[j] = _mm_max_pd(x, hi[j]);
      const __m128d ax = _mm_and_pd(x, abs_mask);
      max_abs[j] = _mm_max_pd(ax, max_abs[j]);
      const __m128d is_zero = _mm_cmpeq_pd(ax, zero);
      min_nz[j] = _mm_min_pd(_mm_or_pd(_mm_and_pd(is_zero, inf), _mm_andnot_pd(is_zero, ax)), min_nz[j]);
      bad[j] = _mm_or_pd(bad[j], _mm_cmpunord_pd(_mm_sub_pd(x, x), zero));
    }
  }
  double l[3][2], h[3][2], ma[3][2], mn[3][2], b[3][2];
  for (int j = 0; j < 3; ++j) {
    _mm_storeu_pd(l[j], lo[j]);
    _mm_storeu_pd(h[j], hi[j]);
    _mm_storeu_pd(ma[j], max_abs[j]);
    _mm_storeu_pd(mn[j], min_nz[j]);
    _mm_storeu_pd(b[j], bad[j]);
  }
  // Lanes by axis: pair 0 = (x, y), pair 1 = (z, x), pair 2 = (y, z).
  static constexpr int kAxis[3][2] = {{0, 1}, {2, 0}, {1, 2}};
  MeshCensus tail = census_portable(xyz + 6 * pairs6, num_vertices - 2 * pairs6);  // 0 or 1 vertex
  double lo_axis[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi_axis[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  double max_all = 0.0, min_all = HUGE_VAL;
  bool any_bad = false;
  for (int j = 0; j < 3; ++j)
    for (int lane = 0; lane < 2; ++lane) {
      const int k = kAxis[j][lane];
      lo_axis[k] = l[j][lane] < lo_axis[k] ? l[j][lane] : lo_axis[k];
      hi_axis[k] = h[j][lane] > hi_axis[k] ? h[j][lane] : hi_axis[k];
      max_all = ma[j][lane] > max_all ? ma[j][lane] : max_all;
      min_all = mn[j][lane] < min_all ? mn[j][lane] : min_all;
      std::uint64_t bits;
      std::memcpy(&bits, &b[j][lane], sizeof bits);
      any_bad |= bits != 0;
    }
  MeshCensus c;
  c.finite = !any_bad && tail.finite;
  if (num_vertices - 2 * pairs6 == 1) {
    const double* p = xyz + 6 * pairs6;
    for (int k = 0; k < 3; ++k) {
      const double ax = std::fabs(p[k]);
      lo_axis[k] = p[k] < lo_axis[k] ? p[k] : lo_axis[k];
      hi_axis[k] = p[k] > hi_axis[k] ? p[k] : hi_axis[k];
      max_all = ax > max_all ? ax : max_all;
      if (ax != 0.0) min_all = ax < min_all ? ax : min_all;
    }
  }
  c.safe = c.finite && max_all <= 0x1p201 && min_all >= 0x1p-142;
  for (int k = 0; k < 3; ++k) c.extent[k] = hi_axis[k] - lo_axis[k];
  return c;
}
#else
MeshCensus census(const double* xyz, std::size_t num_vertices) { return census_portable(xyz, num_vertices); }
#endif

TetSignCounts fail(const char* reason) {
  TetSignCounts r;
  r.ok = false;
  r.error = reason;
  return r;
}

// Pass 1 of a chunk, portable: ids validated on the fly (running max; no pointer is formed from a bad
// id), bare determinant + L1 compare, signs in {-1, 0 (undecided), +1}, no call in the loop.
// Returns false when an id is out of range.
bool pass1_portable(const double* xyz, std::size_t num_vertices, const std::uint32_t* chunk, std::size_t count,
                    double bound, std::int8_t* out, std::size_t& pos, std::size_t& neg) {
  std::uint32_t max_id = 0;
  for (std::size_t t = 0; t < count; ++t) {
    const std::uint32_t* v = chunk + 4 * t;
    const std::uint32_t m01 = v[0] > v[1] ? v[0] : v[1], m23 = v[2] > v[3] ? v[2] : v[3];
    const std::uint32_t m = m01 > m23 ? m01 : m23;
    max_id = m > max_id ? m : max_id;
    if (m >= num_vertices) break;  // reported after the loop, before any pointer is formed
    const double* a = xyz + 3 * std::size_t(v[0]);
    const double* b = xyz + 3 * std::size_t(v[1]);
    const double* c = xyz + 3 * std::size_t(v[2]);
    const double* d = xyz + 3 * std::size_t(v[3]);
    const double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
    const double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
    const double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
    const double det = adz * (bdx * cdy - cdx * bdy) + bdz * (cdx * ady - adx * cdy) + cdz * (adx * bdy - bdx * ady);
    const int above = det > bound, below = det < -bound;
    pos += above;
    neg += below;
    out[t] = static_cast<std::int8_t>(above - below);
  }
  return max_id < num_vertices;
}

#if defined(__x86_64__)
// Pass 1 of a chunk with AVX2, four tets per step in SoA lanes: the same expression and evaluation
// order as pass1_portable (so the same L1 decisions), vertices loaded as (x,y) pairs + z and
// transposed (gathers measured slower). Ids are validated for the whole chunk first (vpmaxud), which
// also yields the chunk's id span: when it exceeds kLocalIds vertices the coordinates are unlikely to
// be cached and the loop prefetches the vertices of the tets kAhead steps ahead (on a vertex-shuffled
// 1M-tet grid 9.5 -> 5.1 ns/tet; on a cache-friendly order the prefetches only cost, so they are off).
constexpr std::uint32_t kLocalIds = 1u << 15;
constexpr std::size_t kAhead = 32;

// Byte i of kSpread[m] is 1 (kSpreadNeg: 0xFF) when bit i of the 4-bit mask m is set.
constexpr std::uint32_t spread(unsigned m, std::uint32_t byte) {
  return ((m & 1u) ? byte : 0u) | ((m & 2u) ? byte << 8 : 0u) | ((m & 4u) ? byte << 16 : 0u) |
         ((m & 8u) ? byte << 24 : 0u);
}
struct SpreadTables {
  std::uint32_t pos[16], neg[16];
  std::uint8_t count[16];
  constexpr SpreadTables() : pos(), neg(), count() {
    for (unsigned m = 0; m < 16; ++m) {
      pos[m] = spread(m, 0x01u);
      neg[m] = spread(m, 0xFFu);
      count[m] = std::uint8_t((m & 1u) + ((m >> 1) & 1u) + ((m >> 2) & 1u) + ((m >> 3) & 1u));
    }
  }
};
constexpr SpreadTables kSpread;

__attribute__((target("avx2"))) bool chunk_ids_valid(const std::uint32_t* ids, std::size_t n, std::size_t num_vertices,
                                                     std::uint32_t* span) {
  __m256i hi = _mm256_setzero_si256(), lo = _mm256_set1_epi32(-1);
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(ids + i));
    hi = _mm256_max_epu32(hi, v);
    lo = _mm256_min_epu32(lo, v);
  }
  alignas(32) std::uint32_t h[8], l[8];
  _mm256_store_si256(reinterpret_cast<__m256i*>(h), hi);
  _mm256_store_si256(reinterpret_cast<__m256i*>(l), lo);
  std::uint32_t max_id = 0, min_id = ~0u;
  for (int k = 0; k < 8; ++k) {
    max_id = h[k] > max_id ? h[k] : max_id;
    min_id = l[k] < min_id ? l[k] : min_id;
  }
  for (; i < n; ++i) {
    max_id = ids[i] > max_id ? ids[i] : max_id;
    min_id = ids[i] < min_id ? ids[i] : min_id;
  }
  *span = max_id - min_id;
  return n == 0 || max_id < num_vertices;
}

__attribute__((target("avx2"))) bool pass1_avx2(const double* xyz, std::size_t num_vertices, const std::uint32_t* chunk,
                                                std::size_t count, double bound, std::int8_t* out, std::size_t& pos,
                                                std::size_t& neg) {
  std::uint32_t span = 0;
  if (!chunk_ids_valid(chunk, 4 * count, num_vertices, &span)) return false;
  const bool prefetch = span > kLocalIds;
  const __m256d above_bound = _mm256_set1_pd(bound), below_bound = _mm256_set1_pd(-bound);
  std::size_t t = 0;
  for (; t + 4 <= count; t += 4) {
    if (prefetch && t + kAhead < count) {
      const std::uint32_t* ahead = chunk + 4 * (t + kAhead);
      for (int q = 0; q < 16; ++q) _mm_prefetch(reinterpret_cast<const char*>(xyz + 3 * std::size_t(ahead[q])), _MM_HINT_T0);
    }
    __m256d X[4], Y[4], Z[4];  // slot k of the four tets, one tet per lane
    for (int k = 0; k < 4; ++k) {
      const double* p0 = xyz + 3 * std::size_t(chunk[4 * t + k]);
      const double* p1 = xyz + 3 * std::size_t(chunk[4 * t + 4 + k]);
      const double* p2 = xyz + 3 * std::size_t(chunk[4 * t + 8 + k]);
      const double* p3 = xyz + 3 * std::size_t(chunk[4 * t + 12 + k]);
      const __m256d q02 = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(p0)), _mm_loadu_pd(p2), 1);
      const __m256d q13 = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(p1)), _mm_loadu_pd(p3), 1);
      X[k] = _mm256_unpacklo_pd(q02, q13);
      Y[k] = _mm256_unpackhi_pd(q02, q13);
      Z[k] = _mm256_setr_pd(p0[2], p1[2], p2[2], p3[2]);
    }
    const __m256d adx = _mm256_sub_pd(X[0], X[3]), ady = _mm256_sub_pd(Y[0], Y[3]), adz = _mm256_sub_pd(Z[0], Z[3]);
    const __m256d bdx = _mm256_sub_pd(X[1], X[3]), bdy = _mm256_sub_pd(Y[1], Y[3]), bdz = _mm256_sub_pd(Z[1], Z[3]);
    const __m256d cdx = _mm256_sub_pd(X[2], X[3]), cdy = _mm256_sub_pd(Y[2], Y[3]), cdz = _mm256_sub_pd(Z[2], Z[3]);
    const __m256d m1 = _mm256_sub_pd(_mm256_mul_pd(bdx, cdy), _mm256_mul_pd(cdx, bdy));
    const __m256d m2 = _mm256_sub_pd(_mm256_mul_pd(cdx, ady), _mm256_mul_pd(adx, cdy));
    const __m256d m3 = _mm256_sub_pd(_mm256_mul_pd(adx, bdy), _mm256_mul_pd(bdx, ady));
    const __m256d det =
        _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(adz, m1), _mm256_mul_pd(bdz, m2)), _mm256_mul_pd(cdz, m3));
    const unsigned above = unsigned(_mm256_movemask_pd(_mm256_cmp_pd(det, above_bound, _CMP_GT_OQ)));
    const unsigned below = unsigned(_mm256_movemask_pd(_mm256_cmp_pd(det, below_bound, _CMP_LT_OQ)));
    const std::uint32_t word = kSpread.pos[above] | kSpread.neg[below];
    std::memcpy(out + t, &word, sizeof word);
    pos += kSpread.count[above];
    neg += kSpread.count[below];
  }
  // The last count % 4 tets (ids already validated).
  return pass1_portable(xyz, num_vertices, chunk + 4 * t, count - t, bound, out + t, pos, neg);
}
#endif

// Batch kernel with the L0 filter already computed. Per chunk of kChunk tets: pass 1 (AVX2 when the
// CPU has it) validates the ids and writes the L1 signs; only a chunk with an undecided entry takes
// pass 2, which resolves those through the guarded layers. (A variant fusing two coordinate arrays
// in one loop, sharing the id loads, measured slower than two passes: 12.8 vs 10.8 ns/tet on the
// bunny pair.)
using Pass1 = bool (*)(const double*, std::size_t, const std::uint32_t*, std::size_t, double, std::int8_t*, std::size_t&,
                      std::size_t&);

Pass1 widest_pass1() {
#if defined(__x86_64__)
  static const Pass1 pass1 = detail::cpu_has_avx2() ? pass1_avx2 : pass1_portable;
  return pass1;
#else
  return pass1_portable;
#endif
}

TetSignCounts batch_kernel(const Orient3dBatchFilter& filter, const double* xyz, std::size_t num_vertices,
                           const std::uint32_t* tets, std::size_t num_tets, std::int8_t* signs,
                           Pass1 pass1 = widest_pass1()) {
  if (!filter.finite) return fail("non-finite vertex coordinate");
  // Without L1 the bound is +inf: every tet goes to the guarded layers (still exact).
  const double bound = filter.static_filter ? filter.static_bound : HUGE_VAL;
  constexpr std::size_t kChunk = 1024;
  std::int8_t chunk_signs[kChunk];
  std::size_t positive = 0, negative = 0;
  for (std::size_t first = 0; first < num_tets; first += kChunk) {
    const std::size_t count = std::min(kChunk, num_tets - first);
    std::int8_t* out = signs ? signs + first : chunk_signs;
    const std::uint32_t* chunk = tets + 4 * first;
    std::size_t pos = 0, neg = 0;
    if (!pass1(xyz, num_vertices, chunk, count, bound, out, pos, neg)) return fail("tet vertex id out of range");
    if (pos + neg != count) {
      for (std::size_t t = 0; t < count; ++t) {
        if (out[t] != 0) continue;
        const std::uint32_t* v = chunk + 4 * t;
        const double* a = xyz + 3 * std::size_t(v[0]);
        const double* b = xyz + 3 * std::size_t(v[1]);
        const double* c = xyz + 3 * std::size_t(v[2]);
        const double* d = xyz + 3 * std::size_t(v[3]);
        const int s = filter.safe ? detail::orient3d_safe_after_static(a, b, c, d) : orient3d(a, b, c, d);
        out[t] = static_cast<std::int8_t>(s);
        pos += s > 0;
        neg += s < 0;
      }
    }
    positive += pos;
    negative += neg;
  }
  TetSignCounts r;
  r.positive = positive;
  r.negative = negative;
  r.zero = num_tets - positive - negative;
  return r;
}

}  // namespace

Orient3dBatchFilter orient3d_batch_filter(const double* xyz, std::size_t num_vertices) {
  VOLMAP_REQUIRE_DEFAULT_FP_ENV(orient3d_batch_filter(xyz, num_vertices));
  const MeshCensus mesh = census(xyz, num_vertices);
  Orient3dBatchFilter f;
  f.finite = mesh.finite;
  f.safe = mesh.safe;
  // L1 is valid when the mesh is safe and every extent is in [1e-97, 1e102) (CGAL's guards).
  bool use_static = mesh.safe;
  for (int k = 0; k < 3; ++k) use_static &= (mesh.extent[k] >= 1e-97 && mesh.extent[k] < 1e102);
  f.static_filter = use_static;
  f.static_bound = use_static ? kO3Static * mesh.extent[0] * mesh.extent[1] * mesh.extent[2] : 0.0;
  return f;
}

TetSignCounts orient3d_tets(const Orient3dBatchFilter& filter, const double* xyz, std::size_t num_vertices,
                            const std::uint32_t* tets, std::size_t num_tets, std::int8_t* signs) {
  VOLMAP_REQUIRE_DEFAULT_FP_ENV(orient3d_tets(filter, xyz, num_vertices, tets, num_tets, signs));
  return batch_kernel(filter, xyz, num_vertices, tets, num_tets, signs);
}

TetSignCounts orient3d_tets(const double* xyz, std::size_t num_vertices, const std::uint32_t* tets,
                            std::size_t num_tets, std::int8_t* signs) {
  VOLMAP_REQUIRE_DEFAULT_FP_ENV(orient3d_tets(xyz, num_vertices, tets, num_tets, signs));
  return batch_kernel(orient3d_batch_filter(xyz, num_vertices), xyz, num_vertices, tets, num_tets, signs);
}

namespace detail {
TetSignCounts orient3d_tets_portable(const Orient3dBatchFilter& filter, const double* xyz, std::size_t num_vertices,
                                     const std::uint32_t* tets, std::size_t num_tets, std::int8_t* signs) {
  VOLMAP_REQUIRE_DEFAULT_FP_ENV(orient3d_tets_portable(filter, xyz, num_vertices, tets, num_tets, signs));
  return batch_kernel(filter, xyz, num_vertices, tets, num_tets, signs, pass1_portable);
}
}  // namespace detail

// The certification count: orient3d <= 0, refused input counting as all tets non-positive.
std::size_t count_nonpositive(const double* xyz, std::size_t num_vertices, const std::uint32_t* tets,
                              std::size_t num_tets, std::int8_t* signs) {
  const TetSignCounts c = orient3d_tets(xyz, num_vertices, tets, num_tets, signs);
  if (c.ok) return c.zero + c.negative;
  if (signs) std::fill(signs, signs + num_tets, std::int8_t(0));
  return num_tets;
}

std::vector<std::uint32_t> nonpositive_tets(const double* xyz, std::size_t num_vertices, const std::uint32_t* tets,
                                            std::size_t num_tets) {
  std::vector<std::int8_t> signs(num_tets);
  const std::size_t bad = count_nonpositive(xyz, num_vertices, tets, num_tets, signs.data());
  std::vector<std::uint32_t> ids;
  ids.reserve(bad);
  for (std::size_t t = 0; t < num_tets; ++t)
    if (signs[t] <= 0) ids.push_back(static_cast<std::uint32_t>(t));
  return ids;
}


}  // namespace volmap
