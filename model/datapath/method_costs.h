// MethodCost: the arithmetic a self-intersection method adds to a ray, counted
// operation by operation from the datapath's code, by kind of operator
// (op_counts.h), for the speed-against-accuracy charts and the energy model
// (docs/energy.md). Values a renderer already holds (the hit point, the
// parent's geometric normal, the ray) cost nothing; the candidate triangle's
// normal is recomputed (2 edges + cross = 15), since the three-half-plane
// tester does not produce it.
//
// Ops per ray = emission + result + candidate * candidates per ray + suspect *
// suspects per ray, with the candidate and suspect counts a replay measures.
#pragma once
#include "datapath/op_counts.h"
#include "datapath/self_intersection_method.h"

namespace vbsim {

/// The operations of a method, by kind.
struct MethodOps {
  OpCounts emission;   ///< once per ray, before it enters the accelerator
  OpCounts result;     ///< once per ray, on the search's answer (reverse-shadow's parent id)
  OpCounts candidate;  ///< per candidate hit the tester reports
  OpCounts suspect;    ///< per suspect (validity-bit epsilon tests)
};

/// The totals of MethodOps (every kind counts one).
struct MethodCost {
  int emission = 0;   ///< operations once per ray, before it enters the accelerator
  int result = 0;     ///< operations once per ray, on the answer
  int candidate = 0;  ///< operations per candidate hit the tester reports
  int suspect = 0;    ///< operations per suspect (validity-bit epsilon tests)
};

/// The operations of `method` as configured (enabled tests, epsilon mode, policy);
/// `emission` and `result` are those of a ray every emission-time part acts on
/// (a shadow ray with a parent surface).
MethodOps method_ops(const SelfIntersectionMethod& method);
/// The emission-time operations `method` performs on one ray, as the ray
/// emission applies its parts (replay/ray_emission.cpp, and the ray source's
/// count): `tmin` on every ray; the offsets, shading positions and the sign bit
/// on rays with a parent surface (`child`), shading positions only on shadow
/// ones; `reverse-shadow` on every shadow ray.
OpCounts emission_ops_for(const SelfIntersectionMethod& method, bool child, bool shadow);
/// The per-ray operations on the answer: reverse-shadow's id compare on shadow rays.
OpCounts result_ops_for(const SelfIntersectionMethod& method, bool shadow);
/// Their totals.
MethodCost method_cost(const SelfIntersectionMethod& method);

}  // namespace vbsim
