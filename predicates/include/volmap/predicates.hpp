// volmap/predicates.hpp — exact geometric predicates (orient2d, orient3d, incircle, insphere).
//
// Sign conventions (Shewchuk's):
//   orient2d(a,b,c)     > 0  iff a,b,c are counter-clockwise.
//   orient3d(a,b,c,d)   = sign det[a-d; b-d; c-d] > 0 iff d lies below the plane of a,b,c seen
//                         counter-clockwise from above. VOLMAP tets (v0,v1,v2,v3) have orient3d > 0.
//   incircle(a,b,c,d)   > 0  iff d is inside the circle through a,b,c (a,b,c counter-clockwise).
//   insphere(a,b,c,d,e) > 0  iff e is inside the sphere through a,b,c,d (orient3d(a,b,c,d) > 0).
// Results are exact for every finite double input (no perturbation, degenerate = 0): subnormals,
// 2^±1000, mixed magnitudes and ±0 included. Evaluation is layered (see predicates/README.md and
// docs/predicates.md): floating-point filter, Shewchuk's adaptive expansion stages inside
// his safe exponent range [2^-142, 2^201], exact integer arithmetic (Boost cpp_int) outside it.
// Preconditions of the unchecked scalar functions: all coordinates finite. The *_checked variants
// and the batch entry point report non-finite input as an error instead of returning a sign.
// This header has the double-precision API only (no Boost or GMP include); exact rational points
// and their predicates are in <volmap/predicates_rational.hpp>.
// Floating-point environment: the filters' error bounds assume IEEE binary64 with round-to-nearest
// and gradual underflow (no FTZ/DAZ, which linking with -ffast-math sets). On x86 every public
// function below checks MXCSR per call (per batch for orient3d_tets) and, when FTZ/DAZ or another
// rounding mode is on, evaluates under the default environment and restores the caller's, so the
// results are exact in any environment. Loops that make many scalar calls can pay that check once
// instead: see FpEnvironmentScope at the end of this header.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace volmap {

enum class Sign : int { Negative = -1, Zero = 0, Positive = 1 };

// Thrown by the checked variants when an input coordinate is NaN or infinite.
class NonFiniteInput : public std::domain_error {
 public:
  using std::domain_error::domain_error;
};

// Scalar predicates on doubles. Points are arrays of 2 (2D) or 3 (3D) doubles. Return -1, 0, +1.
int orient2d(const double* a, const double* b, const double* c);
inline int orient3d(const double* a, const double* b, const double* c, const double* d);
int incircle(const double* a, const double* b, const double* c, const double* d);
int insphere(const double* a, const double* b, const double* c, const double* d, const double* e);

// Same, but throw NonFiniteInput when any coordinate is not finite.
int orient2d_checked(const double* a, const double* b, const double* c);
int orient3d_checked(const double* a, const double* b, const double* c, const double* d);
int incircle_checked(const double* a, const double* b, const double* c, const double* d);
int insphere_checked(const double* a, const double* b, const double* c, const double* d, const double* e);

// Exact tests built on the predicates (3D points, finite coordinates; exact in any FP environment).
// points_equal: value equality of every coordinate (+0 == -0), also under DAZ, where the hardware
// compares subnormals as zero.
bool points_equal(const double* p, const double* q);
// collinear: a, b, c on one line (also when two or three of them coincide), i.e. (b−a)×(c−a) = 0,
// decided as orient2d = 0 in the three coordinate planes.
bool collinear(const double* a, const double* b, const double* c);
// same_half_plane: p and q lie in one open half-plane bounded by the line ab (a != b), i.e. the four
// points are coplanar (orient3d = 0) and p, q, both off the line, are on the same side of it; decided
// as orient2d in a coordinate plane where (a, b, p) does not degenerate (the projection is then
// injective on their common plane). False when p is on the line ab.
bool same_half_plane(const double* a, const double* b, const double* p, const double* q);

// Exact sign of the volume enclosed by a closed triangle surface: sign of Σ det[a; b; c] over the
// triangles (a, b, c) (6 × the signed volume, divergence theorem with the origin as apex). Positive
// when the triangles are oriented outward in the VOLMAP convention (orient3d(a, b, c, inside) > 0).
// xyz: 3*num_vertices doubles; triangles: 3*num_triangles vertex ids. A double sum with a forward
// error bound decides unless the sum is near zero; then an exact expansion (or rational) sum.
// Throws NonFiniteInput when a referenced coordinate is not finite, std::out_of_range for an id >=
// num_vertices. The surface is not checked for closedness (the sum then depends on the origin).
int enclosed_volume_sign(const double* xyz, std::size_t num_vertices, const std::uint32_t* triangles,
                         std::size_t num_triangles);

// Result of a batch orientation pass over a tet mesh.
struct TetSignCounts {
  std::size_t positive = 0;
  std::size_t zero = 0;
  std::size_t negative = 0;
  bool ok = true;            // false when the input had non-finite coordinates or out-of-range ids
  const char* error = "";    // static reason when !ok (no sign is reported then)
};

