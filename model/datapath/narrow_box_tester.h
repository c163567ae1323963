// NarrowBoxTester: the box test of rtcore-systemc's low-precision box units
// (its MPNodeIntersector, MPFR): every slab distance computed in a narrow
// float format of P = mantissa_bits + 1 significand bits and float32's
// exponent range, each operation rounded in the direction that widens the
// slab: a near distance ((bound - o) / d) rounded down at every step, a far
// one up (the ray's origin and direction held rounded both ways). A result
// whose exponent leaves the range becomes a signed zero (below 2^-127) or an
// infinity (2^128 and above), as rtcore's check does. The box is met when the
// largest near distance (and tmin) is at most the smallest far one (and tmax);
// a NaN distance (0 / 0) is passed over. It meets every box the exact slab
// test meets, and more: a search over it keeps its hits and does more work.
//
// Every rounding is exact (double arithmetic with the exact error of each
// subtraction and division recovered, then rounded once to P bits), which a
// test checks against MPFR itself.
#pragma once
#include <cmath>

#include "datapath/ray.h"
#include "scene/bvh.h"

namespace vbsim {

namespace narrow_arithmetic {

/// x rounded to `p` significand bits (1..24) toward -inf (up: false) or +inf,
/// then held to float32's exponent range as rtcore does (see above).
double round_to(double x, int p, bool up);
/// a - b and a / b, exactly rounded to `p` bits in the direction given, then held to the range.
double sub(double a, double b, int p, bool up);
double div(double a, double b, int p, bool up);

}  // namespace narrow_arithmetic

class NarrowBoxTester {
 public:
  /// Latches `ray`; `mantissa_bits` fraction bits (0..22) a narrow value keeps.
  NarrowBoxTester(const Ray& ray, int mantissa_bits);

  /// Both child boxes of `n`: bit c set when child c's box is met within
  /// [tmin, tmax]; entry_c its near distance (meaningful when met).
  unsigned hits(const BvhNode& n, float tmax, float& entry0, float& entry1) const;
  /// One box.
  bool hits(const Bounds3f& b, float tmax, float& entry) const;

  /// The near (far: `far` true) distance of bound `p` on `axis`, in the narrow format.
  float distance(int axis, float p, bool far) const;

 private:
  int p_;
  float tmin_;
  bool negative_[3];  ///< signbit of d on each axis
  double o_down_[3], o_up_[3], d_down_[3], d_up_[3];
};

}  // namespace vbsim
