// One cache of the hierarchy in time: an LRU tag array that allocates a line
// when its miss is sent, its hit latency and its miss-status holding registers
// (MSHRs), each holding one miss until its fill.
//
// Time rules (see docs/memory-model.md):
//  - A request whose line is in the tag array merges with the miss in flight
//    when it arrives before the line's fill cycle (ready at the fill cycle),
//    and hits from the fill cycle on (ready after the hit latency). Either way
//    the line becomes the most recently used of its set.
//    With merging off (CacheConfig::merge_misses false) such a request is a
//    miss of its own instead (below), its line already allocated: it takes
//    an MSHR and asks the next level again, and its data come with that answer.
//  - Otherwise it misses: it takes the MSHR that frees first and leaves the
//    level at the later of its arrival and that MSHR's free cycle (the wait is
//    an MSHR-full stall). The caller then gives the fill cycle the next level
//    answered (fill()): the line enters the tag array at once, as the most
//    recently used, evicting the least recently used line of its set that is
//    not itself in flight (the least recently used line when all are), and
//    the MSHR stays held until the fill.
#pragma once
#include <cstdint>
#include <vector>

#include "hw/memory/free_cycle_ring.h"
#include "hw/memory/lru_cache.h"
#include "hw/memory/memory_config.h"
#include "hw/pending_cycle.h"

namespace vbsim::hw {

struct LevelCounters {
  uint64_t accesses = 0, hits = 0, misses = 0, merges = 0;
  uint64_t mshr_stall_cycles = 0;  ///< summed over misses: cycles waited for a free MSHR
};

class CacheLevel {
 public:
  enum class Outcome { Hit, Merge, Miss };
  /// What a request met. Hit: ready = t + hit latency. Merge: ready = the fill
  /// cycle of the miss in flight. Miss: the cycle it leaves this level (>= its
  /// arrival), when the MSHR that frees first is free.
  struct Access {
    Outcome outcome;
    uint64_t ready;  ///< Hit, Merge
    uint64_t start;  ///< Miss
    /// Miss: the line is already allocated, its own miss in flight (merging
    /// off): the caller holds an MSHR for this miss (hold_mshr) and does not
    /// allocate the line again.
    bool allocated = false;
  };

  /// `config` is valid (make_memory checks it).
  explicit CacheLevel(const CacheConfig& config);

  /// A request for `line` arriving at cycle `t` (counted; a miss's MSHR wait too).
  /// A miss must be followed by fill() of the same line. `Ways`, when not 0, is
  /// the associativity known at compile time (the caller checked it).
  template <uint32_t Ways = 0>
  __attribute__((always_inline)) Access access(uint64_t line, uint64_t t) {
    uint64_t fill;
    if (tags_.touch_in<Ways>(tags_.set_of(line), line, fill)) {
      if (t < fill) {
        if (__builtin_expect(!merge_, 0)) return miss(t, true);
        ++counters_.merges;
        return {Outcome::Merge, fill, 0};
      }
      ++counters_.hits;
      return {Outcome::Hit, t + hit_latency_, 0};
    }
    return miss(t, false);
  }
  /// Functional warming (sampled simulation, hw/sampling/): the tag array
  /// sees `line` as an access would, with no time: a present line becomes the
  /// most recently used of its set (true); an absent one is allocated as the
  /// most recently used, filled long ago, in the way of the least recently
  /// used line not in flight (false). No counter, MSHR or cycle changes; an
  /// unsampled run never calls it.
  bool warm(uint64_t line) {
    uint64_t fill;
    if (tags_.touch(line, fill)) return true;
    tags_.install(line, 0, kPendingCycle - 1);
    return false;
  }
  /// Requests for a line in flight wait for its miss (CacheConfig::merge_misses).
  bool merges_misses() const { return merge_; }
  /// Completes the miss of `line` that the last access() answered with Miss,
  /// sent at `start` (the Access's): its data arrive at `fill` (>= start). The
  /// line is allocated now, in the way of the least recently used line not in
  /// flight at `start`; the MSHR the miss took is held until `fill`. `Ways` as
  /// for access().
  /// Inlined into the caches' line reads.
  template <uint32_t Ways = 0>
  void fill(uint64_t line, uint64_t fill, uint64_t start) {
    install<Ways>(line, fill, start);
    hold_mshr(fill);
  }

