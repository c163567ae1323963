#include "hw/memory/cache_level.h"

namespace vbsim::hw {

CacheLevel::CacheLevel(const CacheConfig& config)
    : tags_(config.size_bytes / (config.ways * config.line_bytes), config.ways),
      hit_latency_(config.hit_latency),
      merge_(config.merge_misses),
      mshrs_(config.mshrs) {}

void CacheLevel::resolve(uint64_t line, uint64_t fill) {
  if (merge_ || tags_.fill_of(line) == kPendingCycle) tags_.set_fill(line, fill);
  // Unknown fills sort last: the first of them takes `fill` and moves to its place.
  if (pending_ == 0) return;  // no MSHR waits for an unknown fill (not a valid call)
  mshrs_.lower(mshrs_.size() - pending_--, fill);
}

}  // namespace vbsim::hw
