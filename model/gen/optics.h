// Directions a renderer gives a child ray, computed in double and rounded to
// float32 once: mirror reflection and Snell refraction. `n` is a unit normal
// on the side the incoming ray comes from (dot(d, n) < 0).
#pragma once
#include <cmath>
#include <optional>

#include "datapath/dvec3.h"

namespace vbsim {

/// Mirror direction of unit d about unit n.
inline DVec3 mirror(DVec3 d, DVec3 n) { return d + (-2.0 * ddot(d, n)) * n; }

/// Refracted direction of unit d through a surface with unit normal n facing
/// d, with eta = n_incident / n_transmitted; empty on total internal reflection.
inline std::optional<DVec3> refracted(DVec3 d, DVec3 n, double eta) {
  const double cosi = -ddot(d, n);
  const double k = 1.0 - eta * eta * (1.0 - cosi * cosi);
  if (k < 0) return std::nullopt;
  return eta * d + (eta * cosi - std::sqrt(k)) * n;
}

}  // namespace vbsim
