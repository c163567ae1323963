// RecentIdWindow: the ids of the last W rays of a trace, in trace order, with
// lookup by id. Memory is fixed at W slots (plus a W-entry hash index once ids
// stop ascending), reached as rays arrive, whatever the trace's length: the bounded state that the
// trace consistency checks keep instead of a set of every id seen.
//
// Each ray occupies one slot (0 .. W-1), reused W rays later; a caller keeps
// per-ray data in a parallel array indexed by slot.
#pragma once
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace vbsim {

class RecentIdWindow {
 public:
  /// `capacity` >= 1 slots.
  explicit RecentIdWindow(std::size_t capacity);

  /// Appends `id` (evicting the oldest when full) and returns its slot.
  /// Precondition: `id` is not in the window (the readers reject duplicates).
  std::size_t push(int64_t id);
  /// Slot of `id`, or -1 when it is not among the last capacity() ids.
  int64_t find(int64_t id) const;

  /// True while every id pushed so far was greater than the one before.
  bool ascending() const { return ascending_; }
  std::size_t size() const { return size_; }
  std::size_t capacity() const { return capacity_; }

 private:
  /// Slot of the k-th oldest id in the window (k in [0, size_)).
  std::size_t slot_of(std::size_t k) const;

  std::size_t capacity_;
  std::vector<int64_t> ids_;  ///< grown as ids arrive, up to capacity_ (no window allocated up front)
  std::size_t next_ = 0;  ///< slot the next push writes
  std::size_t size_ = 0;
  bool ascending_ = true;
  /// id -> slot, kept only once ids stop ascending (until then lookup is a
  /// search of the sorted ring).
  std::unordered_map<int64_t, std::size_t> index_;
};

}  // namespace vbsim
