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
// A min-heap of the cycles asked for (a cycle may be asked for more than once;
// take() drops them all); at most a few per MSHR are pending at once, so its
// storage, reserved up front, does not grow in a run.
#pragma once
#include <algorithm>
#include <cstdint>
#include <functional>
#include <vector>

#include "hw/pending_cycle.h"

namespace vbsim::hw {

class MemoryClock {
 public:
  explicit MemoryClock(size_t expected_pending = 64) { heap_.reserve(expected_pending); }

  /// The memory has work at `cycle` (later than the cycle being handled).
  void request(uint64_t cycle) {
    heap_.push_back(cycle);
    std::push_heap(heap_.begin(), heap_.end(), std::greater<uint64_t>());
    due_ = heap_.front();
  }
  /// The earliest cycle asked for, or kPendingCycle (one load: the scheduler asks before every event).
  uint64_t due() const { return due_; }
  /// Where due() is kept (the scheduler's event wheel fences on it).
  const uint64_t* due_address() const { return &due_; }
  /// Forgets every request at or before `cycle` (its work is being done).
  void take(uint64_t cycle) {
    while (!heap_.empty() && heap_.front() <= cycle) {
      std::pop_heap(heap_.begin(), heap_.end(), std::greater<uint64_t>());
      heap_.pop_back();
    }
    due_ = heap_.empty() ? kPendingCycle : heap_.front();
  }

 private:
  std::vector<uint64_t> heap_;
  uint64_t due_ = kPendingCycle;
};

}  // namespace vbsim::hw
