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

// --- exact null vectors -----------------------------------------------------------------------------
// The null vector x (M x = 0) of the matrix with these rows (all of one length), when the null space
// has dimension one: the reduced row echelon form's free column set to 1. Empty otherwise (also for
// no rows). Multiplier searches (Farkas, Gordan) take it as their candidate multipliers.
std::vector<Rational> one_dimensional_null_vector(std::vector<std::vector<Rational>> rows);

// --- lines in Plücker coordinates and Gordan certificates that no line meets them all ---------------
// The line through p then q: direction d = q − p and moment m = p × q (exact rationals). Their
// permuted inner product side(L, L') = d·m' + d'·m decides tets: orient3d(u, v, x, y) =
// −side(line(u, v), line(x, y)), so the tet (u, v, x, y) is positive iff side(uv, xy) < 0, a strict
// inequality that is linear in the six coordinates of uv.
struct PluckerLine {
  std::array<Rational, 3> d, m;
};
PluckerLine plucker_line(const double* p, const double* q);
Rational side(const PluckerLine& a, const PluckerLine& b);

// True iff `multipliers` prove that no line ℓ has side(ℓ, L_j) < 0 for every j: λ_j >= 0, not all
// zero, Σ λ_j L_j = 0 in all six coordinates. Summing λ_j side(ℓ, L_j) gives side(ℓ, Σ λ_j L_j) = 0,
// which a sum of negative terms cannot be; ℓ may be any six-vector, a line or not (Gordan's theorem:
// such λ exist exactly when that linear system has no solution). Decided in exact rationals.
bool gordan_certifies_no_line(const std::vector<PluckerLine>& lines, const std::vector<Rational>& multipliers);

// --- polyhedral cones of six-vectors that hold no line --------------------------------------------
// `rows` r_j define the closed cone C = {L : r_j·L >= 0 for every j} of six-vectors L = (d, m). The
// Klein form K(a, b) = d_a·m_b + d_b·m_a vanishes on a line's Plücker coordinates: K(L, L) = 0, d != 0.
// True iff the rows have rank six (C is pointed) and K(a, b) has one strict sign for every pair
// (a = b included) of C's extreme rays. Those are enumerated exactly: the one-dimensional solutions
// of five independent rows held at zero that satisfy every row. K(L, L) then has that sign on C
// minus 0, since L is a nonnegative combination of the rays, so no line's coordinates lie in C
// (true as well when C = {0}). Cost: one exact elimination per five rows, so keep the rows few.
using SixVector = std::array<Rational, 6>;
bool cone_holds_no_line(const std::vector<SixVector>& rows);

}  // namespace volmap
