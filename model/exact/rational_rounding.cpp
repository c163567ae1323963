#include "exact/rational_rounding.h"

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace vbsim {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool has_even_significand(double x) {
  uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  return (bits & 1u) == 0;
}

}  // namespace

double round_down_double(const mpq_class& q) {
  const double t = q.get_d();  // truncated toward zero
  if (std::isinf(t)) return t > 0 ? DBL_MAX : t;
  if (cmp(q, t) >= 0) return t;
  return std::nextafter(t, -kInf);
}

double round_up_double(const mpq_class& q) {
  const double t = q.get_d();
  if (std::isinf(t)) return t < 0 ? -DBL_MAX : t;
  if (cmp(q, t) <= 0) return t;
  return std::nextafter(t, kInf);
}

double round_to_nearest_double(const mpq_class& q) {
  const int s = sgn(q);
  if (s == 0) return 0.0;
  const mpq_class a = s > 0 ? mpq_class(q) : mpq_class(-q);
  // lo <= a < hi are the two doubles around a (hi = +inf past DBL_MAX).
  const double lo = a.get_d();
  if (std::isinf(lo)) return s > 0 ? lo : -lo;
  if (cmp(a, lo) == 0) return s > 0 ? lo : -lo;
  const double hi = std::nextafter(lo, kInf);
  // Midpoint; past DBL_MAX IEEE rounds to inf from DBL_MAX + half an ulp.
  const mpq_class mid = std::isinf(hi) ? mpq_class(mpq_class(DBL_MAX) + std::ldexp(1.0, 970))
                                       : mpq_class((mpq_class(lo) + hi) / 2);
  const int c = cmp(a, mid);
  double r;
  if (c < 0) r = lo;
  else if (c > 0) r = hi;
  else r = std::isinf(hi) || has_even_significand(hi) ? hi : lo;
  return s > 0 ? r : -r;
}

}  // namespace vbsim
