#include "hw/sampling/sample_estimator.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vbsim::hw {

double RatioEstimate::relative() const {
  return ratio != 0 ? half_width / std::fabs(ratio) : std::numeric_limits<double>::infinity();
}

double normal_quantile(double p) {
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                             1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                             6.680131188771972e+01,  -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                             -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                             3.754408661907416e+00};
  const double lo = 0.02425, hi = 1 - lo;
  if (p < lo) {
    const double q = std::sqrt(-2 * std::log(p));
    return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  }
  if (p > hi) return -normal_quantile(1 - p);
  const double q = p - 0.5, r = q * q;
  return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
         (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
}

double student_t_quantile(double p, double dof) {
  const double pi = 3.14159265358979323846;
  if (dof <= 1) return std::tan(pi * (p - 0.5));
  if (dof <= 2) return (2 * p - 1) / std::sqrt(2 * p * (1 - p));
  // Cornish-Fisher expansion of t in the normal quantile z (Abramowitz and Stegun 26.7.5).
  const double z = normal_quantile(p), z2 = z * z, v = dof;
  const double g1 = (z2 + 1) * z / 4;
  const double g2 = ((5 * z2 + 16) * z2 + 3) * z / 96;
  const double g3 = (((3 * z2 + 19) * z2 + 17) * z2 - 15) * z / 384;
  const double g4 = ((((79 * z2 + 776) * z2 + 1482) * z2 - 1920) * z2 - 945) * z / 92160;
  return z + g1 / v + g2 / (v * v) + g3 / (v * v * v) + g4 / (v * v * v * v);
}

RatioEstimate ratio_estimate(const std::vector<UnitMeasure>& units, double confidence, double population) {
  RatioEstimate e;
  e.units = units.size();
  double sy = 0, sx = 0;
  for (const UnitMeasure& u : units) sy += u.y, sx += u.x;
  if (units.empty() || sx <= 0) {
    e.half_width = std::numeric_limits<double>::infinity();
    return e;
  }
  e.ratio = sy / sx;
  const double n = static_cast<double>(units.size());
  const double fpc = population > 0 ? std::max(0.0, 1 - sx / population) : 1.0;
  if (fpc == 0) return e;  // every unit of the population measured: no sampling error
  if (units.size() < 2) {
    e.half_width = std::numeric_limits<double>::infinity();
    return e;
  }
  double ss = 0;
  for (const UnitMeasure& u : units) {
    const double r = u.y - e.ratio * u.x;
    ss += r * r;
  }
  const double mean_x = sx / n;
  const double se = std::sqrt(ss / (n - 1) / n * fpc) / mean_x;
  e.half_width = student_t_quantile(0.5 + confidence / 2, n - 1) * se;
  return e;
}

}  // namespace vbsim::hw
