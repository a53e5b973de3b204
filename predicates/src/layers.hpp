// layers.hpp — internal entry points between the predicates' source files (not installed).
// predicates.cpp owns the layered orient3d (stage A, L3, L4); orient3d.cpp puts the scalar fast path
// in front of it, orient3d_tets.cpp the batch filters. Conventions as in <volmap/predicates.hpp>.
#pragma once

#include <volmap/predicates.hpp>

namespace volmap::detail {

// orient3d after a filter that did not decide: MXCSR check (default environment restored if needed),
// then stage A, zero-column shortcut, L3 / L4. Exact for any finite input in any environment.
int orient3d_guarded(const double* a, const double* b, const double* c, const double* d);

// orient3d in the default environment for a point set known to be in Shewchuk's safe range (every
// nonzero |coordinate| in [2^-142, 2^201]): stage A, zero-column shortcut, L3. No environment check.
int orient3d_safe_after_static(const double* a, const double* b, const double* c, const double* d);

// The two builds of the scalar orient3d (the public one dispatches once, at load time, to the widest
// the CPU supports); exposed so that tests can run both on any machine that has AVX2.
int orient3d_sse2(const double* a, const double* b, const double* c, const double* d);
int orient3d_avx2(const double* a, const double* b, const double* c, const double* d);
bool cpu_has_avx2();

// orient3d_tets with the one-tet-per-step pass 1 whatever the CPU (the public one uses AVX2 when it
// can); for tests.
TetSignCounts orient3d_tets_portable(const Orient3dBatchFilter& filter, const double* xyz, std::size_t num_vertices,
                                     const std::uint32_t* tets, std::size_t num_tets, std::int8_t* signs);

}  // namespace volmap::detail
