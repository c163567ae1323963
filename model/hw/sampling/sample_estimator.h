// Estimates with confidence intervals from measured units (SMARTS; the
// statistics are written out in docs/sampling.md). Each unit i gives a
// measure y_i (e.g. cycles) over x_i rays; the ratio estimator R = sum y /
// sum x, its standard error from the residuals y_i - R x_i, the finite
// population correction (1 - sum x / population) and Student's t with n - 1
// degrees of freedom.
#pragma once
#include <cstdint>
#include <vector>

namespace vbsim::hw {

struct UnitMeasure {
  double y = 0;  ///< the measure over the unit (cycles, hits)
  double x = 0;  ///< what it is per (rays, accesses)
};

struct RatioEstimate {
  double ratio = 0;       ///< sum y / sum x
  double half_width = 0;  ///< of the interval around `ratio` (infinite with fewer than 2 units)
  uint64_t units = 0;
  double low() const { return ratio - half_width; }
  double high() const { return ratio + half_width; }
  /// half_width / ratio (infinite when the ratio is 0)
  double relative() const;
};

/// The estimate of sum y / sum x over a population of `population` x (0: no
/// finite population correction) at `confidence` (in (0, 1)).
RatioEstimate ratio_estimate(const std::vector<UnitMeasure>& units, double confidence, double population);

/// The standard normal quantile (Acklam's rational approximation, relative error < 1.2e-9).
double normal_quantile(double p);
/// Student's t quantile with `dof` >= 1 degrees of freedom (exact for 1 and 2,
/// a Cornish-Fisher expansion beyond: 0.12% low at p = 0.975 with 3, within
/// 0.03% from 4 on; testbench/module/sampling_test.cpp checks tabulated values).
double student_t_quantile(double p, double dof);

}  // namespace vbsim::hw
