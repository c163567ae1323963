// The path tracer's random numbers: a hash of (seed, pixel, sample, bounce,
// dimension), not a stream, so a path's numbers do not depend on which rays
// were traced before it (the closed loop answers rays in any order).
#pragma once
#include <cstdint>

#include "datapath/vec3.h"

namespace vbsim {

class RenderRandom {
 public:
  RenderRandom(uint64_t seed, uint32_t pixel, uint32_t sample);
  /// A number in [0, 1) (24 bits) for dimension `dim` of bounce `bounce`
  /// (bounce 0, dimensions 0 and 1: the primary ray's offset in its pixel).
  float uniform(uint32_t bounce, uint32_t dim) const;
  /// A direction about the unit normal `n`, cosine-distributed (Lambert's
  /// importance sampling), from dimensions 2 and 3 of bounce `bounce`.
  Vec3f cosine_direction(Vec3f n, uint32_t bounce) const;

 private:
  uint64_t key_;
};

}  // namespace vbsim
