// Cycle-level replay: a stream of trace rays through the accelerator model
// (hw/accelerator.h) in a fresh SystemC simulation context, with the same
// emission, filter, verdicts and statistics as the functional replay, plus the
// `hw` section. Shared by `vbsim replay --mode cycle`, `vbsim bench --mode
// cycle`, `vbsim score --mode cycle` and the tests; any number of runs one
// after the other in one process (never from several threads at once).
#pragma once
#include <atomic>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "energy/tech_file.h"
#include "hw/accelerator_units.h"
#include "hw/hw_config.h"
#include "hw/scheduler/cycle_engine.h"
#include "hw/source/ray_feed.h"
#include "replay/replay_options.h"
#include "replay/replay_stats.h"
#include "scene/bvh.h"
#include "scene/scene.h"

namespace vbsim::hw {

/// A window of cycles to record, and the instances to record it for.
struct TraceWindow {
  std::string path;         ///< output file (empty: none)
  uint64_t first = 0;       ///< first cycle
  uint64_t cycles = 2000;   ///< cycles in the window
  std::string scope;        ///< the instances kept, a TraceScope (hw/observe/trace_scope.h; empty: all)
};

class SampledFeed;

struct CycleRunOptions {
  const std::atomic<bool>* stop = nullptr;  ///< set (e.g. by SIGINT) to end the run early
  /// Called about every quarter second of wall time with the scheduler (e.g. a progress bar).
  std::function<void(const CycleEngine&)> progress;
  TraceWindow vcd;        ///< per-instance values at cycle resolution (VCD)
  TraceWindow timeline;   ///< busy intervals by instance (Chrome trace-event JSON)
  /// Interval statistics: one JSON line per hw.sim.interval_cycles cycles
  /// written here (empty: none; hw/observe/run_statistics.h).
  std::string interval_stats;
  bool track_parents = true;  ///< keep parent rays (FunctionalReplayer::set_track_parents)
  RayLocator locator;         ///< names a ray's line in errors the model finds (may be empty)
  RayTimesSink ray_times;     ///< every finished ray's cycles (may be empty)
  AcceleratorUnits units;     ///< replaced units (none by default)
  /// Prices hw.energy and hw.area (null: the shipped default, default_tech_path()).
  const TechFile* tech = nullptr;
  /// A sampled run (hw/sampling/sampled_replay.h sets it; null: every ray in
  /// detail): the rays come from it, not from the feed, and the results go to it.
  SampledFeed* sampled = nullptr;
};

struct CycleRunResult {
  ReplayStats stats;     ///< mode "cycle"; partial when stopped
  nlohmann::json hw;     ///< the `hw` section
  std::string table;     ///< the human table of `hw`
  HwCounters counters;
};

/// Replays the rays `feed` gives on `scene`/`bvh`. Throws std::invalid_argument
/// naming the field for a configuration the model cannot build, before any ray
/// is read, TraceScopeError (an std::invalid_argument) for a trace scope that
/// names no instance; std::runtime_error when the run stops making progress (a
/// report of the stuck slots) or loses a ray.
CycleRunResult run_cycle_replay(const RayFeed& feed, const Scene& scene, const Bvh& bvh, const ReplayOptions& opt,
                                const HwConfig& cfg, const RayResultSink& sink, const CycleRunOptions& options);

/// The same run with a closed-loop workload in place of a trace
/// (replay/closed_loop.h): `shader` is asked for rays and receives every
/// answer (after `sink`, which may be empty); the shader outlives the call.
/// The run ends when the shader answers Finished and every ray has finished;
/// a shader that answers Later with nothing in flight stops the run with the
/// report of a stuck run (std::runtime_error).
CycleRunResult run_cycle_closed_loop(RayShader& shader, const Scene& scene, const Bvh& bvh, const ReplayOptions& opt,
                                     const HwConfig& cfg, const RayResultSink& sink, const CycleRunOptions& options);

}  // namespace vbsim::hw
