// Library loops that check the floating-point environment once (volmap::FpEnvironmentScope) instead
// of per predicate call: TetMesh::check_invariants(true) and strict_kernel_point must stay exact when
// the caller runs with MXCSR flush-to-zero | denormals-are-zero, and leave the caller's MXCSR as it
// was. Oracle: a tet with subnormal coordinates (orient3d = 2^-3180 > 0 exactly; under DAZ every
// double evaluation sees 0) and the exact predicates in the default environment. x86-64 only.
#include <doctest/doctest.h>
#include <volmap/volume/kernel_lp.hpp>
#include <volmap/core/mesh_data.hpp>
#include <volmap/predicates.hpp>
#include <volmap/core/tet_mesh.hpp>

#include <cmath>
#include <vector>

#if defined(__SSE2__)
#include <xmmintrin.h>
#define VOLMAP_TEST_HAVE_MXCSR 1
#endif

#ifdef VOLMAP_TEST_HAVE_MXCSR
namespace {
constexpr unsigned kFtzDaz = 0x8040u;
struct FlushToZero {
  unsigned saved = _mm_getcsr();
  FlushToZero() { _mm_setcsr(saved | kFtzDaz); }
  ~FlushToZero() { _mm_setcsr(saved); }
};
bool flushes() {
  volatile double tiny = 0x1p-1070, one = 1.0;
  return tiny * one == 0.0;
}
// One tet (v0..v3) = (t,0,0), (0,t,0), (0,0,t), (0,0,0): orient3d = t^3 > 0 (VOLMAP-positive).
volmap::TetMeshData one_tet(double t, bool flipped) {
  volmap::TetMeshData m;
  m.xyz = {t, 0, 0, 0, t, 0, 0, 0, t, 0, 0, 0};
  m.tets = flipped ? std::vector<std::uint32_t>{1, 0, 2, 3} : std::vector<std::uint32_t>{0, 1, 2, 3};
  return m;
}
}  // namespace
#endif

TEST_CASE("TetMesh check_invariants positivity is exact under FTZ|DAZ and restores MXCSR") {
#ifndef VOLMAP_TEST_HAVE_MXCSR
  MESSAGE("skipped: no MXCSR on this architecture");
#else
  const double t = 0x1p-1060;  // subnormal
  const volmap::TetMesh pos(one_tet(t, false)), neg(one_tet(t, true));
  REQUIRE(pos.check_invariants(true).ok);  // default environment
  REQUIRE_FALSE(neg.check_invariants(true).ok);
  bool pos_ok = false, neg_ok = true, did_flush = false;
  unsigned before = 0, after = 0;
  {
    FlushToZero ftz;
    did_flush = flushes();
    before = _mm_getcsr();
    pos_ok = pos.check_invariants(true).ok;
    neg_ok = neg.check_invariants(true).ok;
    after = _mm_getcsr();
  }
  REQUIRE(did_flush);
  CHECK(pos_ok);
  CHECK_FALSE(neg_ok);
  CHECK((after & ~0x3Fu) == (before & ~0x3Fu));
#endif
}

TEST_CASE("strict_kernel_point under FTZ|DAZ returns an exactly verified point and restores MXCSR") {
#ifdef VOLMAP_TEST_HAVE_MXCSR
  // Faces of a positive tet oriented so that its interior is on their positive side (F0..F3 of the
  // developer guide's outward faces, each with orient3d(face, opposite vertex) > 0).
  const double v[4][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}};
  REQUIRE(volmap::orient3d(v[0], v[1], v[2], v[3]) > 0);
  std::vector<double> tri;
  for (const auto& f : volmap::kTetFace)
    for (int k : f) tri.insert(tri.end(), v[k], v[k] + 3);
  double q[3] = {0, 0, 0};
  bool found = false;
  unsigned before = 0, after = 0;
  {
    FlushToZero ftz;
    before = _mm_getcsr();
    found = volmap::strict_kernel_point(tri, q);
    after = _mm_getcsr();
  }
  REQUIRE(found);
  for (int f = 0; f < 4; ++f) CHECK(volmap::orient3d(&tri[9 * f], &tri[9 * f + 3], &tri[9 * f + 6], q) > 0);
  CHECK((after & ~0x3Fu) == (before & ~0x3Fu));
#endif
}
