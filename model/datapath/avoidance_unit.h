// AvoidanceUnit: the patent's intersection-avoidance unit (US 8,441,482, FIG. 7/8).
//
// A candidate hit is *suspect* when the ray's parent sign bit equals the tester's
// front/back bit (both are "dot(d, N) < 0" for their normal, trace spec). A suspect
// then faces the epsilon tests, each of which says "invalid" (too close to be real):
//   normal     distance from the ray origin to the candidate's plane, along its
//              normal: |dot(o - v0, Ng)| / |Ng| < eps  (evaluated squared, no sqrt)
//   ray        distance from the origin along the ray: t |d| < eps (squared)
//   component  component-wise approximation of the ray test: every |t d_i| <
//              component_scale * eps (a box inscribed in the ray test's sphere)
// Policy `all` rejects when every enabled test says invalid (the patent's preferred
// flow); `vote` rejects when the invalid tests' weights reach half the enabled
// weight (normal weighted 2, the others 1: the normal test alone suffices, the
// two along-the-ray tests must agree to outvote it). `sign_only` rejects every
// suspect with no epsilon test: the bit alone.
//
// Epsilon: fixed, or derived from the candidate's vertices as the patent's
// dynamic epsilon: with E the largest biased float32 exponent among the nine
// vertex coordinates, eps = 2^(max(E - 23 + guard_bits, min_exponent) - 127),
// i.e. one ulp of the largest coordinate widened by the guard band, clamped to a
// minimum biased exponent (the patent suggests 108 to 112; 2^(110-127) = 7.6e-6).
#pragma once
#include <cstdint>
#include <string>

#include "datapath/hit.h"
#include "datapath/ray.h"
#include "datapath/triangle.h"

namespace vbsim {

enum class AvoidancePolicy : uint8_t { All, Vote, SignOnly };
enum class EpsilonMode : uint8_t { Fixed, Exponent };

const char* avoidance_policy_name(AvoidancePolicy p);
bool parse_avoidance_policy(const std::string& s, AvoidancePolicy& out);
const char* epsilon_mode_name(EpsilonMode m);
bool parse_epsilon_mode(const std::string& s, EpsilonMode& out);

struct AvoidanceConfig {
  AvoidancePolicy policy = AvoidancePolicy::All;
  EpsilonMode eps_mode = EpsilonMode::Exponent;
  float eps = 1e-4f;              ///< fixed epsilon (scene units), eps_mode Fixed
  int guard_bits = 5;             ///< eps_mode Exponent: guard band in bits
  int min_exponent = 110;         ///< eps_mode Exponent: minimum biased exponent
  bool test_normal = true;
  bool test_ray = true;
  bool test_component = false;
  float component_scale = 0.57735027f;  ///< 1/sqrt(3): box inside the sphere
  int weight_normal = 2, weight_ray = 1, weight_component = 1;  ///< policy Vote
};

/// Which epsilon tests said "invalid", and the decision. Bit i of `invalid` is
/// set when test i (kTestNormal, kTestRay, kTestComponent) said invalid.
struct AvoidanceDecision {
  enum : uint8_t { kTestNormal = 1, kTestRay = 2, kTestComponent = 4 };
  bool suspect = false;
  uint8_t invalid = 0;
  bool reject = false;
};

/// Epsilon for a candidate on `tri` under `cfg` (fixed or exponent-derived).
float avoidance_epsilon(const AvoidanceConfig& cfg, const Triangle& tri);

/// The unit's decision for one candidate `hit` on `tri` of `ray`. Pure function.
AvoidanceDecision avoidance_decide(const AvoidanceConfig& cfg, const Ray& ray,
                                   const Triangle& tri, const Hit& hit);

}  // namespace vbsim
