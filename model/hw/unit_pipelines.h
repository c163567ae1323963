// UnitPipelines: the `count` identical pipelines of one kind in one core (box
// tests, triangle tests or the avoidance unit), as a reservation table: a
// request ready at cycle r issues at the earliest cycle >= r at which one of
// the pipelines accepts a new operation (issue_interval after its last issue)
// and has its result `latency` cycles later. Requests are served in the order
// they are made; the engine makes them in time order of the steps that need them.
#pragma once
#include <cstdint>
#include <vector>

#include "hw/hw_config.h"

namespace vbsim::hw {

class UnitPipelines {
 public:
  explicit UnitPipelines(const UnitConfig& c) : next_free_(c.count, 0), latency_(c.latency), interval_(c.issue_interval) {}

  /// Issue cycle of an operation whose operands are ready at `ready`.
  uint64_t issue(uint64_t ready) {
    size_t best = 0;
    for (size_t p = 1; p < next_free_.size(); ++p)
      if (next_free_[p] < next_free_[best]) best = p;
    const uint64_t at = ready > next_free_[best] ? ready : next_free_[best];
    next_free_[best] = at + interval_;
    ++ops_;
    wait_cycles_ += at - ready;
    return at;
  }
  uint32_t latency() const { return latency_; }
  uint64_t ops() const { return ops_; }
  uint64_t wait_cycles() const { return wait_cycles_; }  ///< cycles operations waited for a free pipeline

 private:
  std::vector<uint64_t> next_free_;
  uint32_t latency_, interval_;
  uint64_t ops_ = 0, wait_cycles_ = 0;
};

}  // namespace vbsim::hw
