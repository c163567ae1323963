// MemoryClock: the cycles at which the memory modules have work that must be
// done in time order, not when the scheduler's event that found it runs: an L1
// miss that waits for an MSHR is looked up in the shared L2 at the cycle it
// leaves the L1 (so the L2 sees its lookups in time order), and a loosely
// timed L2 request leaves, and its line arrives, at their cycles (so the
// memory target sees its requests in time order). A module asks for a cycle
// (request); the scheduler (hw/scheduler/cycle_engine.h) runs the accelerator's memory
// step for each cycle asked for, before every event of that cycle, and the
// step does every module's work due then, in a fixed order (docs/memory-model.md).
//
// The cycles asked for wait in a calendar queue (hw/memory/timed_queue.h; a
// cycle may be asked for more than once; take() drops them all): a constant
// cost per request, and no allocation once it has grown to the most cycles
// pending at once (a few per MSHR).
#pragma once
#include <cstdint>

#include "hw/memory/timed_queue.h"
#include "hw/pending_cycle.h"

namespace vbsim::hw {

class MemoryClock {
 public:
  /// The memory has work at `cycle` (later than the cycle being handled).
  void request(uint64_t cycle) {
    cycles_.push(cycle, Asked{});
    due_ = cycles_.earliest();
  }
  /// The earliest cycle asked for, or kPendingCycle (one load: the scheduler asks before every event).
  uint64_t due() const { return due_; }
  /// Where due() is kept (the scheduler's event wheel fences on it).
  const uint64_t* due_address() const { return &due_; }
  /// Forgets every request at or before `cycle` (its work is being done).
  void take(uint64_t cycle) {
    uint64_t at;
    Asked asked;
    while (cycles_.pop_due(cycle, at, asked)) {
    }
    due_ = cycles_.earliest();
  }

 private:
  struct Asked {};
  TimedQueue<Asked> cycles_;
  uint64_t due_ = kPendingCycle;
};

}  // namespace vbsim::hw
