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
  /// What a request met. Hit: ready = t + hit latency. Merge: ready = the fill
  /// cycle of the miss in flight. Miss: the MSHR it takes (the first of the
  /// earliest free cycle) and the cycle it leaves this level (>= its arrival).
  struct Access {
    Outcome outcome;
    uint64_t ready;  ///< Hit, Merge
    uint32_t mshr;   ///< Miss
    uint64_t start;  ///< Miss
  };

  /// `config` is valid (make_memory checks it).
  explicit CacheLevel(const CacheConfig& config);

  /// Installs every fill at or before `horizon`, in fill order. The caller
  /// promises that no later lookup or miss arrives before `horizon`.
  void retire(uint64_t horizon) {
    if (horizon >= next_fill_) retire_slow(horizon);
  }
  /// A request for `line` arriving at cycle `t` (counted; a miss's MSHR wait too).
  /// A miss must be followed by hold() on the MSHR it names.
  Access access(uint64_t line, uint64_t t) {
    ++counters_.accesses;
    // A line in flight is never in the tag array, so the order of the two checks is free.
    if (tags_.touch(line)) {
      ++counters_.hits;
      return {Outcome::Hit, t + hit_latency_, 0, 0};
    }
    // One pass over the MSHRs: the one holding `line`, and the first of the
    // earliest free cycle (selects, no branches).
    const uint32_t n = static_cast<uint32_t>(fill_.size());
    uint32_t found = n, best = 0;
    uint64_t free_at = ~uint64_t{0};
    for (uint32_t i = n; i-- > 0;) {
      found = flight_line_[i] == line ? i : found;
      const bool not_later = fill_[i] <= free_at;
      best = not_later ? i : best;
      free_at = not_later ? fill_[i] : free_at;
    }
    if (found != n) {
      const uint64_t fill = fill_[found];
      if (t < fill) {
        ++counters_.merges;
        return {Outcome::Merge, fill, 0, 0};
      }
      ++counters_.hits;  // filled but not yet installed: present all the same
      return {Outcome::Hit, t + hit_latency_, 0, 0};
    }
    ++counters_.misses;
    const uint64_t start = free_at > t ? free_at : t;
    counters_.mshr_stall_cycles += start - t;
    return {Outcome::Miss, 0, best, start};
  }
  /// Records the miss of `line` on MSHR `mshr`, its data filling at `fill`.
  void hold(uint32_t mshr, uint64_t line, uint64_t fill) {
    if (flight_line_[mshr] != LruCache::kNoLine)
      tags_.install(flight_line_[mshr]);  // filled before this miss started: present now
    flight_line_[mshr] = line;
    fill_[mshr] = fill;
    order_[mshr] = ++claims_;
    if (fill < next_fill_) next_fill_ = fill;
  }

  uint32_t hit_latency() const { return hit_latency_; }
  const LevelCounters& counters() const { return counters_; }
  const LruCache& tags() const { return tags_; }

 private:
  void retire_slow(uint64_t horizon);

  LruCache tags_;
  uint32_t hit_latency_;
  // The MSHRs, one entry each in every array:
  std::vector<uint64_t> flight_line_;  // the line in flight (not yet in the tag array), or kNoLine
  std::vector<uint64_t> fill_;         // the cycle the MSHR frees (its line's fill cycle)
  std::vector<uint64_t> order_;        // claim order: breaks ties between equal fill cycles
  std::vector<uint32_t> due_;          // scratch of retire_slow
  uint64_t claims_ = 0;
  uint64_t next_fill_ = ~uint64_t{0};  // earliest fill among MSHRs in flight
  LevelCounters counters_;
};

}  // namespace vbsim::hw
