// Hit point of a parent ray, the two ways Ray Tracing Gems ch. 6.2.1 compares:
// the ray equation o + t d (error mostly along the ray, off the surface) and the
// barycentric interpolation (error mostly along the surface).
#pragma once
#include "datapath/triangle.h"
#include "datapath/vec3.h"

namespace vbsim {

/// o + t d in float32.
inline Vec3f hit_point_ray(Vec3f o, Vec3f d, float t) { return o + t * d; }
/// (1-u-v) v0 + u v1 + v v2 in float32, evaluated in that order.
inline Vec3f hit_point_barycentric(const Triangle& tri, float u, float v) {
  return (1.0f - u - v) * tri.v0 + u * tri.v1 + v * tri.v2;
}

}  // namespace vbsim
