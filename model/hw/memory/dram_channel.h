// DRAM behind the shared L2: one channel of `bytes_per_cycle` bandwidth, an
// unloaded latency and a limit on requests in flight.
//
// A line request arriving at cycle t:
//  1. takes the request slot that frees first (max_outstanding slots); it
//     starts at s = max(t, that slot's free cycle)  -> dram_outstanding_full stall;
//  2. its transfer occupies the channel for line_bytes / bytes_per_cycle
//     cycles; transfers are served in arrival order, the first free at
//     q = max(s, end of the previous transfer);
//  3. its data arrive at s + latency + (ceil(q + x) - ceil(s + x)), x the
//     transfer time: the unloaded latency plus how much later, in whole
//     cycles, its transfer ends than it would on an idle channel (that
//     difference is its dram_bandwidth stall); the slot frees then.
// So the unloaded latency holds when the channel is idle, and back-to-back
// requests arrive spaced by the transfer time (on average, when it is
// fractional: 64-byte lines at 24 bytes per cycle arrive 3, 2, 3, 3, 2, 3 ...
// cycles apart, 8 cycles per 3 lines). Channel time is counted in
// ticks, cycles and transfers both being whole numbers of ticks: the ratio
// bytes_per_cycle / line_bytes is taken as the nearest fraction with terms up
// to 2^20, exact for every decimal setting a configuration is likely to use.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hw/memory/free_cycle_ring.h"

namespace vbsim::hw {

struct DramCounters {
  uint64_t reads = 0, bytes = 0;
  uint64_t outstanding_stall_cycles = 0, bandwidth_stall_cycles = 0;
};

class DramChannel {
 public:
  /// Valid parameters (make_memory checks them): latency >= 1,
  /// bytes_per_cycle > 0, max_outstanding >= 1.
  DramChannel(uint32_t latency, double bytes_per_cycle, uint32_t line_bytes, uint32_t max_outstanding);

  /// The cycle a line requested at `t` arrives.
  uint64_t read_line(uint64_t t);

  uint64_t ticks_per_cycle() const { return ticks_per_cycle_; }
  uint64_t ticks_per_transfer() const { return ticks_per_transfer_; }
  /// Cycles the channel spent transferring.
  double busy_cycles() const {
    return static_cast<double>(counters_.reads * ticks_per_transfer_) / static_cast<double>(ticks_per_cycle_);
  }
  const DramCounters& counters() const { return counters_; }

 private:
  uint32_t latency_, line_bytes_;
  uint64_t ticks_per_cycle_, ticks_per_transfer_;
  uint64_t channel_free_ = 0;      // tick the channel finishes its last transfer
  FreeCycleRing slots_;  // every request slot's free cycle
  DramCounters counters_;
};

}  // namespace vbsim::hw
