#include "hw/memory/cache_level.h"

namespace vbsim::hw {

CacheLevel::CacheLevel(const CacheConfig& config)
    : tags_(config.size_bytes / (config.ways * config.line_bytes), config.ways),
      hit_latency_(config.hit_latency),
      mshrs_(config.mshrs),
      merge_(config.merge_misses) {
  uint32_t bits = 0;
  while ((uint64_t{1} << bits) < config.mshrs) ++bits;
  ring_.assign(size_t{1} << bits, 0);  // every MSHR free from cycle 0
  ring_mask_ = (uint32_t{1} << bits) - 1;
}

void CacheLevel::resolve(uint64_t line, uint64_t fill) {
  if (merge_ || tags_.fill_of(line) == kPendingCycle) tags_.set_fill(line, fill);
  // Unknown fills sort last: the first of them takes `fill` and moves to its place.
  if (pending_ == 0) return;  // no MSHR waits for an unknown fill (not a valid call)
  uint32_t k = mshrs_ - pending_--;
  for (; k > 0 && ring_at(k - 1) > fill; --k) ring_at(k) = ring_at(k - 1);
  ring_at(k) = fill;
}

}  // namespace vbsim::hw
