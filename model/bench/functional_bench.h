// Functional speed benchmark: times vbsim's functional replay and Embree on the
// same rays (random camera-like rays or a captured trace, bench_workload.h)
// against the same scene, in one run, on one thread. A benchmark, not a test:
// it reports and names its disagreements with Embree (bench_disagreements.h),
// it asserts nothing.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/bench_disagreements.h"
#include "bench/bench_workload.h"
#include "replay/replay_options.h"
#include "scene/bvh.h"
#include "scene/scene.h"
#include "trace/trace_record.h"

namespace vbsim {

struct BenchParams {
  int repeats = 3;  ///< each side is timed this many times; the best run counts
  /// Embree's triangle acceleration structure (EmbreeReference's tri_accel);
  /// empty: Embree's choice for the host.
  std::string embree_accel;
  /// Functional mode: above 1, both sides are timed again on this many
  /// threads (rays handed out in chunks, each ray replayed on its own,
  /// replay_one_ray), and the answers are held to one thread's.
  int threads = 1;
};

/// The same rays timed on several threads (BenchParams::threads).
struct ThreadedBench {
  int threads = 1;
  double vbsim_rays_per_s = 0, embree_rays_per_s = 0, ratio = 0;
  /// Rays whose answer differs from one thread's (vbsim, Embree): 0 unless something is wrong.
  int64_t vbsim_differ = 0, embree_differ = 0;
  nlohmann::json to_json() const;
};

struct BenchResult {
  int64_t rays = 0;
  double vbsim_rays_per_s = 0;
  double embree_rays_per_s = 0;
  double ratio = 0;          ///< vbsim / Embree
  int64_t vbsim_hits = 0;
  int64_t embree_hits = 0;   ///< triangles found, and any-hit rays found occluded
  /// Rays where both agree (bench_answers_agree): the same triangle or both
  /// none; on any-hit rays occluded alike.
  int64_t same_prim = 0;
  DisagreementReport disagreements;  ///< the other rays, each classified by the exact oracle
  double node_fetches_per_ray = 0;    ///< vbsim's traversal work per ray: node fetches (of the tree's width)
  double box_tests_per_ray = 0;       ///< ... box tests
  double triangle_tests_per_ray = 0;
  double bvh_build_s = 0;
  double embree_build_s = 0;
  ThreadedBench threaded;  ///< threads 1: not timed on several threads
  nlohmann::json to_json() const;
};

class EmbreeReference;

/// Seconds Embree takes over the workload's emitted rays (rtcIntersect1, or
/// rtcOccluded1 on any-hit rays); each ray's triangle, -1, or kEmbreeOccluded
/// into `answers`.
double time_embree(const EmbreeReference& embree, const BenchWorkload& w, std::vector<int32_t>& answers);
/// Fills the speeds, ratio, agreement counts and classified disagreements of
/// `res` (whose `rays` is set).
void finish_bench(BenchResult& res, double vbsim_s, double embree_s, const Scene& scene, const Bvh& bvh,
                  const ReplayOptions& opt, const BenchWorkload& w, const std::vector<int32_t>& ours,
                  const std::vector<int32_t>& theirs);

BenchResult run_functional_bench(const Scene& scene, const ReplayOptions& opt, const BenchWorkload& w,
                                 const BenchParams& p);

}  // namespace vbsim
