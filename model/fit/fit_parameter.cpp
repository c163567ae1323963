#include "fit/fit_parameter.h"

#include <fmt/format.h>

#include <cmath>

#include "replay/replay_config.h"

namespace vbsim {

namespace {

/// Distances: 2^-40 (far below any float32 scene's rounding near 1) to 2^24,
/// 0.07% apart.
constexpr int kDistanceLowExp = -40, kDistanceHighExp = 24, kStepsPerOctave = 1024;
/// Offset-adaptive scale (a multiplier of Listing 6-1's int_scale and
/// float_scale): 2^-16 to 2^11 (int_scale below the configuration's 1e6 limit).
constexpr int kScaleLowExp = -16, kScaleHighExp = 11;

FitParameter geometric(const std::string& key, std::string description, int low_exp, int high_exp) {
  FitParameter p;
  p.key = key;
  p.description = std::move(description);
  p.lowest = std::ldexp(1.0, low_exp);
  p.steps_per_octave = kStepsPerOctave;
  p.top_index = (high_exp - low_exp) * kStepsPerOctave + 1;
  return p;
}

}  // namespace

double FitParameter::value(int i) const {
  if (i <= 0) return 0.0;
  if (integer) return i;
  return lowest * std::exp2(static_cast<double>(i - 1) / steps_per_octave);
}

ReplayOptions FitParameter::options_at(int i) const {
  ReplayOptions o = base;
  SelfIntersectionMethod& m = o.method;
  const float v = static_cast<float>(value(i));
  if (key == "vb-eps") m.avoidance.eps = v;
  else if (key == "vb-guard-bits") m.avoidance.guard_bits = i;
  else if (key == "tmin-eps") m.tmin_eps = v;
  else if (key == "offset-normal-eps") m.offset_normal_eps = v;
  else if (key == "offset-direction-eps") m.offset_direction_eps = v;
  else if (key == "adaptive-scale") {
    const AdaptiveOffsetParams listing;
    m.adaptive.int_scale = listing.int_scale * v;
    m.adaptive.float_scale = listing.float_scale * v;
  }
  return o;
}

const std::vector<std::string>& fit_parameter_keys() {
  static const std::vector<std::string> keys = {"vb-eps",           "vb-guard-bits",        "tmin-eps",
                                                "offset-normal-eps", "offset-direction-eps", "adaptive-scale"};
  return keys;
}

FitParameter make_fit_parameter(const std::string& key, const FitSettings& s) {
  FitParameter p;
  const char* policy = avoidance_policy_name(s.vb_policy);
  if (key == "vb-eps") {
    p = geometric(key, fmt::format("validity-bit, fixed epsilon (policy {})", policy), kDistanceLowExp,
                  kDistanceHighExp);
    p.base.method.validity_bit = true;
    p.base.method.avoidance.eps_mode = EpsilonMode::Fixed;
  } else if (key == "vb-guard-bits") {
    p.key = key;
    p.description = fmt::format("validity-bit, guard band of the exponent-derived epsilon (policy {}, min exponent {})",
                                policy, s.vb_min_exponent);
    p.integer = true;
    p.top_index = 23;
    p.base.method.validity_bit = true;
    p.base.method.avoidance.eps_mode = EpsilonMode::Exponent;
  } else if (key == "tmin-eps") {
    p = geometric(key, "tmin, distance along the ray", kDistanceLowExp, kDistanceHighExp);
    p.base.method.tmin = true;
  } else if (key == "offset-normal-eps") {
    p = geometric(key, "offset-normal, distance along the shading normal", kDistanceLowExp, kDistanceHighExp);
    p.base.method.offset_normal = true;
  } else if (key == "offset-direction-eps") {
    p = geometric(key, "offset-direction, distance along the ray", kDistanceLowExp, kDistanceHighExp);
    p.base.method.offset_direction = true;
  } else if (key == "adaptive-scale") {
    p = geometric(key, "offset-adaptive, scale of Listing 6-1's int_scale and float_scale (1 = the book's)",
                  kScaleLowExp, kScaleHighExp);
    p.base.method.offset_adaptive = true;
  } else {
    std::string known;
    for (const std::string& k : fit_parameter_keys()) known += (known.empty() ? "" : ", ") + k;
    throw ConfigError(fmt::format("unknown fit parameter '{}' (parameters: {})", key, known));
  }
  p.base.tester = s.tester;
  p.base.hit_point = s.hit_point;
  p.base.method.avoidance.policy = s.vb_policy;
  p.base.method.avoidance.min_exponent = s.vb_min_exponent;
  return p;
}

}  // namespace vbsim
