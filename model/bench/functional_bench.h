// Functional speed benchmark: times vbsim's functional replay and Embree's
// rtcIntersect1 on the same random rays against the same scene, in one run, on
// one thread. A benchmark, not a test: it reports, it asserts nothing.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "replay/replay_options.h"
#include "scene/bvh.h"
#include "scene/scene.h"
#include "trace/trace_record.h"

namespace vbsim {

struct BenchParams {
  int64_t rays = 200000;
  uint64_t seed = 1;
  int repeats = 3;  ///< each side is timed this many times; the best run counts
  /// Embree's triangle acceleration structure (EmbreeReference's tri_accel);
  /// empty: Embree's choice for the host.
  std::string embree_accel;
};

struct BenchResult {
  int64_t rays = 0;
  double vbsim_rays_per_s = 0;
  double embree_rays_per_s = 0;
  double ratio = 0;          ///< vbsim / Embree
  int64_t vbsim_hits = 0;
  int64_t embree_hits = 0;
  int64_t same_prim = 0;     ///< rays where both returned the same triangle (or both missed)
  double node_fetches_per_ray = 0;    ///< vbsim's traversal work per ray: node fetches (of the tree's width)
  double box_tests_per_ray = 0;       ///< ... box tests
  double triangle_tests_per_ray = 0;
  double bvh_build_s = 0;
  double embree_build_s = 0;
  nlohmann::json to_json() const;
};

/// Camera-like rays: origins on a sphere around the scene, aimed at uniform
/// points inside its bounding box (so most of them hit). Deterministic per seed.
std::vector<TraceRay> bench_rays(const Scene& scene, int64_t count, uint64_t seed);

class EmbreeReference;

/// Seconds Embree's rtcIntersect1 takes over `rays`; each ray's triangle (or -1) into `prims`.
double time_embree(const EmbreeReference& embree, const std::vector<TraceRay>& rays, std::vector<int32_t>& prims);
/// Fills the speeds, ratio and agreement counts of `res` (whose `rays` is set).
void finish_bench(BenchResult& res, double vbsim_s, double embree_s, const std::vector<int32_t>& ours,
                  const std::vector<int32_t>& theirs);

BenchResult run_functional_bench(const Scene& scene, const ReplayOptions& opt, const BenchParams& p);

}  // namespace vbsim
