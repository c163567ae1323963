// CycleEngine: the cycle-level model of the accelerator as plain C++ state,
// advanced event by event (no per-cycle tick: time jumps to the next step that
// completes). A SystemC process drives it (hw/systemc_driver.h); tests may too.
//
// Modules (docs/hw-model.md has their timing):
//   ray source   reads trace rays through the ray-emission step (FunctionalReplayer::emit),
//                charging issue_interval + sign-bit and emission-op cycles per ray
//   dispatcher   hands the emitted ray to a free slot (round-robin or least-loaded)
//   cores        R slots each, a BvhStepper per slot; box, triangle and avoidance
//                pipelines (UnitPipelines); fetches through the MemoryPort at the
//                addresses of BvhAddressMap
//   result sink  FunctionalReplayer::conclude (verdict, statistics), per-ray latency
// The hits are those of the functional replay: the steps are the datapath's.
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>

#include "hw/hw_config.h"
#include "hw/hw_counters.h"
#include "hw/memory_port.h"
#include "replay/functional_replayer.h"
#include "scene/bvh.h"

namespace vbsim::hw {

/// Gives the next trace ray; false at the end of the trace.
using RayFeed = std::function<bool(TraceRay&)>;
/// Receives every finished ray, in completion order (may be empty);
/// `trace_index` is the ray's position in the feed (0 for the first ray).
using RayResultSink =
    std::function<void(const TraceRay&, const RayOutcome&, uint64_t finish_cycle, uint64_t trace_index)>;

/// One busy interval of a unit or slot, for the timeline (see set_timeline_window).
struct TimelineEvent {
  const char* name;  ///< "node", "leaf", "refill", "box", "triangle", "avoidance"
  uint32_t core, slot;  ///< slot: the slot index within its core
  uint64_t start, end;
  int64_t ray_id;
};

class CycleEngine {
 public:
  virtual ~CycleEngine() = default;
  /// Processes every event before cycle `limit`.
  virtual void advance(uint64_t limit) = 0;
  /// True when every ray has finished (or the run was stopped).
  virtual bool finished() const = 0;
  /// Cycle of the next event; meaningful when !finished().
  virtual uint64_t next_event_cycle() const = 0;
  /// Ends the run at the next advance: rays in flight are dropped.
  virtual void stop() = 0;
  virtual bool stopped() const = 0;
  virtual const HwCounters& counters() const = 0;
  /// Rays currently in slots.
  virtual uint64_t rays_in_flight() const = 0;
  /// Records busy intervals that start in [first, first + cycles) into `out` (null: none).
  virtual void set_timeline_window(uint64_t first, uint64_t cycles, std::vector<TimelineEvent>* out) = 0;
};

/// The engine for `cfg`. `replayer` does emission, the filter, verdicts and the
/// per-kind statistics; `bvh` must be the replayer's; all must outlive the engine.
/// Throws std::runtime_error when the BVH is deeper than the traversal stack.
std::unique_ptr<CycleEngine> make_cycle_engine(const HwConfig& cfg, FunctionalReplayer& replayer, const Bvh& bvh,
                                               MemoryPort& memory, RayFeed feed, RayResultSink sink);

}  // namespace vbsim::hw
