// pbrt-v4's float32 arithmetic, operation for operation, for the methods that
// name pbrt-v4 as their reference (offset-errbound, the pbrt-watertight tester,
// the pbrt-v4 generator protocol). Each function rounds where pbrt-v4 rounds:
//   difference_of_products(a, b, c, d) = a b - c d with two FMAs and a final add
//     (pbrt's DifferenceOfProducts: cd = c d; (fma(a, b, -cd)) + fma(-c, d, cd));
//   sum_of_products likewise with + (SumOfProducts);
//   pbrt_cross: each component a difference_of_products;
//   pbrt_dot(a, b) = fma(a.x, b.x, sum_of_products(a.y, b.y, a.z, b.z));
//   pbrt_length_squared = (x x + y y) + z z, plain; pbrt_normalize divides each
//     component by the length (no reciprocal);
//   next_float_up/down step one float, treating -0 as +0 (and +0 as -0) first;
//   gamma(n) = n u / (1 - n u) in float, u = 2^-24.
// std::fma rounds once, as the FMA pbrt-v4 calls does. The build turns off FMA
// contraction, so the plain operations round once each, in source order.
#pragma once
#include <cmath>
#include <cstdint>
#include <limits>

#include "datapath/float_bits.h"
#include "datapath/vec3.h"

namespace vbsim::pbrt {

constexpr float kMachineEpsilon = 0.5f * std::numeric_limits<float>::epsilon();  ///< 2^-24
constexpr float kShadowEpsilon = 0.0001f;  ///< pbrt-v4's ShadowEpsilon (SpawnRayTo's tMax is 1 - it)

constexpr float gamma(int n) { return (n * kMachineEpsilon) / (1 - n * kMachineEpsilon); }

inline float difference_of_products(float a, float b, float c, float d) {
  const float cd = c * d;
  const float dop = std::fma(a, b, -cd);
  const float err = std::fma(-c, d, cd);
  return dop + err;
}

inline float sum_of_products(float a, float b, float c, float d) {
  const float cd = c * d;
  const float sop = std::fma(a, b, cd);
  const float err = std::fma(c, d, -cd);
  return sop + err;
}

inline Vec3f pbrt_cross(Vec3f a, Vec3f b) {
  return {difference_of_products(a.y, b.z, a.z, b.y), difference_of_products(a.z, b.x, a.x, b.z),
          difference_of_products(a.x, b.y, a.y, b.x)};
}

inline float pbrt_dot(Vec3f a, Vec3f b) { return std::fma(a.x, b.x, sum_of_products(a.y, b.y, a.z, b.z)); }

inline float pbrt_length_squared(Vec3f a) { return a.x * a.x + a.y * a.y + a.z * a.z; }

inline Vec3f pbrt_normalize(Vec3f a) {
  const float len = std::sqrt(pbrt_length_squared(a));
  return {a.x / len, a.y / len, a.z / len};
}

/// pbrt's FaceForward(n, v): -n when pbrt_dot(n, v) < 0, else n.
inline Vec3f face_forward(Vec3f n, Vec3f v) { return pbrt_dot(n, v) < 0.0f ? -n : n; }

inline float next_float_up(float v) {
  if (std::isinf(v) && v > 0.0f) return v;
  if (v == -0.0f) v = 0.0f;
  uint32_t u = float_bits(v);
  if (v >= 0.0f) ++u;
  else --u;
  return bits_float(u);
}

inline float next_float_down(float v) {
  if (std::isinf(v) && v < 0.0f) return v;
  if (v == 0.0f) v = -0.0f;
  uint32_t u = float_bits(v);
  if (v > 0.0f) --u;
  else ++u;
  return bits_float(u);
}

/// pbrt-v4's Point3fi: one interval per component. A point with an error bound
/// becomes [next_float_down(p - e), next_float_up(p + e)] (exactly p when e is
/// 0); its point is the midpoint (lo + hi) / 2 and its error the half width
/// (hi - lo) / 2, both in float, so neither is exactly the p and e it was made of.
struct PointInterval {
  Vec3f lo, hi;

  static PointInterval from_value_and_error(Vec3f p, Vec3f e) {
    PointInterval pi;
    for (int i = 0; i < 3; ++i) {
      if (e[i] == 0.0f) {
        pi.lo[i] = pi.hi[i] = p[i];
      } else {
        pi.lo[i] = next_float_down(p[i] - e[i]);
        pi.hi[i] = next_float_up(p[i] + e[i]);
      }
    }
    return pi;
  }
  Vec3f point() const { return {(lo.x + hi.x) / 2, (lo.y + hi.y) / 2, (lo.z + hi.z) / 2}; }
  Vec3f error() const { return {(hi.x - lo.x) / 2, (hi.y - lo.y) / 2, (hi.z - lo.z) / 2}; }
};

}  // namespace vbsim::pbrt
