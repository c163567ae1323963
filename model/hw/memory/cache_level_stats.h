// The statistics every cache module declares for its CacheLevel (the L1s and
// the L2 alike): lookups and their outcomes, MSHR waits, hit rate, and the
// misses sent late behind an approximately timed memory. `next` names where a
// miss goes ("the L2", "DRAM") in the descriptions.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "hw/memory/cache_level.h"
#include "hw/observe/stat_provider.h"

namespace vbsim::hw {

inline std::vector<StatDeclaration> cache_level_statistics(const CacheLevel& level, const std::string& next,
                                                           const uint64_t& misses_sent_late) {
  const CacheLevel* l = &level;
  const uint64_t* late = &misses_sent_late;
  return {
      {"accesses", "lines", "line lookups (every line a request spans)", [l] { return l->counters().accesses; }},
      {"hits", "lines", "lookups that found their line filled", [l] { return l->counters().hits; }},
      {"merges", "lines", "lookups that met their line's miss in flight and waited for its fill",
       [l] { return l->counters().merges; }},
      {"misses", "lines", "lookups sent on to " + next, [l] { return l->counters().misses; }},
      {"mshr_stall_cycles", "cycles", "cycles misses waited for a free MSHR",
       [l] { return l->counters().mshr_stall_cycles; }},
      {"misses_sent_late", "lines",
       "misses that waited for an MSHR whose fill was not yet known (approximately timed memory)",
       [late] { return nlohmann::json(*late); }},
      {"hit_rate", "ratio", "hits / accesses",
       [l] {
         const LevelCounters c = l->counters();
         return c.accesses ? static_cast<double>(c.hits) / static_cast<double>(c.accesses) : 0.0;
       }},
  };
}

/// log2 of a power of two (a line size).
inline uint32_t log2_of(uint32_t power_of_two) {
  uint32_t s = 0;
  while ((uint32_t{1} << s) < power_of_two) ++s;
  return s;
}

}  // namespace vbsim::hw
