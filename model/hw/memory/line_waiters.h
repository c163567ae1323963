// LineWaiters: the requests of a cache level waiting for lines whose fill
// cycle is not known yet (a pending miss), answered when it is. Each pending
// line has its own chain of waiters in arrival order, found through a small
// open-addressing table keyed by the line, so a fill touches its own waiters
// only (a level may hold a waiter for every slot of its core, or every core's
// misses, at once). Entries and chains are reused: nothing is allocated once
// the pool, the table and the scratch space have grown to the run's needs.
#pragma once
#include <cstdint>
#include <vector>

#include "hw/memory/cache_level.h"

namespace vbsim::hw {

class LineWaiters {
 public:
  LineWaiters() : table_(kInitialBuckets) {}

  /// Request `who` (a slot, or a core's L1) asked for `line` at cycle `t`.
  void add(uint64_t line, uint32_t who, uint64_t t) {
    const uint32_t e = new_entry(who, t);
    Chain& c = chain_for(line);
    if (c.head == kNone) c.head = e;
    else pool_[c.tail].next = e;
    c.tail = e;
  }

  /// `line` arrives at `fill`: its waiters, in the order they came, are
  /// answered through `answer(who, ready)`: a request at or after the fill is
  /// a hit (recounted from a merge in `level`) ready after the hit latency,
  /// the others at the fill. `answer` may add waiters (of any line: they wait
  /// for a later fill), and fill lines itself (nested calls).
  ///
  /// A level that does not merge misses (CacheConfig::merge_misses false) has
  /// one waiter per miss of its own, each miss one fill: the fill answers the
  /// line's waiter that asked first (the smallest cycle, the earliest added
  /// among equals; misses of one line are sent, and the built-in DRAM answers
  /// them, in that order), never as a hit (its own miss's data come after it
  /// asked).
  template <class Answer>
  void fill(uint64_t line, uint64_t fill, CacheLevel& level, Answer&& answer) {
    const uint32_t b = find(line);
    if (b == kNone) return;
    if (scratch_.size() == depth_) scratch_.emplace_back();
    std::vector<Waiter>& mine = scratch_[depth_];
    mine.clear();
    const bool all = level.merges_misses();
    if (all) {
      for (uint32_t e = table_[b].head; e != kNone;) {
        const uint32_t next = pool_[e].next;
        mine.push_back({pool_[e].who, pool_[e].t});
        release(e);
        e = next;
      }
      erase_bucket(b);
    } else {
      take_first(b, mine);
    }
    ++depth_;
    for (const Waiter& w : mine) {
      const bool hit = all && w.t >= fill;
      if (hit) level.recount_merge_as_hit();
      answer(w.who, hit ? w.t + level.hit_latency() : fill);
    }
    --depth_;
  }

  /// Requests waiting (every line).
  size_t size() const { return waiting_; }

 private:
  static constexpr uint32_t kNone = ~uint32_t{0};
  static constexpr uint32_t kInitialBuckets = 64;  // a power of two
  struct Entry {
    uint64_t t;
    uint32_t who, next;  // next: the line's following waiter, or the free list's
  };
  struct Waiter {
    uint32_t who;
    uint64_t t;
  };
  /// A bucket: a pending line and its waiters, first and last (head kNone: empty).
  struct Chain {
    uint64_t line = 0;
    uint32_t head = kNone, tail = kNone;
  };

  uint32_t new_entry(uint32_t who, uint64_t t) {
    ++waiting_;
    if (free_ != kNone) {
      const uint32_t e = free_;
      free_ = pool_[e].next;
      pool_[e] = {t, who, kNone};
      return e;
    }
    pool_.push_back({t, who, kNone});
    return static_cast<uint32_t>(pool_.size() - 1);
  }
  void release(uint32_t e) {
    --waiting_;
    pool_[e].next = free_;
    free_ = e;
  }
  uint32_t mask() const { return static_cast<uint32_t>(table_.size() - 1); }
  uint32_t home(uint64_t line) const {
    return static_cast<uint32_t>((line * 0x9E3779B97F4A7C15ull) >> 40) & mask();
  }
  /// The bucket of `line`, or kNone.
  uint32_t find(uint64_t line) const {
    for (uint32_t b = home(line);; b = (b + 1) & mask()) {
      if (table_[b].head == kNone) return kNone;
      if (table_[b].line == line) return b;
    }
  }
  /// The bucket of `line`, made (empty) when there is none.
  Chain& chain_for(uint64_t line) {
    uint32_t b = home(line);
    for (;; b = (b + 1) & mask()) {
      if (table_[b].head == kNone) break;
      if (table_[b].line == line) return table_[b];
    }
    if (2 * (lines_ + 1) > table_.size()) {  // at most half full
      grow();
      return chain_for(line);
    }
    ++lines_;
    table_[b].line = line;
    return table_[b];
  }
  void grow() {
    std::vector<Chain> old(table_.size() * 2);
    old.swap(table_);
    for (const Chain& c : old) {
      if (c.head == kNone) continue;
      uint32_t b = home(c.line);
      while (table_[b].head != kNone) b = (b + 1) & mask();
      table_[b] = c;
    }
  }
  /// Empties bucket `b`, moving later buckets of its probe run back (no tombstones).
  void erase_bucket(uint32_t b) {
    --lines_;
    uint32_t hole = b;
    for (uint32_t j = (b + 1) & mask(); table_[j].head != kNone; j = (j + 1) & mask()) {
      const uint32_t h = home(table_[j].line);
      // table_[j] may move into the hole when its home is not in (hole, j].
      const bool stays = hole <= j ? (hole < h && h <= j) : (hole < h || h <= j);
      if (stays) continue;
      table_[hole] = table_[j];
      hole = j;
    }
    table_[hole] = Chain{};
  }
  /// Moves the waiter of bucket `b` with the smallest cycle (the earliest
  /// among equals) into `out`; empties the bucket when it was the last.
  void take_first(uint32_t b, std::vector<Waiter>& out) {
    Chain& c = table_[b];
    uint32_t best = c.head, best_prev = kNone;
    for (uint32_t prev = c.head, e = pool_[c.head].next; e != kNone; prev = e, e = pool_[e].next)
      if (pool_[e].t < pool_[best].t) best = e, best_prev = prev;
    out.push_back({pool_[best].who, pool_[best].t});
    const uint32_t next = pool_[best].next;
    if (best_prev == kNone) c.head = next;
    else pool_[best_prev].next = next;
    if (c.tail == best) c.tail = best_prev;
    release(best);
    if (c.head == kNone) erase_bucket(b);
  }

  std::vector<Entry> pool_;
  uint32_t free_ = kNone;
  std::vector<Chain> table_;  // power-of-two buckets, at most half full
  size_t lines_ = 0, waiting_ = 0;
  std::vector<std::vector<Waiter>> scratch_;  // one per nesting depth of fill()
  size_t depth_ = 0;
};

}  // namespace vbsim::hw
