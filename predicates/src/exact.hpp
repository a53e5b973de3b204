// exact.hpp — the always-correct layer L4 (internal): integer evaluation of the four predicates.
// Doubles are turned into integers with a common power-of-two exponent (exact), translated and
// evaluated in Boost cpp_int (fixed width when the bit length allows, arbitrary otherwise).
// Rational points use homogeneous integer determinants (GMP mpz), see predicates.md §2 L4.
// Sign conventions as in <volmap/predicates.hpp>. Inputs must be finite.
#pragma once

#include <volmap/predicates_rational.hpp>

namespace volmap::detail {

int orient2d_integer(const double* a, const double* b, const double* c);
int orient3d_integer(const double* a, const double* b, const double* c, const double* d);
int incircle_integer(const double* a, const double* b, const double* c, const double* d);
int insphere_integer(const double* a, const double* b, const double* c, const double* d, const double* e);

}  // namespace volmap::detail