  // The parts of fill(), for a miss whose fill cycle (or start) is not known
  // when it is allocated (an approximately timed memory behind the level: the
  // fill is then kPendingCycle until resolve()).
  /// Allocates `line` with fill cycle `fill` at cycle `start` (as fill() does).
  template <uint32_t Ways = 0>
  void install(uint64_t line, uint64_t fill, uint64_t start) {
    tags_.install_in<Ways>(tags_.set_of(line), line, fill, start);
  }
  /// The MSHR that frees first is held until `fill`.
  void hold_mshr(uint64_t fill);
  /// The earliest cycle an MSHR is free (kPendingCycle: every MSHR holds a
  /// miss whose fill is not known yet).
  uint64_t mshr_free_cycle() const { return mshrs_.front(); }
  /// Counts `cycles` more waited for a free MSHR (a miss that waited for one
  /// whose fill was not known when the miss arrived).
  void count_mshr_wait(uint64_t cycles) { counters_.mshr_stall_cycles += cycles; }
  /// Takes back what access() added for a miss at `t` that found every MSHR
  /// waiting for an unknown fill (its start was kPendingCycle).
  void uncount_pending_wait(uint64_t t) { counters_.mshr_stall_cycles -= kPendingCycle - t; }
  /// The miss of `line` allocated with an unknown fill has its data at `fill`:
  /// the line (if still present) and one MSHR held until an unknown cycle
  /// take that cycle. With merging off the line's fill is set only while it
  /// is unknown (a later miss of the same line does not move its first fill).
  void resolve(uint64_t line, uint64_t fill);
  /// A request counted as a merge turned out to arrive at or after the fill: a hit.
  void recount_merge_as_hit() {
    --counters_.merges;
    ++counters_.hits;
  }

  uint32_t hit_latency() const { return hit_latency_; }
  /// The counters, accesses = hits + misses + merges.
  LevelCounters counters() const {
    LevelCounters c = counters_;
    c.accesses = c.hits + c.misses + c.merges;
    return c;
  }
  const LruCache& tags() const { return tags_; }

 private:
  /// A miss at `t`: it leaves when the MSHR that frees first is free.
  Access miss(uint64_t t, bool allocated) {
    ++counters_.misses;
    // The earliest free cycle of any MSHR: the front of the sorted ring.
    const uint64_t free_at = mshrs_.front();
    const uint64_t start = free_at > t ? free_at : t;
    // (start kPendingCycle: every MSHR waits for a fill not known yet; the
    // caller takes this back, uncount_pending_wait, and counts the wait once
    // the miss is sent.)
    counters_.mshr_stall_cycles += start - t;
    return {Outcome::Miss, 0, start, allocated};
  }

  LruCache tags_;
  uint32_t hit_latency_;
  bool merge_;
  // Every MSHR's free cycle: the fill of the miss it holds (kPendingCycle: not
  // known yet, so those sort last), 0 when it never held one.
  FreeCycleRing mshrs_;
  uint32_t pending_ = 0;  // MSHRs held until an unknown fill: the ring's last places
  LevelCounters counters_;  // accesses unused: counters() derives it
};

__attribute__((always_inline)) inline void CacheLevel::hold_mshr(uint64_t fill) {
  if (__builtin_expect(mshrs_.front() == kPendingCycle, 0)) --pending_;  // (callers take a known front)
  if (__builtin_expect(fill == kPendingCycle, 0)) ++pending_;
  mshrs_.take_front(fill);
}

}  // namespace vbsim::hw
