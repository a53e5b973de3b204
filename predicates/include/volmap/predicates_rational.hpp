// volmap/predicates_rational.hpp — the exact predicates on rational points (Boost.Multiprecision + GMP).
// Same sign conventions and results as the double predicates of <volmap/predicates.hpp> (included),
// for points whose coordinates are exact rationals (e.g. a map file written as num/den tokens).
// Evaluation: homogeneous integer determinants (Bareiss on GMP mpz); orient3d first tries a double
// prefilter whose bound includes the conversion error (see predicates/README.md).
#pragma once

#include <volmap/predicates.hpp>

#include <boost/multiprecision/gmp.hpp>

#include <array>
#include <vector>

namespace volmap {

// Exact rational number (GMP backend, expression templates off: safe to store in auto).
using Rational = boost::multiprecision::number<boost::multiprecision::gmp_rational,
                                               boost::multiprecision::et_off>;

// Exact predicates on rational points (arrays of 2 or 3 Rationals).
int orient2d(const Rational* a, const Rational* b, const Rational* c);
int orient3d(const Rational* a, const Rational* b, const Rational* c, const Rational* d);
int incircle(const Rational* a, const Rational* b, const Rational* c, const Rational* d);
int insphere(const Rational* a, const Rational* b, const Rational* c, const Rational* d, const Rational* e);

// orient3d_tets on exact rational coordinates (3*num_vertices Rationals): a double prefilter with
// the conversion error in its bound decides most tets, the rest use homogeneous integer determinants.
TetSignCounts orient3d_tets(const Rational* xyz, std::size_t num_vertices, const std::uint32_t* tets,
                            std::size_t num_tets, std::int8_t* signs);

// --- strict half-spaces of oriented faces and their Farkas certificates ---------------------------
// A point x is on the positive side of the outward face (a,b,c) iff orient3d(a,b,c,x) > 0, i.e.
// n·x > d with n = (c − a) × (b − a) and d = n·a (exactly, in rationals).
struct StrictHalfspace {
  std::array<Rational, 3> n;
  Rational d;
};
StrictHalfspace strict_halfspace(const double* a, const double* b, const double* c);

// True iff `multipliers` prove that no point is strictly inside every half-space: λ_j >= 0, not all
// zero, Σ λ_j n_j = 0 and Σ λ_j d_j >= 0 (Farkas: such λ exist exactly when the strict system has
// no solution). False for mismatched sizes or an empty system. Decided in exact rationals.
bool farkas_certifies_empty(const std::vector<StrictHalfspace>& halfspaces, const std::vector<Rational>& multipliers);

}  // namespace volmap
