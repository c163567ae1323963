#include "hw/dram_channel.h"

#include <cmath>

namespace vbsim::hw {

DramChannel::DramChannel(uint32_t latency, double bytes_per_cycle, uint32_t line_bytes,
                         uint32_t max_outstanding)
    : latency_(latency),
      line_bytes_(line_bytes),
      transfer_ticks_(static_cast<uint64_t>(
          std::llround(static_cast<double>(line_bytes) * kTicksPerCycle / bytes_per_cycle))),
      slot_free_(max_outstanding, 0) {
  if (transfer_ticks_ == 0) transfer_ticks_ = 1;
}

uint64_t DramChannel::read_line(uint64_t t) {
  size_t slot = 0;
  for (size_t i = 1; i < slot_free_.size(); ++i)
    if (slot_free_[i] < slot_free_[slot]) slot = i;
  const uint64_t start = slot_free_[slot] > t ? slot_free_[slot] : t;
  const uint64_t start_ticks = start * kTicksPerCycle;
  const uint64_t transfer = channel_free_ > start_ticks ? channel_free_ : start_ticks;
  channel_free_ = transfer + transfer_ticks_;
  const uint64_t queued = (transfer - start_ticks + kTicksPerCycle - 1) / kTicksPerCycle;
  const uint64_t ready = start + queued + latency_;
  slot_free_[slot] = ready;

  if (counters_.reads == 0 || t < counters_.first_request) counters_.first_request = t;
  if (ready > counters_.last_ready) counters_.last_ready = ready;
  ++counters_.reads;
  counters_.bytes += line_bytes_;
  counters_.busy_ticks += transfer_ticks_;
  counters_.outstanding_stall_cycles += start - t;
  counters_.bandwidth_stall_cycles += queued;
  return ready;
}

}  // namespace vbsim::hw
