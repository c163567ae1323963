// pbrt-v4's Triangle Reintersect protocol (gen/pbrt_reintersect.h) measured
// in process, without files: each trial's triangle becomes a one-triangle
// scene, its rays are replayed with every configuration (method x tester,
// through replay_one_ray, as `vbsim score` replays a trace), and every hit of
// a child ray is a re-intersection, as pbrt's test counts it: the only geometry
// is the parent triangle, whose exact answer for a ray leaving it is always a
// miss (checked against the oracle in the tests, and by `vbsim gen
// random-triangles --set protocol=pbrt-v4` + `vbsim score` on the same trials).
// Counts are sums over trials, so the thread count does not change them.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "score/score_run.h"

namespace vbsim {

struct ReintersectParams {
  uint64_t first = 0;        ///< first triangle index (pbrt's RNG sequence)
  int64_t triangles = 1000;  ///< pbrt's own size
  int64_t children = 1000;   ///< SpawnRay and SpawnRayTo children per triangle, each
  float exp = 8.0f;
  int threads = 1;
};

/// What one configuration counted.
struct ReintersectCounts {
  uint64_t camera_rays = 0, camera_misses = 0;      ///< camera rays this tester did not hit
  uint64_t spawn_rays = 0, spawn_rehits = 0;        ///< SpawnRay children and their re-hits
  uint64_t spawn_to_rays = 0, spawn_to_rehits = 0;  ///< SpawnRayTo children (tmax 1) and their re-hits
  uint64_t offset_fallbacks = 0;                    ///< children whose offset left its reference
  void add(const ReintersectCounts& o);
};

struct ReintersectResult {
  ReintersectParams params;
  uint64_t degenerate = 0;  ///< triangles pbrt's protocol drops before any ray
  uint64_t skipped = 0;     ///< triangles whose camera ray pbrt's test missed (no children)
  std::vector<ScoreConfig> configs;
  std::vector<ReintersectCounts> counts;  ///< per configuration
  double wall_s = 0;
};

ReintersectResult run_reintersect(const ReintersectParams& params, const std::vector<ScoreConfig>& configs);

/// JSON: params, degenerate, skipped, and per configuration the counts with the
/// re-hit rates per million child rays and their 95% Wilson intervals.
nlohmann::json reintersect_json(const ReintersectResult& r, const std::string& command);
/// A markdown table of the same (one row per configuration).
std::string reintersect_markdown(const nlohmann::json& j);

}  // namespace vbsim
