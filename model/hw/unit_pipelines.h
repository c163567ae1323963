// UnitPipelines: the `count` identical pipelines of one kind in one core (box
// tests, triangle tests or the avoidance unit), as a reservation table: a
// request ready at cycle r issues at the earliest cycle >= r at which one of
// the pipelines accepts a new operation (issue_interval after its last issue)
// and has its result `latency` cycles later. Requests are served in the order
// they are made; the engine makes them in time order of the steps that need them.
// Operations and their waits are added to a UnitCounters the caller owns (the
// engine sums every core's pipelines of one kind into one).
#pragma once
#include <cstdint>
#include <vector>

#include "hw/hw_config.h"
#include "hw/hw_counters.h"

namespace vbsim::hw {

class UnitPipelines {
 public:
  /// `totals` must outlive the pipelines.
  UnitPipelines(const UnitConfig& c, UnitCounters& totals)
      : next_free_(c.count, 0), latency_(c.latency), interval_(c.issue_interval), totals_(&totals) {}

  /// Issue cycle of an operation whose operands are ready at `ready`.
  uint64_t issue(uint64_t ready) {
    size_t best = 0;
    for (size_t p = 1; p < next_free_.size(); ++p)
      if (next_free_[p] < next_free_[best]) best = p;
    const uint64_t at = ready > next_free_[best] ? ready : next_free_[best];
    next_free_[best] = at + interval_;
    ++totals_->ops;
    totals_->wait_cycles += at - ready;
    return at;
  }
  uint32_t latency() const { return latency_; }

 private:
  std::vector<uint64_t> next_free_;
  uint32_t latency_, interval_;
  UnitCounters* totals_;
};

}  // namespace vbsim::hw
