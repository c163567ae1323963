// Correct rounding of exact rationals to double (mpq_get_d truncates toward zero).
#pragma once
#include <gmpxx.h>

namespace vbsim {

/// q rounded to the nearest double, ties to even (IEEE round-to-nearest);
/// magnitudes beyond the double range round to +-inf as IEEE overflow does.
double round_to_nearest_double(const mpq_class& q);

/// Largest double <= q and smallest double >= q (directed roundings of q).
double round_down_double(const mpq_class& q);
double round_up_double(const mpq_class& q);

}  // namespace vbsim
