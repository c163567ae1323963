// DVec3: double-precision vectors for building geometry and directions before
// they are rounded to float32 once (scenario generators, the render camera).
#pragma once
#include <cmath>

#include "datapath/vec3.h"

namespace vbsim {

struct DVec3 {
  double x = 0, y = 0, z = 0;
};
inline DVec3 operator+(DVec3 a, DVec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline DVec3 operator-(DVec3 a, DVec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline DVec3 operator*(double s, DVec3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double ddot(DVec3 a, DVec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline DVec3 dcross(DVec3 a, DVec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline DVec3 dunit(DVec3 a) { return (1.0 / std::sqrt(ddot(a, a))) * a; }
inline DVec3 to_dvec(Vec3f v) { return {v.x, v.y, v.z}; }
inline Vec3f to_vec3f(DVec3 v) {
  return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
}

}  // namespace vbsim
