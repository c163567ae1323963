// The tag array of one set-associative cache with least-recently-used
// replacement. Each way holds a line and its fill cycle, the cycle at which the
// line's data arrive: a cache that allocates a line when its miss is sent keeps
// it here from then on, with a fill cycle that may lie ahead. It answers which
// lines are present and when they filled; timing rules (merges, miss registers)
// live in CacheLevel around it.
//
// Lines are numbered by `addr / line_bytes`; a line lives in set
// `line % sets`. Storage is flat, no allocation after construction: a set is
// its `ways` ways side by side (16 bytes each, a set starting on a 64-byte host
// line, so a 4-way set is one host line), most recently used first (empty ways,
// kNoLine, last), so a hit moves its line to the front and an install evicts
// the last one that is not in flight. A way holds its line complemented (~line),
// so that an empty way is all zero bytes: the storage starts as zeros that the
// host supplies a page at a time on first write (ZeroedHostArray), and host
// memory follows the sets a run touches, not the cache's configured size.
#pragma once
#include <cstddef>
#include <cstdint>

#include "hw/memory/zeroed_host_array.h"

namespace vbsim::hw {

class LruCache {
 public:
  static constexpr uint64_t kNoLine = ~uint64_t{0};
  /// One way: a line (stored complemented: key ~line, 0 when empty) and its fill cycle.
  struct Way {
    uint64_t key = 0, fill = 0;
    uint64_t line() const { return ~key; }
  };

  /// `sets` >= 1 and `ways` >= 1 (make_memory validates the configuration).
  LruCache(uint32_t sets, uint32_t ways);

  /// True when `line` is present, its fill cycle into `fill`; a hit makes it
  /// the most recently used of its set.
  bool touch(uint64_t line, uint64_t& fill) { return touch_in(set_of(line), line, fill); }
  /// touch() of `line`, whose set (set_of(line)) the caller already knows.
  /// `Ways`, when not 0, is the associativity known at compile time (the caller checked it).
  template <uint32_t Ways = 0>
  bool touch_in(uint32_t set_index, uint64_t line, uint64_t& fill) {
    const uint32_t ways = Ways ? Ways : ways_;
    Way* set = set_at_index(set_index, ways);
    const uint64_t key = ~line;
    if (set[0].key == key) {  // already the most recent: nothing moves
      fill = set[0].fill;
      return true;
    }
    const uint32_t w = Ways ? find_in<Ways>(set, key) : find_in(set, key, ways);
    if (w == ways) return false;
    const Way hit = set[w];
    for (uint32_t i = w; i > 0; --i) set[i] = set[i - 1];  // the line becomes the most recent
    set[0] = hit;
    fill = hit.fill;
    return true;
  }
  /// True when `line` is present; changes nothing.
  bool contains(uint64_t line) const {
    const Way* set = set_at_index(set_of(line), ways_);
    return find_in(set, ~line, ways_) != ways_;
  }
  /// Puts `line` (not present) with fill cycle `fill` into its set at cycle
  /// `now`, as the most recently used line. It replaces an empty way, else the
  /// least recently used line whose fill is at or before `now` (a line still in
  /// flight keeps its way), else, when every way is in flight, the least
  /// recently used line. Returns the line it replaced, or kNoLine.
  uint64_t install(uint64_t line, uint64_t fill, uint64_t now) { return install_in(set_of(line), line, fill, now); }
  /// install() of `line`, whose set (set_of(line)) the caller already knows;
  /// `Ways` as for touch_in.
  template <uint32_t Ways = 0>
  uint64_t install_in(uint32_t set_index, uint64_t line, uint64_t fill, uint64_t now) {
    const uint32_t ways = Ways ? Ways : ways_;
    Way* set = set_at_index(set_index, ways);
    // The usual case: the least recent way (an empty way has fill 0) is not in flight.
    if (set[ways - 1].fill > now) return install_past_flight(set, ways, line, fill, now);
    const uint64_t replaced = set[ways - 1].line();
    for (uint32_t i = ways - 1; i > 0; --i) set[i] = set[i - 1];  // every way one place down
    set[0] = {~line, fill};
    return replaced;
  }

  /// Sets the fill cycle of `line` (present or not) to `fill` without touching
  /// its recency: the answer to a miss that was allocated before its fill cycle
  /// was known (kPendingCycle of hw/unit_interfaces.h). False when the line has
  /// left the array meanwhile.
  bool set_fill(uint64_t line, uint64_t fill) {
    Way* set = set_at_index(set_of(line), ways_);
    const uint32_t w = find_in(set, ~line, ways_);
    if (w == ways_) return false;
    set[w].fill = fill;
    return true;
  }

  /// The fill cycle of `line`, or 0 when it is not in the array.
  uint64_t fill_of(uint64_t line) const {
    const Way* set = set_at_index(set_of(line), ways_);
    const uint32_t w = find_in(set, ~line, ways_);
    return w == ways_ ? 0 : set[w].fill;
  }

  /// Asks the host's caches for the set of `line` (no effect on any result).
  void prefetch(uint64_t line) const {
    const char* p = reinterpret_cast<const char*>(set_at_index(set_of(line), ways_));
    for (size_t at = 0; at < set_stride(ways_) * sizeof(Way); at += 64) __builtin_prefetch(p + at);
  }

  /// The set `line` lives in.
  uint32_t set_of(uint64_t line) const {
    return static_cast<uint32_t>(sets_pow2_ ? (line & set_mask_) : line % sets_);
  }

 private:
  /// 64 bytes of ways: the storage unit, so that every set starts on a host line.
  struct alignas(64) HostLine {
    Way ways[64 / sizeof(Way)];
  };
  static constexpr uint32_t kWaysPerHostLine = 64 / sizeof(Way);

  Way* set_at_index(uint32_t set_index, uint32_t ways) {
    return static_cast<HostLine*>(storage_.data())->ways + static_cast<size_t>(set_index) * set_stride(ways);
  }
  const Way* set_at_index(uint32_t set_index, uint32_t ways) const {
    return static_cast<const HostLine*>(storage_.data())->ways + static_cast<size_t>(set_index) * set_stride(ways);
  }
  /// Ways from one set's start to the next: whole host lines.
  static size_t set_stride(uint32_t ways) {
    return (ways + kWaysPerHostLine - 1) / kWaysPerHostLine * kWaysPerHostLine;
  }
  /// install_in() when the least recent way is in flight at `now` (kept out of line).
  static uint64_t install_past_flight(Way* set, uint32_t ways, uint64_t line, uint64_t fill, uint64_t now);
  /// Way holding `key` (~line) in `set`, or `ways`: every way is compared (no
  /// early exit, so no branch depends on where the line is); unrolled when
  /// `Ways` is known.
  template <uint32_t Ways>
  static uint32_t find_in(const Way* set, uint64_t key) {
    return find_in(set, key, Ways);
  }
  static uint32_t find_in(const Way* set, uint64_t key, uint32_t ways) {
    uint32_t found = ways;
    for (uint32_t w = ways; w-- > 0;) found = set[w].key == key ? w : found;
    return found;
  }

  uint32_t sets_, ways_;
  bool sets_pow2_;                  // sets is a power of two (1 included): a set is line & set_mask_
  uint64_t set_mask_;               // sets - 1
  ZeroedHostArray storage_;         // HostLines: sets * set_stride(ways) ways; per set in recency order
};

}  // namespace vbsim::hw
