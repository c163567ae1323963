// Operation counts per method; each constant is derived in the comment beside it
// from the function that does the work (see method_costs.h for the unit).
#include "datapath/method_costs.h"

namespace vbsim {

namespace {

constexpr int kDot = 5, kNormalize = 10, kTriangleNormal = 6 + 9;
// unit_on_side (origin_offsets.cpp): normalize, dot with d, compare, 3 selects.
constexpr int kUnitOnSide = kNormalize + kDot + 1 + 3;

int emission_ops(const SelfIntersectionMethod& m) {
  int ops = 0;
  if (m.shading_position || m.shading_position_always) {
    // shading_position.cpp: per vertex normalize, p - v, dot, 3 mul, 3 sub (24);
    // interpolation w = 1-u-v (2), 9 mul + 6 add; convex-only test: 3 sub, dot,
    // compare, 3 selects (12).
    ops += 3 * (kNormalize + 3 + kDot + 3 + 3) + 2 + 15 + (m.shading_position ? 12 : 0);
  }
  if (m.offset_errbound) {
    // pbrt-v4 (pbrt_interaction.cpp; an FMA counts as one operation, a step to
    // the next float as two: a compare and an integer step). The barycentrics
    // are the renderer's own: recovering them at replay is not the method's cost.
    //   point b0 p0 + b1 p1 + b2 p2: 9 mul + 6 add; error: 9 abs, 6 add, 3 mul;
    //   interval: 3 compares with 0, 3 sub + 3 add, 6 next-float steps;
    //   midpoint and half width: 3 add + 3 div, 3 sub + 3 div;
    //   normal: 6 sub, 3 differences of products (mul, 2 fma, add), normalise
    //     (3 mul, 2 add, sqrt, 3 div);
    //   dot(|n|, error): 3 abs + a pbrt dot (mul, 3 fma, add); offset: 3 mul;
    //   side: a pbrt dot, compare, 3 negations; 3 add; rounding outward: per
    //   component 2 compares and a next-float step.
    constexpr int kPbrtDot = 5;
    ops += (9 + 6) + (9 + 6 + 3) + (3 + 3 + 3 + 6 * 2) + (3 + 3 + 3 + 3) + (6 + 3 * 4 + 9) + (3 + kPbrtDot) + 3 +
           (kPbrtDot + 1 + 3) + 3 + 3 * (2 + 2);
  }
  if (m.offset_adaptive) {
    // Listing 6-1: unit_on_side, then per component: mul, float->int, sign
    // compare, negation select, integer add, abs, compare, mul, add, select.
    ops += kUnitOnSide + 3 * 10;
  }
  if (m.offset_normal) ops += kUnitOnSide + 3 + 3;        // p + eps * u: 3 mul, 3 add
  if (m.offset_direction) ops += kNormalize + 3 + 3;      // p + eps * unit(d)
  if (m.tmin) ops += kDot + 1 + 1;                        // |d| = sqrt(dot), eps / |d|
  if (m.reverse_shadow) ops += 3 + 3 + 3 + 1;             // o + t d, -d, sign flip
  if (m.validity_bit) ops += kDot + 1;                    // sign = dot(d, Ng) < 0
  return ops;
}

int suspect_ops(const AvoidanceConfig& a) {
  if (a.policy == AvoidancePolicy::SignOnly) return 0;
  // epsilon: fixed is eps^2 (1 mul); exponent is 9 exponent extractions, 8 max,
  // subtract-and-add of the guard band (2), max with the minimum, a shift, eps^2.
  int ops = a.eps_mode == EpsilonMode::Fixed ? 1 : 9 + 8 + 2 + 1 + 1 + 1;
  // normal test: candidate normal (15), o - v0 (3), dot, square, dot(Ng, Ng),
  // eps^2 * |Ng|^2, compare.
  if (a.test_normal) ops += kTriangleNormal + 3 + kDot + 1 + kDot + 1 + 1;
  const bool along = a.test_ray || a.test_component;
  if (along) ops += 3;                             // t * d
  if (a.test_ray) ops += kDot + 1;                 // |t d|^2 < eps^2
  if (a.test_component) ops += 1 + 3 + 3;          // scale * eps, 3 abs, 3 compares
  ops += a.policy == AvoidancePolicy::Vote ? 6 : 2;  // combine the invalid bits
  return ops;
}

}  // namespace

MethodCost method_cost(const SelfIntersectionMethod& m) {
  MethodCost c;
  c.emission = emission_ops(m);
  if (m.primid || m.reverse_shadow) c.candidate += 1;  // compare with the parent id
  if (m.validity_bit) {
    c.candidate += 1;  // sign bit == front/back bit
    c.suspect = suspect_ops(m.avoidance);
  }
  return c;
}

}  // namespace vbsim
