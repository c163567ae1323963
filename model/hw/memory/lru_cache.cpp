#include "hw/memory/lru_cache.h"

namespace vbsim::hw {

LruCache::LruCache(uint32_t sets, uint32_t ways)
    : sets_(sets),
      ways_(ways),
      sets_pow2_((sets & (sets - 1)) == 0),
      set_mask_(sets - 1),
      storage_(static_cast<size_t>(sets) * set_stride(ways) / kWaysPerHostLine * sizeof(HostLine)) {
  static_assert(sizeof(HostLine) == 64 && sizeof(Way) == 16, "a set starts on a 64-byte host line");
}

uint64_t LruCache::install_past_flight(Way* set, uint32_t ways, uint64_t line, uint64_t fill, uint64_t now) {
  uint32_t victim = ways - 1;
  while (victim > 0 && set[victim].fill > now) --victim;  // the least recent way not in flight
  if (set[victim].fill > now) victim = ways - 1;          // every way is in flight: the least recent
  const uint64_t replaced = set[victim].line();
  for (uint32_t i = victim; i > 0; --i) set[i] = set[i - 1];  // the ways before it one place down
  set[0] = {~line, fill};
  return replaced;
}

}  // namespace vbsim::hw
