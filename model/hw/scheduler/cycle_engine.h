// Part contract (hw/scheduler/): the one scheduler that keeps the
// accelerator's time (the Accelerator's SC_METHOD drives it). It may call every
// part: the source (hw/source/) for rays, a core's units (hw/core/) and memory
// port (hw/memory/) for a slot's steps, the sink (hw/sink/) for finished rays,
// and the recorders (hw/observe/). Only the Accelerator (hw/accelerator.h)
// calls it, and the memory answers it (resume) for reads it answered late.
//
// CycleEngine: the one scheduler that keeps the accelerator's time. It owns the
// calendar queue of pending events (a busy slot's next step, the ray source)
// and the slots' ray records and BvhSteppers, and handles events in cycle order
// (within a cycle in scheduling order), running each slot's BvhStepper, whose
// units policy asks the accelerator's unit modules (hw/accelerator.h) for the
// answers and their schedule: inlined datapath calls and the built-in modules'
// reservation tables when every unit and memory is built-in (BuiltinUnits),
// the units' interfaces otherwise (PortUnits, hw/scheduler/port_units.h). It never visits an idle cycle. The Accelerator's
// SC_METHOD drives it (advance) and keeps SystemC time in step.
//
// Steps of a slot (docs/hw-model.md has their timing): the root box at
// dispatch, a node (read it, test every child box), a leaf (read its
// triangles, test each, send suspects to the avoidance unit), a stack refill,
// and done (the result sink). A read whose data come later (approximately timed
// memory) parks the slot until resume().
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hw/hw_config.h"
#include "hw/hw_counters.h"
#include "hw/memory/memory_clock.h"
#include "hw/observe/timeline_recorder.h"
#include "hw/observe/vcd_recorder.h"
#include "hw/source/ray_feed.h"
#include "hw/unit_interfaces.h"
#include "replay/functional_replayer.h"
#include "scene/bvh.h"

namespace vbsim::hw {

class AvoidanceUnit;
class BoxUnit;
class Dispatcher;
class IdealMemory;
class TriangleTester;
class RaySource;
class RaySourceIf;
class RayTestCore;
class ResultSink;
class SampledFeed;

class CycleEngine {
 public:
  virtual ~CycleEngine() = default;
  /// The source starts emitting the first ray at cycle 0 (once, before advance).
  virtual void start() = 0;
  /// Handles every event before cycle `limit`, which may be lowered while it
  /// runs (an approximately timed request bounds how far ahead it may go).
  virtual void advance(const uint64_t& limit) = 0;
  /// The cycle of the last event handled.
  virtual uint64_t last_handled() const = 0;
  /// True when no event and no memory step is pending (or the run was
  /// stopped). Rays may still wait for memory (waiting_for_memory()).
  virtual bool finished() const = 0;
  /// True when every ray the source read has finished and the trace has ended.
  virtual bool complete() const = 0;
  /// Cycle of the next event or memory step; meaningful when !finished().
  virtual uint64_t next_event_cycle() const = 0;
  /// Ends the run at the next advance: rays in flight are dropped.
  virtual void stop() = 0;
  virtual bool stopped() const = 0;
  /// Rays currently in slots; rays finished; rays the source has read from the trace.
  virtual uint64_t rays_in_flight() const = 0;
  virtual uint64_t rays_done() const = 0;
  virtual uint64_t rays_fed() const = 0;
  /// Slots parked on a read whose data are not known yet.
  virtual uint64_t waiting_for_memory() const = 0;
  /// The pending read of slot `slot` has its data at `ready` (>= the cycle being handled).
  virtual void resume(uint32_t slot, uint64_t ready) = 0;
  /// Sampled simulation (hw/sampling/sampled_feed.h): takes the rays
  /// `feed.next_fast_forward` gives, each through the functional datapath
  /// (emission, the search a slot's BvhStepper makes, conclusion) with no
  /// simulated time, the reads of its traversal warming its core's caches'
  /// tags (cores taken round-robin; feed.warm()), and reports each to
  /// `feed.fast_forwarded`. One call per run of fast-forwarded rays.
  virtual void fast_forward(SampledFeed& feed) = 0;
  /// Every busy slot's state, for the report of a run that stopped making progress.
  virtual std::string slot_report(size_t max_slots) const = 0;
};

/// A core as the scheduler reaches it: its module and, per unit, the built-in
/// module (called directly) or the interface a replacement implements.
struct CoreBinding {
  RayTestCore* core;
  BoxUnit* box_builtin;
  BoxUnitIf* box;
  BoxUnit* box_low;  ///< the low-precision box pool (always built-in), or null without one
  TriangleTester* triangle_builtin;
  TriangleTesterIf* triangle;
  AvoidanceUnit* avoidance_builtin;
  AvoidanceUnitIf* avoidance;
  MemoryReadIf* memory;
};

/// What the scheduler runs: every unit of one accelerator.
struct EngineParts {
  const HwConfig& config;
  FunctionalReplayer& replayer;
  const Bvh& bvh;
  RaySourceIf& source;     ///< the ray source (the built-in RaySource or a replacement)
  DispatchIf& dispatcher;
  Dispatcher* builtin_dispatcher;  ///< `dispatcher` when it is the built-in one (called directly), else null
  ResultSink& sink;        ///< the built-in result sink (called directly)
  std::vector<CoreBinding> cores;
  /// All cores' memory ports reach the built-in L1s / one built-in ideal memory
  /// (then reads are direct calls); otherwise through MemoryReadIf.
  bool builtin_l1s = false;
  IdealMemory* builtin_ideal = nullptr;
  bool avoidance_in_use = false;  ///< validity-bit with a policy that tests suspects
  TimelineRecorder* timeline = nullptr;
  VcdRecorder* vcd = nullptr;
  RayTimesSink ray_times;  ///< every finished ray's cycles (may be empty)
  /// The memory's work in time order (may be null): `memory_step(c)` runs for
  /// every cycle c the clock was asked for, before the events of cycle c.
  MemoryClock* memory_clock = nullptr;
  std::function<void(uint64_t)> memory_step;
  /// Statistics samples (null: none): `on_sample(c, interval, warmup)` runs
  /// once every event before cycle c is handled and none of cycle c is: at
  /// every multiple c > 0 of `sample_interval` (0: none) with interval = true,
  /// and once at the warm-up's end with warmup = true, the cycle
  /// `warmup_cycle` or, with `warmup_rays` set, the cycle after the one the
  /// warmup_rays-th ray finished (0 rays: cycle 0). kNoWarmup: none.
  static constexpr uint64_t kNoWarmup = ~uint64_t{0};
  std::function<void(uint64_t cycle, bool interval, bool warmup)> on_sample;
  uint64_t sample_interval = 0;
  uint64_t warmup_cycle = kNoWarmup, warmup_rays = kNoWarmup;
};

/// The scheduler for `parts` (which outlive it). Throws std::runtime_error when
/// the BVH is deeper than the traversal stack or the slots are too many.
std::unique_ptr<CycleEngine> make_cycle_engine(const EngineParts& parts);

}  // namespace vbsim::hw
