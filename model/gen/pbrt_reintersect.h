// pbrt-v4's `Triangle, Reintersect` test (src/pbrt/shapes_test.cpp) as pbrt-v4
// runs it, one trial per triangle index i:
//   RNG(i) (pbrt's PCG32, util/rng.h); nine values pExp = 10^Lerp(u, -8, 8)
//   (positive) for the vertices; the triangle is dropped when its float
//   |pbrt_cross(v1 - v0, v2 - v0)|^2 < 1e-20; a target sampled on it
//   (Triangle::Sample: SampleUniformTriangle, the point's interval midpoint);
//   an origin of three pExp; the camera ray o -> target tested with pbrt's
//   IntersectTriangle, and when it misses the triangle is skipped (pbrt's
//   `continue`); otherwise `children` times: a SpawnRay child along
//   SampleUniformSphere(u) (tMax infinite) and a SpawnRayTo child toward three
//   pExp, tested with tMax 1, both from the hit's SurfaceInteraction.
// The trace records each child as pbrt's renderer holds it before the offset:
// origin pbrt's point (the interval midpoint), the SpawnRayTo direction
// p2 - that point, tmax 1; the replay's offset-errbound then recomputes pbrt's
// offset origin. pbrt itself draws 1000 children of each kind per triangle.
#pragma once
#include <cstdint>
#include <vector>

#include "datapath/triangle.h"
#include "trace/trace_record.h"

namespace vbsim {

/// pbrt-v4's RNG: PCG32 with its sequence set-up (RNG(seqIndex) uses the
/// seed MixBits(seqIndex)) and its float draw min(1 - 2^-24, u32 * 2^-32).
class PbrtRng {
 public:
  explicit PbrtRng(uint64_t sequence_index);
  /// SetSequence(sequence_index, seed), the PCG32 reference's srandom(seed, sequence).
  PbrtRng(uint64_t sequence_index, uint64_t seed);
  uint32_t next_u32();
  float uniform_float();

 private:
  uint64_t state_ = 0, inc_ = 0;
};

/// One trial of the protocol.
struct PbrtReintersectTrial {
  uint64_t index = 0;
  bool degenerate = false;  ///< dropped before any ray (pbrt's GetRandomTriangle returned null)
  bool camera_hit = false;  ///< pbrt's test hit the camera ray; only then are there children
  Triangle tri;
  /// The camera ray (id 0), then per child index j a `diffuse` SpawnRay child
  /// and a `shadow` SpawnRayTo child (ids 1, 2, ...); empty when degenerate.
  std::vector<TraceRay> rays;
};

/// Trial `index` with `children` SpawnRay and `children` SpawnRayTo rays and
/// pExp's exponent range `exp` (pbrt: 8).
PbrtReintersectTrial pbrt_reintersect_trial(uint64_t index, int64_t children, float exp = 8.0f);

}  // namespace vbsim
