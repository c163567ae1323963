// TraceIdSet: the ids a stream of rays has shown, in bounded memory, for the
// duplicate-id rule and for telling a parent that was dropped from a window
// from one that never came.
//
// The ids are kept as ranges of consecutive ids (ids in trace order, from any
// first id, form one range; a few ids out of place cost a range each). At most
// max_ranges() ranges are kept: when a new range would exceed that, the two
// lowest ranges are merged into one range marked merged, which also covers the
// ids between them that never came. Membership is then answered in three ways:
//   No       the id never came (exact);
//   Yes      the id came (exact);
//   Unknown  the id lies in a merged range: it may or may not have come.
// So the answer is never wrong, only sometimes unknown, and memory is at most
// about 64 bytes a range whatever the number of rays or the order of their ids.
#pragma once
#include <cstddef>
#include <cstdint>
#include <map>

namespace vbsim {

class TraceIdSet {
 public:
  enum class Membership : uint8_t { No, Yes, Unknown };
  /// 131,072 ranges: at most about 8 MB.
  static constexpr std::size_t kDefaultMaxRanges = std::size_t{1} << 17;

  /// `max_ranges` >= 2.
  explicit TraceIdSet(std::size_t max_ranges = kDefaultMaxRanges);

  /// Adds `id` (>= 0); returns its membership before the call (Yes: a duplicate).
  Membership insert(int64_t id);
  Membership contains(int64_t id) const;

  std::size_t ranges() const { return ranges_.size(); }
  std::size_t max_ranges() const { return max_ranges_; }
  /// True until a merge: every answer so far and from now on is Yes or No.
  bool exact() const { return !merged_any_; }

 private:
  struct Range {
    int64_t last;  ///< the last id (inclusive: a range may end at the largest int64)
    bool merged;   ///< covers ids that may never have come
  };
  /// Merges the two lowest ranges (called when there are too many).
  void merge_lowest();

  std::map<int64_t, Range> ranges_;  ///< first id -> range; disjoint, not adjacent
  std::size_t max_ranges_;
  bool merged_any_ = false;
};

}  // namespace vbsim
