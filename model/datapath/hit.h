// Hit: what a tester reports for one candidate, and what a closest-hit search returns.
// Sign convention (trace spec): front = 1 when dot(d, Ng) < 0, i.e. the ray meets
// the triangle's front side; this is the three-half-plane tester's front/back bit.
#pragma once
#include <cstdint>

namespace vbsim {

struct Hit {
  int32_t prim = -1;  ///< triangle index in scene order; -1 for a miss
  float t = 0.0f;     ///< distance along the ray in units of d
  float u = 0.0f;     ///< barycentrics: p = (1-u-v) v0 + u v1 + v v2
  float v = 0.0f;
  uint8_t front = 0;  ///< front/back bit
  bool valid() const { return prim >= 0; }
};

}  // namespace vbsim
