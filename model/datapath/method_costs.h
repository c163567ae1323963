// MethodCost: the arithmetic a self-intersection method adds to a ray, counted
// operation by operation from the datapath's code, for the speed-against-accuracy
// charts. One operation is one float add, subtract, multiply, divide, square
// root, compare, absolute value, negation or select, one float<->int conversion,
// or one integer add, compare, shift or exponent-field extraction. Vector ops
// count per component: dot = 3 mul + 2 add = 5, cross = 6 mul + 3 sub = 9,
// normalize = dot + sqrt + div + 3 mul = 10. Values a renderer already holds
// (the hit point, the parent's geometric normal, the ray) cost nothing; the
// candidate triangle's normal is recomputed (2 edges + cross = 15), since the
// three-half-plane tester does not produce it.
//
// Ops per ray = emission + candidate * candidates per ray + suspect * suspects
// per ray, with the candidate and suspect counts a replay measures.
#pragma once
#include "datapath/self_intersection_method.h"

namespace vbsim {

struct MethodCost {
  int emission = 0;   ///< operations once per ray, before it enters the accelerator
  int candidate = 0;  ///< operations per candidate hit the tester reports
  int suspect = 0;    ///< operations per suspect (validity-bit epsilon tests)
};

/// The cost of `method` as configured (enabled tests, epsilon mode, policy).
MethodCost method_cost(const SelfIntersectionMethod& method);

}  // namespace vbsim
