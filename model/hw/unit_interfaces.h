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
// When, in SystemC time: the scheduler runs loosely timed, a quantum of
// Q = sim.quantum_cycles cycles at a time. An activation at SystemC time T
// (cycle c = (T - start) / clock period) handles the events of cycles
// [c, c + Q) and sleeps until the next, so a call carrying `now` happens while
// sc_time_stamp() is at cycle c with
//
//     0 <= now - c < Q        i.e. c in [now - Q + 1, now]
//
// (a unit may be asked up to Q - 1 cycles ahead of SystemC time, never behind
// it; Q = 1 keeps every call at its own cycle). With an approximately timed
// memory and requests outstanding the bound is tighter (the target's
// lookahead). Results never depend on Q; a unit that reads SystemC time or
// other modules' signals must allow for it (testbench/module/unit_payload_test.cpp
// records sc_time_stamp() in a unit's calls and checks the bound).
//
// What a unit decides is *when* and *what*: the box unit, the triangle tester
// and the avoidance unit each take an operation carrying its payload (the
// ray, the node or triangle, the candidate: hw/unit_operations.h) and answer
// its schedule with its result, which the slot's BvhStepper acts on (which
// child to descend into, whether a candidate hit shortens the interval). The
// built-in modules (hw/pipeline_units.h) compute the result with the plain-C++
// datapath (RayBoxTester, the configured triangle tester, avoidance_decide),
// so with them functional and cycle-level runs give identical hits; a
// replacement that computes otherwise (hw/examples/reduced_precision_units.h)
// changes them.
#pragma once
#include <cstdint>

#include <systemc>

#include "hw/pending_cycle.h"
#include "hw/unit_operations.h"
#include "replay/functional_replayer.h"
#include "replay/ray_emission.h"
#include "trace/trace_record.h"

namespace vbsim::hw {

/// The box unit: the root's box of a ray at dispatch, then every child box (2,
/// 4 or 8: bvh.width) of each node the ray's slot fetches.
class BoxUnitIf : public virtual sc_core::sc_interface {
 public:
  virtual BoxAnswer test_boxes(const BoxOp& op) = 0;
};

/// The triangle tester: one triangle per operation, with the front/back bit.
class TriangleTesterIf : public virtual sc_core::sc_interface {
 public:
  virtual TriangleAnswer test_triangle(const TriangleOp& op) = 0;
};

/// The intersection-avoidance unit: one suspect candidate per operation
/// (asked only when the method is validity-bit with a policy that tests;
/// policy sign-only rejects every suspect on the bit alone, without the unit).
class AvoidanceUnitIf : public virtual sc_core::sc_interface {
 public:
  virtual AvoidanceAnswer decide(const AvoidanceOp& op) = 0;
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

/// What a replacement L1 (AcceleratorUnits::l1_cache) implements besides
/// MemoryReadIf to be wired as the built-in L1 is: with the cache hierarchy,
/// the accelerator binds next_level() to the shared L2's LineReadIf (misses go
/// on to the L2) and gives the L2 fill_target() for the lines it answers
/// kPendingCycle; the core binds read_done() to its ReadDoneIf (the answers to
/// the core's reads the replacement answered kPendingCycle). With an ideal
/// memory there is no L2 and next_level() stays unbound (declare it
/// sc_port<LineReadIf, 1, SC_ZERO_OR_MORE_BOUND> to allow that). A replacement
/// without it is the core's whole memory path (it does not reach the L2).
class L2ClientIf {
 public:
  virtual ~L2ClientIf() = default;
  virtual sc_core::sc_port_b<LineReadIf>& next_level() = 0;
  virtual LineFillIf& fill_target() = 0;
  virtual sc_core::sc_port_b<ReadDoneIf>& read_done() = 0;
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
