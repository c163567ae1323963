// DRAM behind the shared L2: one channel of `bytes_per_cycle` bandwidth, an
// unloaded latency and a limit on requests in flight.
//
// A line request arriving at cycle t:
//  1. takes the request slot that frees first (max_outstanding slots); it
//     starts at s = max(t, that slot's free cycle)  -> dram_outstanding_full stall;
//  2. its transfer occupies the channel for line_bytes / bytes_per_cycle
//     cycles; transfers are served in arrival order, the first free at
//     q = max(s, end of the previous transfer)        -> dram_bandwidth stall q - s;
//  3. its data arrive at s + ceil(q - s) + latency; the slot frees then.
// So the unloaded latency holds when the channel is idle, and back-to-back
// requests arrive spaced by the transfer time. Channel time is kept in
// fixed point (1/65536 cycle), so fractional transfer times stay exact and
// deterministic.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vbsim::hw {

struct DramCounters {
  uint64_t reads = 0, bytes = 0;
  uint64_t busy_ticks = 0;  ///< channel occupancy in 1/65536 cycles
  uint64_t outstanding_stall_cycles = 0, bandwidth_stall_cycles = 0;
  uint64_t first_request = 0, last_ready = 0;  ///< valid when reads > 0
};

class DramChannel {
 public:
  static constexpr uint64_t kTicksPerCycle = 65536;

  /// Valid parameters (make_memory checks them): latency >= 1,
  /// bytes_per_cycle > 0, max_outstanding >= 1.
  DramChannel(uint32_t latency, double bytes_per_cycle, uint32_t line_bytes, uint32_t max_outstanding);

  /// The cycle a line requested at `t` arrives.
  uint64_t read_line(uint64_t t);

  uint64_t transfer_ticks() const { return transfer_ticks_; }
  const DramCounters& counters() const { return counters_; }

 private:
  uint32_t latency_, line_bytes_;
  uint64_t transfer_ticks_;        // channel occupancy of one line
  uint64_t channel_free_ = 0;      // tick the channel finishes its last transfer
  std::vector<uint64_t> slot_free_;  // per request slot: cycle it frees
  DramCounters counters_;
};

}  // namespace vbsim::hw