// The hot path of every map check. xyz: 3*num_vertices doubles (x,y,z per vertex);
// tets: 4*num_tets vertex ids (0-based). Writes orient3d(tet) in {-1,0,+1} into signs[t]
// (signs may be nullptr when only the counts are wanted) and returns the counts.
// Ids >= num_vertices or a non-finite coordinate anywhere in xyz[0 .. 3*num_vertices) make the
// result !ok (counts are then zero and the content of signs is unspecified).
// Single-threaded, no allocation; ~5 ns/tet on a 1M-tet indexed mesh (bench/bench_predicates.cpp).
TetSignCounts orient3d_tets(const double* xyz, std::size_t num_vertices, const std::uint32_t* tets,
                            std::size_t num_tets, std::int8_t* signs);

// L0 of the batch path (finiteness, per-axis extents, exponent census) for one coordinate array,
// computed once in O(num_vertices) and reused by any number of batch calls over that array (e.g.
// parallel blocks of one mesh), which then do no per-vertex work.
struct Orient3dBatchFilter {
  bool finite = true;              // every coordinate finite (batch calls report !ok otherwise)
  bool safe = true;                // every nonzero |coordinate| in [2^-142, 2^201] (L1–L3 unguarded)
  double static_bound = 0.0;       // L1 threshold 5.11e-15·Δx·Δy·Δz; 0 when L1 does not apply
  bool static_filter = false;      // whether static_bound is valid
};
Orient3dBatchFilter orient3d_batch_filter(const double* xyz, std::size_t num_vertices);

// orient3d_tets with a precomputed filter of the same xyz (no O(num_vertices) census per call).
TetSignCounts orient3d_tets(const Orient3dBatchFilter& filter, const double* xyz, std::size_t num_vertices,
                            const std::uint32_t* tets, std::size_t num_tets, std::int8_t* signs);

// Number of tets with orient3d <= 0 (the certification count: a map is valid iff it is 0), by
// orient3d_tets. Input orient3d_tets refuses (non-finite coordinate, id out of range) counts every tet
// as non-positive: the result is then num_tets and signs (when given) are all 0.
std::size_t count_nonpositive(const double* xyz, std::size_t num_vertices, const std::uint32_t* tets,
                              std::size_t num_tets, std::int8_t* signs = nullptr);
// Ids of the tets with orient3d <= 0 (every id when the input is refused), increasing.
std::vector<std::uint32_t> nonpositive_tets(const double* xyz, std::size_t num_vertices, const std::uint32_t* tets,
                                            std::size_t num_tets);
// The same on flat arrays (xyz.size()/3 vertices, tets.size()/4 tets).
inline std::size_t count_nonpositive(const std::vector<double>& xyz, const std::vector<std::uint32_t>& tets) {
  return count_nonpositive(xyz.data(), xyz.size() / 3, tets.data(), tets.size() / 4);
}
inline std::vector<std::uint32_t> nonpositive_tets(const std::vector<double>& xyz,
                                                   const std::vector<std::uint32_t>& tets) {
  return nonpositive_tets(xyz.data(), xyz.size() / 3, tets.data(), tets.size() / 4);
}

// One floating-point environment check for a whole loop of scalar predicate calls.
// Construction reads MXCSR once and, when FTZ/DAZ or a non-nearest rounding mode is set, switches the
// calling thread to the default environment; destruction (also during stack unwinding) restores the
// caller's control bits. The member predicates are the free functions without their per-call check
// (same results, ~4 ns less per call on x86): they are only valid while the scope is alive, on the
// thread that created it, with nothing inside the scope changing MXCSR. MXCSR is per thread, so a
// parallel loop creates one scope per task body, never one captured from the launching thread.
// Everything else run inside the scope also sees the default environment. Non-x86: no-op.
//   volmap::FpEnvironmentScope fp;
//   for (...) if (fp.orient3d(a, b, c, d) <= 0) ...;
class FpEnvironmentScope {
 public:
  FpEnvironmentScope() noexcept;
  ~FpEnvironmentScope();
  FpEnvironmentScope(const FpEnvironmentScope&) = delete;
  FpEnvironmentScope& operator=(const FpEnvironmentScope&) = delete;

  // Whether the caller's environment was not the default one (and is restored at destruction).
  bool switched() const noexcept { return switched_; }

  // Unchecked scalar predicates (preconditions as the free functions: finite coordinates).
  int orient2d(const double* a, const double* b, const double* c) const;
  int orient3d(const double* a, const double* b, const double* c, const double* d) const;
  int incircle(const double* a, const double* b, const double* c, const double* d) const;
  int insphere(const double* a, const double* b, const double* c, const double* d, const double* e) const;

 private:
  unsigned saved_ = 0;     // the caller's MXCSR
  bool switched_ = false;  // saved_ had non-default control bits
};

// orient3d's fast path is chosen per CPU at the first call (orient3d.cpp: AVX2 or SSE2 build of the
// semi-static filter); the call goes straight to it, one indirect call and no wrapper.
namespace detail {
using Orient3dImpl = int (*)(const double*, const double*, const double*, const double*);
extern std::atomic<Orient3dImpl> orient3d_impl;
}  // namespace detail

inline int orient3d(const double* a, const double* b, const double* c, const double* d) {
  return detail::orient3d_impl.load(std::memory_order_relaxed)(a, b, c, d);
}

}  // namespace volmap
