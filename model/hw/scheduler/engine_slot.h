// EngineSlot: one ray slot of a ray-test core as the scheduler keeps it: the
// ray in it (as the trace gave it and as it was emitted), its traversal
// (BvhStepper, with its on-chip stack), its pending step and the cycles the
// per-ray log reports. The scheduler (hw/scheduler/engine.h) owns every
// core's slots in one array, indexed by slot id.
#pragma once
#include <cstddef>
#include <cstdint>

#include "datapath/bvh_stepper.h"
#include "datapath/candidate_filter.h"
#include "replay/ray_emission.h"
#include "scene/bvh.h"
#include "trace/trace_record.h"

namespace vbsim::hw::engine_detail {

// 64-byte aligned: a step's first host cache line holds the slot's core and
// request and the stepper's scalars.
template <class Tester>
struct alignas(64) EngineSlot {
  EngineSlot(const Bvh& bvh, const CandidateFilter& filter, int depth, uint32_t core_index)
      : core(core_index), stepper(bvh, filter, depth) {}
  uint32_t core;  ///< the core holding this slot
  StepRequest pending;
  BvhStepper<Tester> stepper;  // its traversal stack at its end
  uint64_t dispatched = 0;
  uint64_t trace_index = 0;  ///< the ray's position in the feed
  TraceRay tr;
  EmittedRay er;
  bool parked = false;       ///< its read's data are not known yet (resume() continues it)
  bool resumed = false;      ///< parked, and resume() has scheduled its continuation
  uint64_t requested = 0;    ///< parked: the cycle its read was issued
  uint64_t ready = 0, emitted = 0;  ///< when the ray was ready for emission and its emission started
  uint64_t entered = 0;             ///< when it entered the source's buffer
  /// Per-triangle fetch (hw.triangle_fetch "triangle"): the leaf's next triangle to read.
  uint32_t leaf_next = 0;
  /// Bytes from the slot's start that a node step reads: the header (core,
  /// request) and the stepper up to its box tester (3 host lines). Leaf steps
  /// read further; prefetching those lines for every step cost more than it
  /// saved (docs/results/speed.md, round 9).
  static constexpr size_t kNodeStepBytes = 16 + BvhStepper<Tester>::node_step_host_bytes();

  /// Asks the host's caches for the part of the slot a node step uses.
  void prefetch() const {
    const char* p = reinterpret_cast<const char*>(this);
    for (size_t at = 0; at < kNodeStepBytes; at += 64) __builtin_prefetch(p + at);
  }
};

}  // namespace vbsim::hw::engine_detail
