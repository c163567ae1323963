// One cache of the hierarchy in time: an LRU tag array, its hit latency and
// its miss-status holding registers (MSHRs), each holding one line in flight.
//
// Time rules (see docs/memory-model.md):
//  - A miss takes the MSHR that frees first; it starts at the later of its
//    arrival and that MSHR's free cycle (the wait is an MSHR-full stall).
//  - A line in flight is not in the tag array. A lookup of it at a cycle
//    before its fill merges (ready at the fill cycle); at or after its fill it
//    hits. The fill is installed in the tag array (evicting the LRU line) by
//    `retire` once the caller's time horizon passes the fill cycle, fills in
//    fill order, or when its MSHR is taken by a later miss, whichever is first.
#pragma once
#include <cstdint>
#include <vector>

#include "hw/lru_cache.h"
#include "hw/memory_port.h"

namespace vbsim::hw {

struct LevelCounters {
  uint64_t accesses = 0, hits = 0, misses = 0, merges = 0;
  uint64_t mshr_stall_cycles = 0;  ///< summed over misses: cycles waited for a free MSHR
};

class CacheLevel {
 public:
  enum class Outcome { Hit, Merge, Miss };
  struct Lookup {
    Outcome outcome;
    uint64_t ready;  ///< Hit: t + hit latency; Merge: the fill cycle; Miss: unused
  };
  struct MissStart {
    uint32_t mshr;   ///< the MSHR the miss holds
    uint64_t start;  ///< cycle the miss leaves this level (>= arrival)
  };

  /// `config` is valid (make_memory checks it).
  explicit CacheLevel(const CacheConfig& config);

  /// Installs every fill at or before `horizon`, in fill order. The caller
  /// promises that no later lookup or miss arrives before `horizon`.
  void retire(uint64_t horizon) {
    if (horizon >= next_fill_) retire_slow(horizon);
  }
  /// A request for `line` arriving at cycle `t` (counted).
  Lookup lookup(uint64_t line, uint64_t t);
  /// The MSHR a miss arriving at `t` takes and when it can start.
  MissStart start_miss(uint64_t t);
  /// Records the miss of `line` on MSHR `mshr`, its data filling at `fill`.
  void hold(uint32_t mshr, uint64_t line, uint64_t fill);

  uint32_t hit_latency() const { return hit_latency_; }
  const LevelCounters& counters() const { return counters_; }
  const LruCache& tags() const { return tags_; }

 private:
  struct Mshr {
    uint64_t line = LruCache::kNoLine;
    uint64_t fill = 0;     // the cycle this MSHR frees (its line's fill cycle)
    uint64_t order = 0;    // claim order: breaks ties between equal fill cycles
    bool in_flight = false;  // line not yet installed in the tag array
  };
  void retire_slow(uint64_t horizon);

  LruCache tags_;
  uint32_t hit_latency_;
  std::vector<Mshr> mshrs_;
  uint64_t claims_ = 0;
  uint64_t next_fill_ = ~uint64_t{0};  // earliest fill among MSHRs in flight
  LevelCounters counters_;
};

}  // namespace vbsim::hw
