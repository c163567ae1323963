// LineWaiters: the requests of a cache level waiting for lines whose fill
// cycle is not known yet (a pending miss), answered when it is. A flat list in
// arrival order: few lines are pending at once (at most the level's MSHRs and
// deferred misses), so a scan is cheaper than a hash table's allocation per
// line, and nothing is allocated once the list and its scratch space have grown.
#pragma once
#include <cstdint>
#include <vector>

#include "hw/memory/cache_level.h"

namespace vbsim::hw {

class LineWaiters {
 public:
  /// Request `who` (a slot, or a core's L1) asked for `line` at cycle `t`.
  void add(uint64_t line, uint32_t who, uint64_t t) { entries_.push_back({line, who, t}); }

  /// `line` arrives at `fill`: its waiters, in the order they came, are
  /// answered through `answer(who, ready)`: a request at or after the fill is
  /// a hit (recounted from a merge in `level`) ready after the hit latency,
  /// the others at the fill. `answer` may add waiters for other lines, and
  /// fill lines itself (nested calls).
  ///
  /// A level that does not merge misses (CacheConfig::merge_misses false) has
  /// one waiter per miss of its own, each miss one fill: the fill answers the
  /// line's waiter that asked first (the smallest cycle; misses of one line
  /// are sent, and the built-in DRAM answers them, in that order), never as a
  /// hit (its own miss's data come after it asked).
  template <class Answer>
  void fill(uint64_t line, uint64_t fill, CacheLevel& level, Answer&& answer) {
    if (scratch_.size() == depth_) scratch_.emplace_back();
    std::vector<Entry>& mine = scratch_[depth_];
    mine.clear();
    size_t kept = 0;
    const bool all = level.merges_misses();
    size_t first = entries_.size();
    if (!all)
      for (size_t i = 0; i < entries_.size(); ++i)
        if (entries_[i].line == line && (first == entries_.size() || entries_[i].t < entries_[first].t)) first = i;
    for (size_t i = 0; i < entries_.size(); ++i) {
      const Entry& e = entries_[i];
      if (all ? e.line == line : i == first) mine.push_back(e);
      else entries_[kept++] = e;
    }
    entries_.resize(kept);
    ++depth_;
    for (const Entry& e : mine) {
      const bool hit = all && e.t >= fill;
      if (hit) level.recount_merge_as_hit();
      answer(e.who, hit ? e.t + level.hit_latency() : fill);
    }
    --depth_;
  }

 private:
  struct Entry {
    uint64_t line;
    uint32_t who;
    uint64_t t;
  };
  std::vector<Entry> entries_;
  std::vector<std::vector<Entry>> scratch_;  // one per nesting depth of fill()
  size_t depth_ = 0;
};

}  // namespace vbsim::hw
