#include "bench/functional_bench.h"

#include <algorithm>
#include <chrono>

#include "gen/seeded_random.h"
#include "replay/functional_replayer.h"
#include "scene/embree_reference.h"

namespace vbsim {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}
}  // namespace

nlohmann::json BenchResult::to_json() const {
  return {{"rays", rays},
          {"vbsim_rays_per_s", vbsim_rays_per_s},
          {"embree_rays_per_s", embree_rays_per_s},
          {"ratio", ratio},
          {"vbsim_hits", vbsim_hits},
          {"embree_hits", embree_hits},
          {"same_prim", same_prim},
          {"node_fetches_per_ray", node_fetches_per_ray},
          {"box_tests_per_ray", box_tests_per_ray},
          {"triangle_tests_per_ray", triangle_tests_per_ray},
          {"bvh_build_s", bvh_build_s},
          {"embree_build_s", embree_build_s}};
}

std::vector<TraceRay> bench_rays(const Scene& scene, int64_t count, uint64_t seed) {
  SeededRandom rng(seed);
  const Vec3f lo = scene.bounds.lo, hi = scene.bounds.hi;
  const Vec3f center = 0.5f * (lo + hi);
  const float radius = std::max(0.5f * length(hi - lo), 1e-6f);
  std::vector<TraceRay> rays(static_cast<size_t>(count));
  for (int64_t i = 0; i < count; ++i) {
    TraceRay& r = rays[static_cast<size_t>(i)];
    r.id = i;
    r.o = center + (2.0f * radius) * rng.unit_vector();
    const Vec3f target{static_cast<float>(rng.uniform(lo.x, hi.x)), static_cast<float>(rng.uniform(lo.y, hi.y)),
                       static_cast<float>(rng.uniform(lo.z, hi.z))};
    r.d = target - r.o;
  }
  return rays;
}

BenchResult run_functional_bench(const Scene& scene, const ReplayOptions& opt, const BenchParams& p) {
  BenchResult res;
  const std::vector<TraceRay> rays = bench_rays(scene, p.rays, p.seed);
  res.rays = p.rays;

  auto t0 = Clock::now();
  const Bvh bvh = build_bvh(scene, opt.bvh);
  res.bvh_build_s = seconds_since(t0);
  t0 = Clock::now();
  const EmbreeReference embree(scene, p.embree_accel);
  res.embree_build_s = seconds_since(t0);

  std::vector<int32_t> ours(rays.size()), theirs(rays.size());
  double best_vbsim = 1e300, best_embree = 1e300;
  for (int rep = 0; rep < p.repeats; ++rep) {
    FunctionalReplayer replayer(scene, bvh, opt);
    replayer.set_track_parents(false);
    t0 = Clock::now();
    for (size_t i = 0; i < rays.size(); ++i) ours[i] = replayer.replay(rays[i]).answer;
    best_vbsim = std::min(best_vbsim, seconds_since(t0));
    const KindStats total = replayer.stats().total();
    res.node_fetches_per_ray = static_cast<double>(total.traversal.node_visits) / p.rays;
    res.box_tests_per_ray = static_cast<double>(total.traversal.box_tests) / p.rays;
    res.triangle_tests_per_ray = static_cast<double>(total.traversal.triangle_tests) / p.rays;

    best_embree = std::min(best_embree, time_embree(embree, rays, theirs));
  }
  finish_bench(res, best_vbsim, best_embree, ours, theirs);
  return res;
}

double time_embree(const EmbreeReference& embree, const std::vector<TraceRay>& rays, std::vector<int32_t>& prims) {
  prims.resize(rays.size());
  const auto t0 = Clock::now();
  for (size_t i = 0; i < rays.size(); ++i) {
    int32_t prim;
    float t, u, v;
    const TraceRay& r = rays[i];
    prims[i] = embree.intersect(r.o, r.d, r.tmin, r.tmax, prim, t, u, v) ? prim : -1;
  }
  return seconds_since(t0);
}

void finish_bench(BenchResult& res, double vbsim_s, double embree_s, const std::vector<int32_t>& ours,
                  const std::vector<int32_t>& theirs) {
  res.vbsim_rays_per_s = res.rays / vbsim_s;
  res.embree_rays_per_s = res.rays / embree_s;
  res.ratio = res.vbsim_rays_per_s / res.embree_rays_per_s;
  for (size_t i = 0; i < ours.size(); ++i) {
    res.vbsim_hits += ours[i] >= 0;
    res.embree_hits += theirs[i] >= 0;
    res.same_prim += ours[i] == theirs[i];
  }
}

}  // namespace vbsim
