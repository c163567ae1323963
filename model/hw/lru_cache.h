// The tag array of one set-associative cache with least-recently-used
// replacement. It only knows which lines are present: timing, fills in flight
// and miss limits live in the memory hierarchy around it.
//
// Lines are numbered by `addr / line_bytes`; a line lives in set
// `line % sets`. Storage is flat: one tag and one age stamp per way, a set's ways adjacent, no
// allocation after construction.
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
  bool touch(uint64_t line);
  /// True when `line` is present; changes nothing.
  bool contains(uint64_t line) const;
  /// Puts `line` (not present) into its set as the most recently used line,
  /// replacing an empty way or else the least recently used line. Returns the
  /// line it replaced, or kNoLine.
  uint64_t install(uint64_t line);

  uint32_t sets() const { return sets_; }
  uint32_t ways() const { return ways_; }

 private:
  uint32_t set_of(uint64_t line) const {
    return static_cast<uint32_t>(set_mask_ ? (line & set_mask_) : (sets_ == 1 ? 0 : line % sets_));
  }

  uint32_t sets_, ways_;
  uint64_t set_mask_;            // sets - 1 when sets is a power of two > 1, else 0
  uint64_t clock_ = 0;           // touch counter: a larger stamp is more recent
  struct Way {
    uint64_t line = kNoLine;  // kNoLine when empty
    uint64_t stamp = 0;       // last touch
  };
  std::vector<Way> ways_of_sets_;  // sets * ways, a set's ways side by side
};

}  // namespace vbsim::hw
