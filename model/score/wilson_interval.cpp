#include "score/wilson_interval.h"

#include <algorithm>
#include <cmath>

namespace vbsim {

Proportion wilson_interval(uint64_t k, uint64_t n, double z) {
  Proportion p;
  if (n == 0) {
    p.upper = 1.0;
    return p;
  }
  const double kd = static_cast<double>(k), nd = static_cast<double>(n), z2 = z * z;
  p.estimate = kd / nd;
  const double centre = (kd + z2 / 2) / (nd + z2);
  const double half = z * std::sqrt(kd * (nd - kd) / nd + z2 / 4) / (nd + z2);
  // The exact bounds at k = 0 and k = n are 0 and 1; rounding must not cross them.
  p.lower = k == 0 ? 0.0 : std::max(0.0, centre - half);
  p.upper = k == n ? 1.0 : std::min(1.0, centre + half);
  return p;
}

}  // namespace vbsim
