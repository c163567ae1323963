// A sampled cycle-level replay (hw/sampling/sampled_feed.h, docs/sampling.md):
// run_cycle_replay's run with the trace sampled. Its ReplayStats (hits,
// verdicts, functional statistics) cover every ray exactly; in its `hw`
// section `cycles`, `rays_per_cycle` and `rays_per_s` are estimates for the
// whole trace (`rays` is its exact count), `sampling` holds the parameters,
// the strata, the units, the estimates and their intervals, and every other
// figure describes only the rays simulated in detail. The table opens with the
// estimates.
#pragma once
#include "hw/cycle_replay.h"
#include "hw/sampling/sampling_config.h"

namespace vbsim::hw {

/// As run_cycle_replay; throws std::invalid_argument for a bad `sampling`
/// (naming its option) or replaced units (fast-forwarding uses the built-in
/// datapath and ray source).
CycleRunResult run_sampled_cycle_replay(const RayFeed& feed, const Scene& scene, const Bvh& bvh,
                                        const ReplayOptions& opt, const HwConfig& cfg, const RayResultSink& sink,
                                        const CycleRunOptions& options, const SamplingConfig& sampling);

}  // namespace vbsim::hw
