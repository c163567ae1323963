// Directions a renderer gives a child ray, computed in double and rounded to
// float32 once: mirror reflection and Snell refraction. `n` is a unit normal
// on the side the incoming ray comes from (dot(d, n) < 0).
#pragma once
#include <cmath>
#include <optional>

#include "datapath/vec3.h"

namespace vbsim {

struct DVec3 {
  double x, y, z;
};
inline DVec3 to_dvec(Vec3f v) { return {v.x, v.y, v.z}; }
inline Vec3f to_fvec(DVec3 v) { return {float(v.x), float(v.y), float(v.z)}; }
inline double ddot(DVec3 a, DVec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline DVec3 dscale(double s, DVec3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline DVec3 dadd(DVec3 a, DVec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline DVec3 dunit(DVec3 a) { return dscale(1.0 / std::sqrt(ddot(a, a)), a); }

/// Mirror direction of unit d about unit n.
inline DVec3 mirror(DVec3 d, DVec3 n) { return dadd(d, dscale(-2.0 * ddot(d, n), n)); }

/// Refracted direction of unit d through a surface with unit normal n facing
/// d, with eta = n_incident / n_transmitted; empty on total internal reflection.
inline std::optional<DVec3> refracted(DVec3 d, DVec3 n, double eta) {
  const double cosi = -ddot(d, n);
  const double k = 1.0 - eta * eta * (1.0 - cosi * cosi);
  if (k < 0) return std::nullopt;
  return dadd(dscale(eta, d), dscale(eta * cosi - std::sqrt(k), n));
}

}  // namespace vbsim
