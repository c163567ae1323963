// BenchWorkload: the rays `vbsim bench` times, random camera-like rays or a
// captured trace, each with the ray vbsim's accelerator receives for it (after
// emission: the method's origin, tmin, reversal), which is the ray Embree is
// given too, so that both answer the same query.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "replay/ray_emission.h"
#include "replay/replay_options.h"
#include "scene/scene.h"
#include "trace/trace_record.h"
#include "trace/trace_source.h"

namespace vbsim {

struct BenchWorkload {
  std::vector<TraceRay> rays;       ///< vbsim replays these, in order (no expect: the bench scores nothing)
  std::vector<EmittedRay> emitted;  ///< per ray: what emission gives the accelerator (and Embree)
  /// Per ray: 1 when vbsim's search stops at the first accepted hit (shadow
  /// rays under any_hit_for_shadow); Embree then answers with rtcOccluded1 and
  /// the two are held to agree on occlusion, not on the triangle.
  std::vector<uint8_t> any_hit;
  bool with_parents = false;  ///< some ray has a parent: the replay keeps parent rays
  /// Ray `i`'s parent trace ray as a streamed replay finds it (what a ray
  /// replayed on its own, replay_one_ray, needs), or null.
  const ParentRay* parent(size_t i) const { return emitted[i].parent ? &*emitted[i].parent : nullptr; }
  int64_t size() const { return static_cast<int64_t>(rays.size()); }
};

/// Embree's answer for an any-hit ray it found occluded (no triangle named).
constexpr int32_t kEmbreeOccluded = -2;

/// Camera-like rays: origins on a sphere around the scene, aimed at uniform
/// points inside its bounding box (so most of them hit). Deterministic per seed.
std::vector<TraceRay> bench_rays(const Scene& scene, int64_t count, uint64_t seed);

/// `count` random rays (bench_rays) emitted under `opt`.
BenchWorkload random_workload(const Scene& scene, const ReplayOptions& opt, int64_t count, uint64_t seed);

/// The rays of `source` (the trace of `scene`), at most `limit` of them (< 0:
/// all), in trace order, emitted under `opt` with parents looked up as a replay
/// does. Throws TraceError from the source, and at the ray whose parent lies
/// beyond opt.parent_window (field 'parent').
BenchWorkload trace_workload(TraceSource& source, const Scene& scene, const ReplayOptions& opt, int64_t limit);

}  // namespace vbsim
