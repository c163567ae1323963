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
// ray, the node or triangle, the candidate: hw/core/unit_operations.h) and answer
// its schedule with its result, which the slot's BvhStepper acts on (which
// child to descend into, whether a candidate hit shortens the interval). The
// built-in modules (hw/core/pipeline_units.h) compute the result with the plain-C++
// datapath (RayBoxTester, the configured triangle tester, avoidance_decide),
// so with them functional and cycle-level runs give identical hits; a
// replacement that computes otherwise (testbench/examples/reduced_precision/reduced_precision_units.h)
// changes them.
#pragma once
#include <cstdint>

#include <systemc>

#include "hw/core/unit_operations.h"
#include "hw/memory/memory_interfaces.h"
#include "hw/pending_cycle.h"
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
