// Cycle-level replay: a stream of trace rays through the cycle engine under
// SystemC, with the same emission, filter, verdicts and statistics as the
// functional replay, plus the `hw` section. Shared by `vbsim replay --mode
// cycle`, `vbsim bench --mode cycle` and the tests.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hw/cycle_engine.h"
#include "hw/hw_config.h"
#include "hw/systemc_driver.h"
#include "replay/replay_options.h"
#include "replay/replay_stats.h"
#include "scene/bvh.h"
#include "scene/scene.h"

namespace vbsim::hw {

struct CycleRunOptions {
  DriveOptions drive;                ///< VCD, stop flag, progress callback
  std::string timeline;              ///< Chrome trace-event JSON of a cycle window (empty: none)
  uint64_t timeline_first = 0;       ///< first cycle of the window
  uint64_t timeline_cycles = 2000;   ///< cycles in the window
  bool track_parents = true;         ///< keep parent rays (FunctionalReplayer::set_track_parents)
};

struct CycleRunResult {
  ReplayStats stats;     ///< mode "cycle"; partial when stopped
  nlohmann::json hw;     ///< the `hw` section
  std::string table;     ///< the human table of `hw`
  HwCounters counters;
};

/// Replays the rays `feed` gives on `scene`/`bvh`. Throws what make_memory
/// throws (e.g. a memory model this build lacks) before any ray is read.
CycleRunResult run_cycle_replay(const RayFeed& feed, const Scene& scene, const Bvh& bvh, const ReplayOptions& opt,
                                const HwConfig& cfg, const RayResultSink& sink, const CycleRunOptions& options);

/// Writes `events` as Chrome trace-event JSON (one process per core, one thread
/// per slot; 1 us on the viewer's time axis = 1 cycle).
void write_timeline(const std::string& path, const std::vector<TimelineEvent>& events);

}  // namespace vbsim::hw
