// Fit parameters: the one number of a self-intersection method that `vbsim fit`
// searches, on a grid of candidate values. Index 0 is the value 0 (the method
// with nothing to act on); indices 1..top() are either the integers 1..top()
// (guard bits) or a geometric grid from `lowest` up by a factor 2^(1/steps_per_octave).
#pragma once
#include <string>
#include <vector>

#include "replay/replay_options.h"

namespace vbsim {

struct FitParameter {
  std::string key;          ///< vb-eps, vb-guard-bits, tmin-eps, offset-normal-eps, offset-direction-eps, adaptive-scale
  std::string description;  ///< for the report
  bool integer = false;     ///< grid of integers 0..top()
  int top_index = 0;        ///< the largest grid index
  double lowest = 0.0;      ///< value of index 1 on a geometric grid
  int steps_per_octave = 1;
  ReplayOptions base;       ///< the method alone, the parameter not yet set

  /// The value at grid index `i` (0 <= i <= top_index).
  double value(int i) const;
  /// `base` with the parameter set to value(i).
  ReplayOptions options_at(int i) const;
};

/// The settings shared by every fit: tester, hit point, the avoidance unit's
/// policy and (for the guard band) minimum exponent.
struct FitSettings {
  TesterKind tester = TesterKind::ThreeHalfPlane;
  HitPointMode hit_point = HitPointMode::Given;
  AvoidancePolicy vb_policy = AvoidancePolicy::All;
  int vb_min_exponent = 1;  ///< 1: no clamp, the guard band alone sets epsilon
};

/// Every parameter key `vbsim fit` knows, in report order.
const std::vector<std::string>& fit_parameter_keys();

/// The parameter called `key` under `settings`; throws ConfigError for an unknown key.
FitParameter make_fit_parameter(const std::string& key, const FitSettings& settings);

}  // namespace vbsim
