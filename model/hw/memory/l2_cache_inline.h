// L2Cache::read_line_inline: the L2's lookup of one line, inlined into the
// built-in L1's reads (hw/memory/l1_cache.cpp) and into L2Cache::read_line.
#pragma once
#include "hw/memory/l2_cache.h"

namespace vbsim::hw {

template <uint32_t Ways>
__attribute__((always_inline)) inline uint64_t L2Cache::read_line_inline(uint64_t line, uint64_t t, uint32_t core) {
  const CacheLevel::Access a = level_.access<Ways>(line, t);
  if (a.outcome != CacheLevel::Outcome::Miss) {
    if (__builtin_expect(a.ready == kPendingCycle, 0)) wait_for(line, core, t);  // a merge with a pending miss
    return a.ready;
  }
  if (__builtin_expect(a.start == kPendingCycle, 0)) {  // every MSHR waits for a fill not known yet
    level_.uncount_pending_wait(t);
    if (!a.allocated) level_.install<Ways>(line, kPendingCycle, t);
    defer_miss(line, core, t);
    return kPendingCycle;
  }
  const uint64_t fill = dram_read(line, a.start + level_.hit_latency());
  if (__builtin_expect(a.allocated, 0)) level_.hold_mshr(fill);  // merging off: the line is there, in flight
  else level_.fill<Ways>(line, fill, a.start);
  if (__builtin_expect(fill == kPendingCycle, 0)) wait_for(line, core, t);
  return fill;
}

}  // namespace vbsim::hw
