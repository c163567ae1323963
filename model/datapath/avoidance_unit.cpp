#include "datapath/avoidance_unit.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace vbsim {

namespace {

int biased_exponent(float f) {
  uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  return static_cast<int>((bits >> 23) & 0xffu);
}

bool test_enabled(const AvoidanceConfig& cfg, uint8_t test) {
  switch (test) {
    case AvoidanceDecision::kTestNormal: return cfg.test_normal;
    case AvoidanceDecision::kTestRay: return cfg.test_ray;
    default: return cfg.test_component;
  }
}

int test_weight(const AvoidanceConfig& cfg, uint8_t test) {
  switch (test) {
    case AvoidanceDecision::kTestNormal: return cfg.weight_normal;
    case AvoidanceDecision::kTestRay: return cfg.weight_ray;
    default: return cfg.weight_component;
  }
}

}  // namespace

const char* avoidance_policy_name(AvoidancePolicy p) {
  switch (p) {
    case AvoidancePolicy::All: return "all";
    case AvoidancePolicy::Vote: return "vote";
    default: return "sign-only";
  }
}

bool parse_avoidance_policy(const std::string& s, AvoidancePolicy& out) {
  if (s == "all") out = AvoidancePolicy::All;
  else if (s == "vote") out = AvoidancePolicy::Vote;
  else if (s == "sign-only") out = AvoidancePolicy::SignOnly;
  else return false;
  return true;
}

const char* epsilon_mode_name(EpsilonMode m) {
  return m == EpsilonMode::Fixed ? "fixed" : "exponent";
}

bool parse_epsilon_mode(const std::string& s, EpsilonMode& out) {
  if (s == "fixed") out = EpsilonMode::Fixed;
  else if (s == "exponent") out = EpsilonMode::Exponent;
  else return false;
  return true;
}

float avoidance_epsilon(const AvoidanceConfig& cfg, const Triangle& tri) {
  if (cfg.eps_mode == EpsilonMode::Fixed) return cfg.eps;
  int e = 0;
  for (const Vec3f& v : {tri.v0, tri.v1, tri.v2})
    for (int i = 0; i < 3; ++i) e = std::max(e, biased_exponent(v[i]));
  const int eps_exponent = std::max(e - 23 + cfg.guard_bits, cfg.min_exponent);
  return std::ldexp(1.0f, eps_exponent - 127);
}

AvoidanceDecision avoidance_decide(const AvoidanceConfig& cfg, const Ray& ray,
                                   const Triangle& tri, const Hit& hit) {
  AvoidanceDecision out;
  out.suspect = (ray.sign == hit.front);
  if (!out.suspect) return out;
  if (cfg.policy == AvoidancePolicy::SignOnly) {
    out.reject = true;
    return out;
  }
  const float eps = avoidance_epsilon(cfg, tri);
  const float eps2 = eps * eps;
  if (cfg.test_normal) {
    const Vec3f ng = geometric_normal(tri);
    const float dist = dot(ray.o - tri.v0, ng);  // |Ng| * signed distance
    if (dist * dist < eps2 * dot(ng, ng)) out.invalid |= AvoidanceDecision::kTestNormal;
  }
  const Vec3f along = hit.t * ray.d;  // displacement from origin to the candidate
  if (cfg.test_ray && dot(along, along) < eps2) out.invalid |= AvoidanceDecision::kTestRay;
  if (cfg.test_component) {
    const float box = cfg.component_scale * eps;
    const Vec3f a = abs(along);
    if (a.x < box && a.y < box && a.z < box) out.invalid |= AvoidanceDecision::kTestComponent;
  }

  int enabled = 0, invalid = 0, enabled_weight = 0, invalid_weight = 0;
  for (uint8_t test : {AvoidanceDecision::kTestNormal, AvoidanceDecision::kTestRay,
                       AvoidanceDecision::kTestComponent}) {
    if (!test_enabled(cfg, test)) continue;
    ++enabled;
    enabled_weight += test_weight(cfg, test);
    if (out.invalid & test) {
      ++invalid;
      invalid_weight += test_weight(cfg, test);
    }
  }
  if (cfg.policy == AvoidancePolicy::All)
    out.reject = enabled > 0 && invalid == enabled;
  else
    out.reject = enabled_weight > 0 && 2 * invalid_weight >= enabled_weight;
  return out;
}

}  // namespace vbsim
