#include "datapath/narrow_box_tester.h"

#include <limits>

namespace vbsim {

namespace narrow_arithmetic {

namespace {

/// rtcore's check_exponent_and_set_inf: MPFR exponent (x = m 2^e, m in [0.5, 1))
/// below -126 gives a signed zero, above 128 a signed infinity.
double held(double x) {
  if (x == 0.0 || !std::isfinite(x)) return x;
  int e = 0;
  std::frexp(x, &e);
  if (e < -126) return std::copysign(0.0, x);
  if (e > 128) return std::copysign(std::numeric_limits<double>::infinity(), x);
  return x;
}

/// x to p bits toward -inf or +inf, the exponent unbounded.
double round_bits(double x, int p, bool up) {
  if (x == 0.0 || !std::isfinite(x)) return x;
  int e = 0;
  const double m = std::frexp(x, &e);  // x = m 2^e, |m| in [0.5, 1)
  const double scaled = std::ldexp(m, p);
  return std::ldexp(up ? std::ceil(scaled) : std::floor(scaled), e - p);
}

/// The exact value s + err (err: the sign of the exact value's excess over s
/// is what matters) rounded to p bits in the direction given.
double round_exact(double s, int err_sign, int p, bool up) {
  if (!std::isfinite(s)) return s;
  const double r = round_bits(s, p, up);
  if (r != s || err_sign == 0) return r;  // s off the grid: the excess cannot cross a grid point
  if (up && err_sign > 0) return round_bits(std::nextafter(s, INFINITY), p, true);
  if (!up && err_sign < 0) return round_bits(std::nextafter(s, -INFINITY), p, false);
  return r;
}

int sign_of(double x) { return x > 0 ? 1 : x < 0 ? -1 : 0; }

}  // namespace

double round_to(double x, int p, bool up) { return held(round_bits(x, p, up)); }

double sub(double a, double b, int p, bool up) {
  const double s = a - b;
  if (!std::isfinite(s)) return held(s);
  const double bb = s - a;  // TwoSum of a and -b: s + err is exactly a - b
  const double err = (a - (s - bb)) + (-b - bb);
  // An exact zero is -0 when rounding down (IEEE, as MPFR), unless both terms are +0 and -(-0).
  if (s == 0.0 && err == 0.0 && !up && !(a == 0.0 && b == 0.0 && !std::signbit(a) && std::signbit(b)))
    return -0.0;
  return held(round_exact(s, sign_of(err), p, up));
}

double div(double a, double b, int p, bool up) {
  const double q = a / b;
  if (!std::isfinite(q) || b == 0.0) return held(q);
  const double r = std::fma(-q, b, a);  // a - q b, exact: the sign of a / b - q is sign(r) sign(b)
  return held(round_exact(q, sign_of(r) * sign_of(b), p, up));
}

}  // namespace narrow_arithmetic

NarrowBoxTester::NarrowBoxTester(const Ray& ray, int mantissa_bits) : p_(mantissa_bits + 1), tmin_(ray.tmin) {
  using narrow_arithmetic::round_to;
  for (int a = 0; a < 3; ++a) {
    negative_[a] = std::signbit(ray.d[a]);
    o_down_[a] = round_to(ray.o[a], p_, false);
    o_up_[a] = round_to(ray.o[a], p_, true);
    d_down_[a] = round_to(ray.d[a], p_, false);
    d_up_[a] = round_to(ray.d[a], p_, true);
  }
}

float NarrowBoxTester::distance(int axis, float p, bool far) const {
  using namespace narrow_arithmetic;
  // rtcore's intersect_axis: the bound, then its difference with the origin,
  // then the quotient by the direction, each rounded so that near distances
  // can only shrink and far ones grow.
  double t;
  if (!negative_[axis]) {
    t = far ? div(sub(round_to(p, p_, true), o_down_[axis], p_, true), d_down_[axis], p_, true)
            : div(sub(round_to(p, p_, false), o_up_[axis], p_, false), d_up_[axis], p_, false);
  } else {
    t = far ? div(sub(round_to(p, p_, false), o_up_[axis], p_, false), d_up_[axis], p_, true)
            : div(sub(round_to(p, p_, true), o_down_[axis], p_, true), d_down_[axis], p_, false);
  }
  return static_cast<float>(t);  // exact: p bits inside float32's range
}

bool NarrowBoxTester::hits(const Bounds3f& b, float tmax, float& entry) const {
  // rtcore's robust_max / robust_min nesting: a NaN distance is passed over.
  float tn = tmin_, tf = tmax;
  for (int a = 2; a >= 0; --a) {
    const float lo = b.lo[a], hi = b.hi[a];
    const float n = distance(a, negative_[a] ? hi : lo, false);
    const float f = distance(a, negative_[a] ? lo : hi, true);
    tn = n > tn ? n : tn;
    tf = f < tf ? f : tf;
  }
  entry = tn;
  return tn <= tf;
}

unsigned NarrowBoxTester::hits(const BvhNode& n, float tmax, float& entry0, float& entry1) const {
  const unsigned m0 = hits(n.child_bounds(0), tmax, entry0) ? 1u : 0u;
  const unsigned m1 = hits(n.child_bounds(1), tmax, entry1) ? 2u : 0u;
  return m0 | m1;
}

}  // namespace vbsim
