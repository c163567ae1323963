#include "trace/trace_id_set.h"

#include <iterator>
#include <limits>
#include <stdexcept>

namespace vbsim {

namespace {

constexpr int64_t kLargestId = std::numeric_limits<int64_t>::max();

/// Whether `id` comes right after `last` (no overflow at the largest id).
bool follows(int64_t last, int64_t id) { return last != kLargestId && id == last + 1; }

}  // namespace

TraceIdSet::TraceIdSet(std::size_t max_ranges) : max_ranges_(max_ranges) {
  if (max_ranges < 2) throw std::invalid_argument("TraceIdSet: max_ranges must be at least 2");
}

TraceIdSet::Membership TraceIdSet::contains(int64_t id) const {
  auto it = ranges_.upper_bound(id);  // first range starting after id
  if (it == ranges_.begin()) return Membership::No;
  --it;
  if (id > it->second.last) return Membership::No;
  return it->second.merged ? Membership::Unknown : Membership::Yes;
}

TraceIdSet::Membership TraceIdSet::insert(int64_t id) {
  // Ids in trace order extend the highest range: one look-up of the last range.
  if (!ranges_.empty()) {
    auto last = std::prev(ranges_.end());
    if (follows(last->second.last, id)) {
      last->second.last = id;
      return Membership::No;
    }
  }
  auto next = ranges_.upper_bound(id);
  if (next != ranges_.begin()) {
    auto prev = std::prev(next);
    if (id <= prev->second.last) return prev->second.merged ? Membership::Unknown : Membership::Yes;
    if (follows(prev->second.last, id)) {  // extends prev, and may join it to next
      prev->second.last = id;
      if (next != ranges_.end() && follows(id, next->first)) {
        prev->second.last = next->second.last;
        prev->second.merged |= next->second.merged;
        ranges_.erase(next);
      }
      return Membership::No;
    }
  }
  if (next != ranges_.end() && follows(id, next->first)) {  // extends next downwards
    const Range r = next->second;
    ranges_.erase(next);
    ranges_.emplace(id, r);
    return Membership::No;
  }
  ranges_.emplace_hint(next, id, Range{id, false});
  if (ranges_.size() > max_ranges_) merge_lowest();
  return Membership::No;
}

void TraceIdSet::merge_lowest() {
  auto first = ranges_.begin();
  auto second = std::next(first);
  first->second.last = second->second.last;
  first->second.merged = true;
  ranges_.erase(second);
  merged_any_ = true;
}

}  // namespace vbsim
