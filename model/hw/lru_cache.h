// The tag array of one set-associative cache with least-recently-used
// replacement. It only knows which lines are present: timing, fills in flight
// and miss limits live in the memory hierarchy around it.
//
// Lines are numbered by `addr / line_bytes`; a line lives in set
// `line % sets`. Storage is flat, no allocation after construction: a set is
// its `ways` lines side by side, most recently used first (empty ways, kNoLine,
// last), so a hit moves its line to the front and a fill evicts the last one.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vbsim::hw {

class LruCache {
 public:
  static constexpr uint64_t kNoLine = ~uint64_t{0};

  /// `sets` >= 1 and `ways` >= 1 (make_memory validates the configuration).
  LruCache(uint32_t sets, uint32_t ways);

  /// True when `line` is present; a hit makes it the most recently used of its set.
  bool touch(uint64_t line) { return touch_in(set_of(line), line); }
  /// touch() of `line`, whose set (set_of(line)) the caller already knows.
  /// `Ways`, when not 0, is ways() known at compile time (the caller checked it).
  template <uint32_t Ways = 0>
  bool touch_in(uint32_t set_index, uint64_t line) {
    const uint32_t ways = Ways ? Ways : ways_;
    uint64_t* set = &lines_[static_cast<size_t>(set_index) * ways];
    if (set[0] == line) return true;  // already the most recent: nothing moves
    const uint32_t w = Ways ? find_in<Ways>(set, line) : find_way(set, line);
    if (w == ways) return false;
    for (uint32_t i = w; i > 0; --i) set[i] = set[i - 1];  // the line becomes the most recent
    set[0] = line;
    return true;
  }
  /// True when `line` is present; changes nothing.
  bool contains(uint64_t line) const { return find_way(set_at(line), line) != ways_; }
  /// Puts `line` (not present) into its set as the most recently used line,
  /// replacing an empty way or else the least recently used line. Returns the
  /// line it replaced, or kNoLine.
  uint64_t install(uint64_t line) { return install_in(set_of(line), line); }
  /// install() of `line`, whose set (set_of(line)) the caller already knows;
  /// `Ways` as for touch_in.
  template <uint32_t Ways = 0>
  uint64_t install_in(uint32_t set_index, uint64_t line) {
    const uint32_t ways = Ways ? Ways : ways_;
    uint64_t* set = &lines_[static_cast<size_t>(set_index) * ways];
    const uint64_t replaced = set[ways - 1];  // the least recent line, or an empty way
    if constexpr (Ways != 0) {
      age<Ways>(set);
    } else {
      switch (ways_) {  // every way moves one place down: unrolled for the usual associativities
        case 4: age<4>(set); break;
        case 8: age<8>(set); break;
        case 16: age<16>(set); break;
        default: age(set, ways_);
      }
    }
    set[0] = line;
    return replaced;
  }

  /// Asks the host's caches for the set of `line` (no effect on any result).
  void prefetch(uint64_t line) const { __builtin_prefetch(set_at(line)); }

  uint32_t sets() const { return sets_; }
  uint32_t ways() const { return ways_; }
  /// The set `line` lives in.
  uint32_t set_of(uint64_t line) const {
    return static_cast<uint32_t>(sets_pow2_ ? (line & set_mask_) : line % sets_);
  }

 private:
  const uint64_t* set_at(uint64_t line) const { return &lines_[static_cast<size_t>(set_of(line)) * ways_]; }
  /// Way of `line` in `set`, or ways_: every way is compared (no early exit, so
  /// no branch depends on where the line is).
  uint32_t find_way(const uint64_t* set, uint64_t line) const {
    switch (ways_) {  // the usual associativities with their loops unrolled
      case 4: return find_in<4>(set, line);
      case 8: return find_in<8>(set, line);
      case 16: return find_in<16>(set, line);
      default: return find_in(set, line, ways_);
    }
  }
  template <uint32_t Ways>
  static uint32_t find_in(const uint64_t* set, uint64_t line) {
    return find_in(set, line, Ways);
  }
  template <uint32_t Ways>
  static void age(uint64_t* set) {
    age(set, Ways);
  }
  static void age(uint64_t* set, uint32_t ways) {
    for (uint32_t i = ways - 1; i > 0; --i) set[i] = set[i - 1];
  }
  static uint32_t find_in(const uint64_t* set, uint64_t line, uint32_t ways) {
    uint32_t found = ways;
    for (uint32_t w = ways; w-- > 0;) found = set[w] == line ? w : found;
    return found;
  }

  uint32_t sets_, ways_;
  bool sets_pow2_;               // sets is a power of two (1 included): a set is line & set_mask_
  uint64_t set_mask_;            // sets - 1
  std::vector<uint64_t> lines_;  // sets * ways; per set in recency order, kNoLine when empty
};

}  // namespace vbsim::hw
