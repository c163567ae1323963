#include "bench/functional_bench.h"

#include <algorithm>
#include <chrono>

#include "parallel/parallel_for.h"
#include "replay/functional_replayer.h"
#include "scene/embree_reference.h"

namespace vbsim {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Rays a thread takes at a time.
constexpr size_t kChunkRays = 256;

/// Embree's answer for emitted ray `i` (as time_embree gives it).
int32_t embree_answer(const EmbreeReference& embree, const BenchWorkload& w, size_t i) {
  const Ray& r = w.emitted[i].ray;
  if (w.any_hit[i]) return embree.occluded(r.o, r.d, r.tmin, r.tmax) ? kEmbreeOccluded : -1;
  int32_t prim;
  float t, u, v;
  return embree.intersect(r.o, r.d, r.tmin, r.tmax, prim, t, u, v) ? prim : -1;
}

/// Seconds `chunk(begin, end)` takes for every chunk of the rays on `threads` threads.
template <class Chunk>
double time_threads(size_t rays, int threads, Chunk chunk) {
  const auto t0 = Clock::now();
  parallel_for_chunks(rays, kChunkRays, threads, [&](size_t, size_t begin, size_t end) { chunk(begin, end); });
  return seconds_since(t0);
}

/// Both sides on p.threads threads, best of p.repeats; answers held to one thread's.
ThreadedBench run_threaded(const Scene& scene, const Bvh& bvh, const ReplayOptions& opt, const BenchWorkload& w,
                           const EmbreeReference& embree, const BenchParams& p, const std::vector<int32_t>& ours,
                           const std::vector<int32_t>& theirs) {
  ThreadedBench t;
  t.threads = p.threads;
  const CandidateFilter filter(opt.method);
  std::vector<int32_t> ours_n(w.rays.size()), theirs_n(w.rays.size());
  double best_vbsim = 1e300, best_embree = 1e300;
  for (int rep = 0; rep < p.repeats; ++rep) {
    best_vbsim = std::min(best_vbsim, time_threads(w.rays.size(), p.threads, [&](size_t begin, size_t end) {
      KindStats ks;  // counted once, by the one-thread run
      for (size_t i = begin; i < end; ++i)
        ours_n[i] = replay_one_ray(w.rays[i], scene, bvh, opt, filter, w.parent(i), ks).answer;
    }));
    best_embree = std::min(best_embree, time_threads(w.rays.size(), p.threads, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) theirs_n[i] = embree_answer(embree, w, i);
    }));
  }
  for (size_t i = 0; i < w.rays.size(); ++i) {
    t.vbsim_differ += ours_n[i] != ours[i];
    t.embree_differ += theirs_n[i] != theirs[i];
  }
  t.vbsim_rays_per_s = static_cast<double>(w.rays.size()) / best_vbsim;
  t.embree_rays_per_s = static_cast<double>(w.rays.size()) / best_embree;
  t.ratio = t.vbsim_rays_per_s / t.embree_rays_per_s;
  return t;
}
}  // namespace

nlohmann::json ThreadedBench::to_json() const {
  return {{"threads", threads},
          {"vbsim_rays_per_s", vbsim_rays_per_s},
          {"embree_rays_per_s", embree_rays_per_s},
          {"ratio", ratio},
          {"vbsim_differ_from_one_thread", vbsim_differ},
          {"embree_differ_from_one_thread", embree_differ}};
}

nlohmann::json BenchResult::to_json() const {
  return {{"rays", rays},
          {"vbsim_rays_per_s", vbsim_rays_per_s},
          {"embree_rays_per_s", embree_rays_per_s},
          {"ratio", ratio},
          {"vbsim_hits", vbsim_hits},
          {"embree_hits", embree_hits},
          {"same_prim", same_prim},
          {"disagreements", disagreements.to_json()},
          {"node_fetches_per_ray", node_fetches_per_ray},
          {"box_tests_per_ray", box_tests_per_ray},
          {"triangle_tests_per_ray", triangle_tests_per_ray},
          {"bvh_build_s", bvh_build_s},
          {"embree_build_s", embree_build_s},
          {"threaded", threaded.threads > 1 ? threaded.to_json() : nlohmann::json()}};
}

BenchResult run_functional_bench(const Scene& scene, const ReplayOptions& opt, const BenchWorkload& w,
                                 const BenchParams& p) {
  BenchResult res;
  res.rays = w.size();

  auto t0 = Clock::now();
  const Bvh bvh = build_bvh(scene, opt.bvh);
  res.bvh_build_s = seconds_since(t0);
  t0 = Clock::now();
  const EmbreeReference embree(scene, p.embree_accel);
  res.embree_build_s = seconds_since(t0);

  std::vector<int32_t> ours(w.rays.size()), theirs(w.rays.size());
  double best_vbsim = 1e300, best_embree = 1e300;
  for (int rep = 0; rep < p.repeats; ++rep) {
    FunctionalReplayer replayer(scene, bvh, opt);
    replayer.set_track_parents(w.with_parents);
    t0 = Clock::now();
    for (size_t i = 0; i < w.rays.size(); ++i) ours[i] = replayer.replay(w.rays[i]).answer;
    best_vbsim = std::min(best_vbsim, seconds_since(t0));
    const KindStats total = replayer.stats().total();
    res.node_fetches_per_ray = static_cast<double>(total.traversal.node_visits) / res.rays;
    res.box_tests_per_ray = static_cast<double>(total.traversal.box_tests) / res.rays;
    res.triangle_tests_per_ray = static_cast<double>(total.traversal.triangle_tests) / res.rays;

    best_embree = std::min(best_embree, time_embree(embree, w, theirs));
  }
  finish_bench(res, best_vbsim, best_embree, scene, bvh, opt, w, ours, theirs);
  if (p.threads > 1) res.threaded = run_threaded(scene, bvh, opt, w, embree, p, ours, theirs);
  return res;
}

double time_embree(const EmbreeReference& embree, const BenchWorkload& w, std::vector<int32_t>& answers) {
  answers.resize(w.emitted.size());
  const auto t0 = Clock::now();
  for (size_t i = 0; i < w.emitted.size(); ++i) answers[i] = embree_answer(embree, w, i);
  return seconds_since(t0);
}

void finish_bench(BenchResult& res, double vbsim_s, double embree_s, const Scene& scene, const Bvh& bvh,
                  const ReplayOptions& opt, const BenchWorkload& w, const std::vector<int32_t>& ours,
                  const std::vector<int32_t>& theirs) {
  res.vbsim_rays_per_s = res.rays / vbsim_s;
  res.embree_rays_per_s = res.rays / embree_s;
  res.ratio = res.vbsim_rays_per_s / res.embree_rays_per_s;
  for (size_t i = 0; i < ours.size(); ++i) {
    res.vbsim_hits += ours[i] >= 0;
    res.embree_hits += theirs[i] != -1;
    res.same_prim += bench_answers_agree(ours[i], theirs[i], w.any_hit[i] != 0);
  }
  res.disagreements = classify_disagreements(scene, bvh, opt, w, ours, theirs);
}

}  // namespace vbsim
