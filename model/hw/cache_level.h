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
  /// A miss must be followed by hold() on the MSHR it names. `Ways`, when not
  /// 0, is the associativity known at compile time (the caller checked it).
  template <uint32_t Ways = 0>
  Access access(uint64_t line, uint64_t t) {
    ++counters_.accesses;
    // A line in flight is never in the tag array, so the order of the two checks is free.
    const uint32_t set = tags_.set_of(line);
    if (tags_.touch_in<Ways>(set, line)) {
      ++counters_.hits;
      return {Outcome::Hit, t + hit_latency_, 0, 0};
    }
    if (in_flight_per_set_[set] != 0) {  // else no MSHR can hold it
      const uint32_t found = find_in_flight(line);
      if (found != mshrs_) {
        const uint64_t fill = fill_[found];
        if (t < fill) {
          ++counters_.merges;
          return {Outcome::Merge, fill, 0, 0};
        }
        ++counters_.hits;  // filled but not yet installed: present all the same
        return {Outcome::Hit, t + hit_latency_, 0, 0};
      }
    }
    ++counters_.misses;
    // The first of the earliest free cycle: the front of the free order.
    const uint64_t front = ring_[head_];
    const uint64_t free_at = front >> index_bits_;
    const uint64_t start = free_at > t ? free_at : t;
    counters_.mshr_stall_cycles += start - t;
    return {Outcome::Miss, 0, static_cast<uint32_t>(front & index_mask_), start};
  }
  /// Records the miss of `line` that the last access() answered with Miss: it
  /// holds the MSHR access() named until its data fill at `fill` (> every
  /// horizon retired so far).
  /// Inlined into the hierarchy's line reads (below the class); `Ways` as for access().
  template <uint32_t Ways = 0>
  void hold(uint64_t line, uint64_t fill);

  uint32_t hit_latency() const { return hit_latency_; }
  const LevelCounters& counters() const { return counters_; }
  const LruCache& tags() const { return tags_; }

 private:
  void retire_slow(uint64_t horizon);
  /// The MSHR whose line in flight is `line`, or mshrs_.
  uint32_t find_in_flight(uint64_t line) const {
    uint32_t found = mshrs_;
    for (uint32_t i = mshrs_; i-- > 0;) found = flight_line_[i] == line ? i : found;
    return found;
  }
  /// Installs MSHR `mshr`'s line in flight; the MSHR holds no line afterwards.
  template <uint32_t Ways = 0>
  void install(uint32_t mshr) {
    const uint64_t line = flight_line_[mshr];
    const uint32_t set = tags_.set_of(line);
    tags_.install_in<Ways>(set, line);
    --in_flight_per_set_[set];
    flight_line_[mshr] = LruCache::kNoLine;
  }
  /// The key at position k of the free order (0: the front).
  uint64_t& ring_at(uint32_t k) { return ring_[(head_ + k) & index_mask_]; }
  uint64_t fill_of_key(uint64_t key) const { return key >> index_bits_; }

  LruCache tags_;
  uint32_t hit_latency_;
  uint32_t mshrs_;
  // The MSHRs, one entry each in every array:
  std::vector<uint64_t> flight_line_;  // the line in flight (not yet in the tag array), or kNoLine
  std::vector<uint64_t> fill_;         // the cycle the MSHR frees (its line's fill cycle)
  std::vector<uint64_t> order_;        // claim order: breaks ties between equal fill cycles
  // Every MSHR as (free cycle << index_bits_ | index), sorted, in a ring that
  // starts at head_: the front is the first of the earliest free cycle, the
  // one a miss takes. The ring's storage has 2^index_bits_ >= mshrs_ places (a
  // position wraps with index_mask_); the ring is the mshrs_ places from head_.
  // The MSHRs whose fill is after the last retired horizon hold their line in
  // flight; they are the ring's tail from position pending_from_.
  std::vector<uint64_t> ring_;
  uint32_t head_ = 0, pending_from_;
  uint32_t index_bits_;
  uint64_t index_mask_;
  std::vector<uint32_t> in_flight_per_set_;  // per tag set: lines in flight that map to it
  std::vector<uint32_t> due_;                // scratch of retire_slow
  uint64_t claims_ = 0;
  uint64_t next_fill_ = ~uint64_t{0};  // the fill at pending_from_, or none
  LevelCounters counters_;
};

template <uint32_t Ways>
__attribute__((always_inline)) inline void CacheLevel::hold(uint64_t line, uint64_t fill) {
  // The front leaves the ring; its line, if still in flight, filled before
  // this miss started: present now.
  const uint32_t mshr = static_cast<uint32_t>(ring_[head_] & index_mask_);
  if (pending_from_ == 0) install<Ways>(mshr);
  else --pending_from_;
  head_ = static_cast<uint32_t>((head_ + 1) & index_mask_);

  flight_line_[mshr] = line;
  fill_[mshr] = fill;
  order_[mshr] = ++claims_;
  ++in_flight_per_set_[tags_.set_of(line)];

  // Back in at its place from the tail (cycles stay below 2^(64 - index_bits_),
  // i.e. 2^52). Its fill is after every retired horizon, so it lands in the
  // pending tail; fills arrive nearly in order, so this moves few keys.
  const uint64_t key = (fill << index_bits_) | mshr;
  uint32_t k = mshrs_ - 1;
  for (; k > pending_from_ && ring_at(k - 1) > key; --k) ring_at(k) = ring_at(k - 1);
  ring_at(k) = key;
  next_fill_ = fill_of_key(ring_at(pending_from_));
}

}  // namespace vbsim::hw
