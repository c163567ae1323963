#include "score/cycle_cost.h"

#include "hw/cycle_replay.h"

namespace vbsim {

CycleCost cycle_replay_cost(const hw::RayFeed& feed, const Scene& scene, const Bvh& bvh, const ReplayOptions& opt,
                            const hw::HwConfig& cfg, const hw::RayLocator& locate, const TechFile* tech) {
  hw::CycleRunOptions options;
  options.locator = locate;
  options.tech = tech;
  const hw::CycleRunResult run = hw::run_cycle_replay(feed, scene, bvh, opt, cfg, hw::RayResultSink{}, options);
  CycleCost c;
  c.rays = run.counters.rays;
  c.cycles = run.counters.cycles;
  c.stats = run.stats;
  c.total_pj = run.hw["energy"]["total_pj"].get<double>();
  c.chip_mm2 = run.hw["area"]["chip_mm2"].get<double>();
  return c;
}

}  // namespace vbsim
