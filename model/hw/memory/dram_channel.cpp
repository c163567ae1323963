#include "hw/memory/dram_channel.h"

#include <cmath>
#include <utility>

namespace vbsim::hw {

namespace {

constexpr uint64_t kMaxTerm = uint64_t{1} << 20;

// The fraction num/den nearest to x (> 0) among the convergents of its
// continued fraction with num, den <= 2^20; x = 0.375 gives 3/8.
std::pair<uint64_t, uint64_t> nearest_fraction(double x) {
  if (x >= static_cast<double>(kMaxTerm)) return {kMaxTerm, 1};
  uint64_t h0 = 0, h1 = 1, k0 = 1, k1 = 0;  // convergents h/k, previous and current
  double rest = x;
  for (int i = 0; i < 64; ++i) {
    const double whole = std::floor(rest);
    const uint64_t a = static_cast<uint64_t>(whole);
    const uint64_t h2 = a * h1 + h0, k2 = a * k1 + k0;
    if (h2 > kMaxTerm || k2 > kMaxTerm) break;
    h0 = h1, h1 = h2, k0 = k1, k1 = k2;
    const double frac = rest - whole;
    if (frac < 1e-12 || std::fabs(static_cast<double>(h1) / static_cast<double>(k1) - x) <= 1e-15 * x) break;
    rest = 1 / frac;
  }
  if (h1 == 0 || k1 == 0) return {1, kMaxTerm};
  return {h1, k1};
}

uint64_t ceil_div(uint64_t a, uint64_t b) { return (a + b - 1) / b; }

}  // namespace

DramChannel::DramChannel(uint32_t latency, double bytes_per_cycle, uint32_t line_bytes,
                         uint32_t max_outstanding)
    : latency_(latency), line_bytes_(line_bytes), slots_(max_outstanding) {
  // transfers per cycle = bytes_per_cycle / line_bytes = ticks_per_cycle / ticks_per_transfer
  const auto [num, den] = nearest_fraction(bytes_per_cycle / line_bytes);
  ticks_per_cycle_ = num;
  ticks_per_transfer_ = den;
}

uint64_t DramChannel::read_line(uint64_t t) {
  const uint64_t free_at = slots_.front();  // the slot that frees first
  const uint64_t start = free_at > t ? free_at : t;
  const uint64_t start_ticks = start * ticks_per_cycle_;
  const uint64_t transfer = channel_free_ > start_ticks ? channel_free_ : start_ticks;
  channel_free_ = transfer + ticks_per_transfer_;
  const uint64_t queued = ceil_div(channel_free_, ticks_per_cycle_) -
                          ceil_div(start_ticks + ticks_per_transfer_, ticks_per_cycle_);
  const uint64_t ready = start + latency_ + queued;
  slots_.take_front(ready);

  ++counters_.reads;
  counters_.bytes += line_bytes_;
  counters_.outstanding_stall_cycles += start - t;
  counters_.bandwidth_stall_cycles += queued;
  return ready;
}

}  // namespace vbsim::hw
