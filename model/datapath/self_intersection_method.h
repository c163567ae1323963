// SelfIntersectionMethod: which self-intersection methods a replay applies and
// their parameters. Methods are chosen by name at run time and compose with '+'
// ("offset-adaptive+primid"). Two places act:
//   at emission (the ray's origin/interval before it enters the accelerator):
//     tmin, offset-normal, offset-direction, offset-adaptive, offset-errbound,
//     shading-position, shading-position-always, reverse-shadow
//   per candidate hit (inside the closest-hit search): primid, validity-bit,
//     sign-only
// `none` is the empty composition.
#pragma once
#include <string>
#include <vector>

#include "datapath/avoidance_unit.h"

namespace vbsim {

struct AdaptiveOffsetParams {  ///< Ray Tracing Gems ch. 6, Listing 6-1 constants
  float origin = 1.0f / 32.0f;
  float float_scale = 1.0f / 65536.0f;
  float int_scale = 256.0f;
};

struct SelfIntersectionMethod {
  bool tmin = false;
  float tmin_eps = 1e-4f;          ///< distance (scene units): tmin = eps / |d|
  bool primid = false;
  bool offset_normal = false;
  float offset_normal_eps = 1e-4f;     ///< scene units, along the unit shading normal
  bool offset_direction = false;
  float offset_direction_eps = 1e-4f;  ///< scene units, along the unit direction
  bool offset_adaptive = false;
  AdaptiveOffsetParams adaptive;
  bool offset_errbound = false;
  bool validity_bit = false;       ///< the avoidance unit (policy all/vote/sign-only)
  AvoidanceConfig avoidance;
  bool shading_position = false;   ///< shadow rays: convex-only shading position
  bool shading_position_always = false;  ///< shadow rays: shading position always
  bool reverse_shadow = false;     ///< shadow rays traced from the light back

  /// Canonical name: the enabled methods joined by '+' in a fixed order, or "none".
  std::string name() const;
  /// Bits per ray in flight this composition needs (see ray.h).
  int bits_per_ray() const;
  bool filters_candidates() const { return primid || validity_bit; }
};

/// Names accepted by parse_method, in canonical order.
const std::vector<std::string>& method_names();

/// Enables the methods named in `spec` ("a+b+..."); parameters keep their
/// current values. Returns false with `error` naming the unknown part.
bool parse_method(const std::string& spec, SelfIntersectionMethod& method, std::string& error);

}  // namespace vbsim
