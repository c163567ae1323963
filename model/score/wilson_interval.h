// Wilson score interval: a confidence interval for a binomial proportion k/n
// that stays inside [0, 1] and gives zero counts a non-zero upper bound
// (k = 0: upper = z^2 / (n + z^2)), unlike the normal approximation.
#pragma once
#include <cstdint>

namespace vbsim {

/// z for a two-sided 95% interval (the 97.5% quantile of the standard normal).
constexpr double kZ95 = 1.959963984540054;

struct Proportion {
  double estimate = 0.0;  ///< k / n (0 when n = 0)
  double lower = 0.0;
  double upper = 0.0;     ///< 1 when n = 0: nothing is known
};

/// The Wilson score interval of k successes in n trials at quantile z:
/// centre (k + z^2/2) / (n + z^2), half-width z sqrt(k (n - k) / n + z^2 / 4) / (n + z^2).
/// Precondition: k <= n.
Proportion wilson_interval(uint64_t k, uint64_t n, double z = kZ95);

}  // namespace vbsim
