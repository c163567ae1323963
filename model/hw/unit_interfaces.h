// The interfaces between the accelerator's units (docs/hw-model.md, "Modules").
// Every unit is an sc_module reached through one of these, bound at elaboration
// (sc_port<IF> to sc_export<IF>), so another module implementing the interface
// can be bound instead (AcceleratorUnits in hw/accelerator.h).
//
// Time is in cycles of the accelerator's clock, counted from the run's start.
// The scheduler (hw/accelerator.h) handles events in cycle order and calls the
// units while handling the event at cycle `now`; calls carry that `now`, which
// never decreases from one call to the next of one unit.
//
// What a unit decides is *when*: the answers (which triangle a ray hits, what
// the avoidance unit rejects) are the plain-C++ datapath's (BvhStepper with its
// tester and candidate filter), so a replaced unit changes timing, never hits.
#pragma once
#include <cstdint>

#include <systemc>

#include "hw/pending_cycle.h"
#include "replay/functional_replayer.h"
#include "replay/ray_emission.h"
#include "trace/trace_record.h"

namespace vbsim::hw {

/// When one operation of a pipelined unit issues and when its result is there.
struct UnitSchedule {
  uint64_t issue;  ///< cycle the operation enters a pipeline (>= its ready cycle)
  uint64_t done;   ///< cycle its result is available (>= issue)
};

/// A unit of a ray-test core that times one kind of operation: the box unit
/// (both child boxes of a node), the three-half-plane tester (one triangle,
/// front/back bit), the avoidance unit (one suspect's epsilon tests).
class PipelineIf : public virtual sc_core::sc_interface {
 public:
  /// An operation whose operands are ready at `ready` (>= now), requested while
  /// handling the event at `now`.
  virtual UnitSchedule schedule(uint64_t ready, uint64_t now) = 0;
};

/// A core's reads of the BVH (nodes, triangles, its slots' stack spill areas),
/// answered by its L1 cache or by an ideal memory.
class MemoryReadIf : public virtual sc_core::sc_interface {
 public:
  /// A read of `bytes` at byte address `addr` issued at cycle `now` for slot
  /// `slot` (the core's index of it): the cycle its data are there (>= now + 1),
  /// or kPendingCycle, and then the memory calls ReadDoneIf::read_done(slot,
  /// cycle) of the same core later (approximately timed memory only).
  virtual uint64_t read(uint64_t addr, uint32_t bytes, uint64_t now, uint32_t slot) = 0;
};

/// The core's side of a pending read.
class ReadDoneIf : public virtual sc_core::sc_interface {
 public:
  /// The read of slot `slot` that was answered kPendingCycle has its data at
  /// `ready` (not before the cycle being handled).
  virtual void read_done(uint32_t slot, uint64_t ready) = 0;
};

/// An L1's misses, to the shared L2: one cache line each.
class LineReadIf : public virtual sc_core::sc_interface {
 public:
  /// Line `line` (byte address / line size) asked for at cycle `t` by the L1 of
  /// core `core`: the cycle it arrives there, or kPendingCycle, and then the L2
  /// calls LineFillIf::line_filled(line, cycle) of that core's L1 later.
  virtual uint64_t read_line(uint64_t line, uint64_t t, uint32_t core) = 0;
};

/// The L1's side of a pending line.
class LineFillIf : public virtual sc_core::sc_interface {
 public:
  virtual void line_filled(uint64_t line, uint64_t fill) = 0;
};

/// The dispatcher: which core takes the next ray.
class DispatchIf : public virtual sc_core::sc_interface {
 public:
  /// `free_slots[c]` is core c's number of free slots; the chosen core (which
  /// has one), or -1 when every core is full.
  virtual int pick(const uint32_t* free_slots, uint32_t cores) = 0;
};

/// The result sink: where finished rays go (verdicts, statistics, hits file).
class ResultSinkIf : public virtual sc_core::sc_interface {
 public:
  /// Ray `tr` (emitted as `er`, trace position `trace_index`), dispatched at
  /// `dispatched`, finished at `now` with `hit` and `rejected` rejected candidates.
  virtual void ray_done(const TraceRay& tr, const EmittedRay& er, const Hit& hit, uint64_t rejected,
                        uint64_t dispatched, uint64_t now, uint64_t trace_index) = 0;
};

}  // namespace vbsim::hw
