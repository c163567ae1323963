#include "bench/cycle_bench.h"

#include <algorithm>
#include <chrono>

#include "hw/cycle_replay.h"
#include "scene/embree_reference.h"

namespace vbsim {

CycleBenchResult run_cycle_bench(const Scene& scene, const ReplayOptions& opt, const hw::HwConfig& cfg,
                                 const BenchWorkload& w, const BenchParams& p) {
  CycleBenchResult out;
  BenchResult& res = out.speed;
  const std::vector<TraceRay>& rays = w.rays;
  res.rays = w.size();
  auto t0 = std::chrono::steady_clock::now();
  const Bvh bvh = build_bvh(scene, opt.bvh);
  res.bvh_build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  t0 = std::chrono::steady_clock::now();
  const EmbreeReference embree(scene, p.embree_accel);
  res.embree_build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  std::vector<int32_t> ours(rays.size()), theirs;
  double best_vbsim = 1e300, best_embree = 1e300;
  hw::CycleRunOptions options;
  options.track_parents = w.with_parents;
  for (int rep = 0; rep < p.repeats; ++rep) {
    size_t next = 0;
    const hw::RayFeed feed = [&](TraceRay& tr) {
      if (next == rays.size()) return false;
      tr = rays[next++];
      return true;
    };
    const hw::RayResultSink sink = [&](const TraceRay&, const RayOutcome& o, uint64_t, uint64_t index) {
      ours[index] = o.answer;
    };
    const hw::CycleRunResult run = hw::run_cycle_replay(feed, scene, bvh, opt, cfg, sink, options);
    best_vbsim = std::min(best_vbsim, run.stats.wall_s);
    const KindStats total = run.stats.total();
    res.node_fetches_per_ray = static_cast<double>(total.traversal.node_visits) / res.rays;
    res.box_tests_per_ray = static_cast<double>(total.traversal.box_tests) / res.rays;
    res.triangle_tests_per_ray = static_cast<double>(total.traversal.triangle_tests) / res.rays;
    out.cycles = run.counters.cycles;
    out.energy = run.hw["energy"];
    out.area = run.hw["area"];
    out.rays_per_cycle = run.counters.cycles ? static_cast<double>(run.counters.rays) / run.counters.cycles : 0;
    best_embree = std::min(best_embree, time_embree(embree, w, theirs));
  }
  finish_bench(res, best_vbsim, best_embree, scene, bvh, opt, w, ours, theirs);
  return out;
}

}  // namespace vbsim
