// Cycle-level cost of a trace's rays under one configuration: the one place
// `vbsim score --mode cycle` and the main job's trade-off table run the
// cycle-level model (hw::run_cycle_replay). SystemC runs one simulation at a
// time per process, so callers run these one after another, never from
// several threads.
#pragma once
#include <cstdint>

#include "energy/tech_file.h"
#include "hw/hw_config.h"
#include "hw/source/ray_feed.h"
#include "replay/replay_options.h"
#include "replay/replay_stats.h"
#include "scene/bvh.h"
#include "scene/scene.h"

namespace vbsim {

struct CycleCost {
  uint64_t rays = 0;
  uint64_t cycles = 0;  ///< from the first ray's arrival to the last ray's verdict
  ReplayStats stats;    ///< the cycle-level replay's own verdicts and counters
  /// The run's energy (operations, memory, leakage: hw.energy.total_pj) and
  /// the chip's area (hw.area.chip_mm2), priced by the technology file.
  double total_pj = 0, chip_mm2 = 0;
};

/// Replays the rays `feed` gives (one trace, parents before children, streamed:
/// nothing of the trace is held beyond the model's own window) through the
/// cycle-level model of `cfg` on `scene`/`bvh` under `opt`. `locate` names a
/// ray's file and line in the errors the model finds (may be empty). `tech`
/// prices the energy and area (null: the shipped default).
CycleCost cycle_replay_cost(const hw::RayFeed& feed, const Scene& scene, const Bvh& bvh, const ReplayOptions& opt,
                            const hw::HwConfig& cfg, const hw::RayLocator& locate = {},
                            const TechFile* tech = nullptr);

}  // namespace vbsim
