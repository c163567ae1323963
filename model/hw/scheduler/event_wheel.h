// EventWheel: the cycle engine's pending events, handed out by cycle, and
// within one cycle in the order they were scheduled (first scheduled, first
// handed out). Each id has at most one pending event (a busy slot's current
// step, the ray source).
//
// A calendar queue: a ring of 2^k buckets, one per cycle of the window
// [base, base + 2^k), each a singly linked FIFO list of ids threaded through
// one link per id, with a bitmap of the non-empty buckets; events beyond the
// window wait in an overflow min-heap of (cycle, scheduling order) and move into
// the ring, in that order, as the window reaches them (every event that goes
// straight into a bucket was scheduled after those moved into it, so each
// bucket stays in scheduling order). Taking an event follows the current
// cycle's list; an event scheduled for the cycle being handed out joins its
// end. A fence (set_fence: a cycle the wheel reads whenever it opens a cycle)
// keeps it from opening a cycle at or after the fence, so that work outside
// the wheel (the memory step, hw/memory/memory_clock.h) can run before the events of
// its cycle at no cost per event. Nothing is allocated after construction (the
// heap's room is reserved for every id).
#pragma once
#include <algorithm>
#include <cstdint>
#include <functional>
#include <vector>

namespace vbsim::hw {

class EventWheel {
 public:
  static constexpr uint32_t kNone = ~uint32_t{0};

  /// Ids are 0 .. ids-1; the window spans 2^window_log2 cycles.
  explicit EventWheel(uint32_t ids, uint32_t window_log2 = 10)
      : ids_(ids), mask_((uint64_t{1} << window_log2) - 1), tail_(size_t{1} << window_log2),
        occupied_(((size_t{1} << window_log2) + 63) / 64, 0), link_(ids + (size_t{1} << window_log2), kNone) {
    for (size_t b = 0; b < tail_.size(); ++b) tail_[b] = head_cell(b);
    overflow_.reserve(ids);
  }

  bool empty() const { return pending_ == 0; }

  /// take() opens no cycle at or after `*fence` (which outlives the wheel; it
  /// may change between takes, and is never at or before a cycle handed out
  /// while that cycle still has events). Default: no fence.
  void set_fence(const uint64_t* fence) { fence_ = fence; }

  /// Schedules `id` (not pending) at cycle `at`, which is not before the cycle
  /// last handed out.
  __attribute__((always_inline)) void schedule(uint64_t at, uint32_t id) {
    ++pending_;
    link_[id] = kNone;
    if (at == base_) {  // joins the end of the cycle being handed out (its bucket stays empty)
      if (next_ == kNone) next_ = id;
      else link_[batch_tail_] = id;
      batch_tail_ = id;
      return;
    }
    if (at - base_ > mask_) return schedule_far(at, id);
    put(at, id);
  }

  /// Cycle of the next event; the wheel is not empty.
  uint64_t next_cycle() const {
    if (next_ != kNone) return base_;
    const uint64_t ring = pending_ > overflow_.size() ? base_ + distance_to_next_bucket() : ~uint64_t{0};
    const uint64_t over = overflow_.empty() ? ~uint64_t{0} : overflow_.front().at;
    return ring < over ? ring : over;
  }

  /// A hint that lets the caller prefetch state: the id take() hands out next as
  /// far as is known now - the next of the cycle being handed out, else the first
  /// of the next cycle's bucket - or kNone. (An event scheduled for the current
  /// cycle meanwhile would come first.)
  uint32_t peek_next() const {
    if (next_ != kNone) return next_;
    const size_t b = static_cast<size_t>((base_ + 1) & mask_);
    return (occupied_[b >> 6] >> (b & 63)) & 1u ? link_[head_cell(b)] : kNone;
  }

  /// Takes the next event if its cycle is before `limit`: its id into `id`,
  /// its cycle into `at`. False (and nothing taken) otherwise.
  bool take(uint64_t limit, uint64_t& at, uint32_t& id) {
    if (next_ == kNone && !open_next(limit)) return false;
    if (base_ >= limit) return false;
    at = base_;
    id = next_;
    next_ = link_[id];  // read now: handling `id` may schedule it again, which rewrites its link
    --pending_;
    return true;
  }

 private:
  /// An event beyond the window: its cycle and its place in scheduling order.
  struct Far {
    uint64_t at, order;
    uint32_t id;
    bool operator>(const Far& o) const { return at != o.at ? at > o.at : order > o.order; }
  };

  /// The link cell that heads bucket `b`'s list (after the ids' own links).
  uint32_t head_cell(size_t b) const { return ids_ + static_cast<uint32_t>(b); }

  /// The current cycle is used up: opens the next one if it is before `limit`
  /// (kept out of line so that take(), called once per event, stays small).
  __attribute__((noinline)) bool open_next(uint64_t limit) {
    if (pending_ == 0) return false;
    const uint64_t next = next_cycle();
    if (next >= limit || next >= *fence_) return false;
    open_batch(next);
    return true;
  }

  /// An event beyond the window waits in the overflow heap (kept out of line:
  /// schedule() is inlined into every caller).
  __attribute__((noinline)) void schedule_far(uint64_t at, uint32_t id) {
    overflow_.push_back({at, far_order_++, id});
    std::push_heap(overflow_.begin(), overflow_.end(), std::greater<>());
  }

  /// Appends `id` (its link already kNone) to the bucket of cycle `at`.
  void put(uint64_t at, uint32_t id) {
    const size_t b = static_cast<size_t>(at & mask_);
    link_[tail_[b]] = id;
    tail_[b] = id;
    occupied_[b >> 6] |= uint64_t{1} << (b & 63);
  }

  /// Buckets from base's to the first non-empty one (the ring is not empty).
  uint64_t distance_to_next_bucket() const {
    const size_t n = tail_.size(), start = static_cast<size_t>(base_ & mask_);
    size_t w = start >> 6;
    uint64_t bits = occupied_[w] & (~uint64_t{0} << (start & 63));
    for (size_t k = 0; bits == 0; ++k) {
      w = w + 1 == occupied_.size() ? 0 : w + 1;
      bits = occupied_[w];
      if (k > occupied_.size()) break;  // unreachable while the ring holds an event
    }
    const size_t b = (w << 6) + static_cast<size_t>(__builtin_ctzll(bits));
    return (b + n - start) & mask_;
  }

  /// Moves the window to start at `cycle` and makes its bucket the list being handed out.
  void open_batch(uint64_t cycle) {
    base_ = cycle;
    while (!overflow_.empty() && overflow_.front().at - base_ <= mask_) {
      const Far f = overflow_.front();
      std::pop_heap(overflow_.begin(), overflow_.end(), std::greater<>());
      overflow_.pop_back();
      link_[f.id] = kNone;
      put(f.at, f.id);
    }
    const size_t b = static_cast<size_t>(cycle & mask_);
    next_ = link_[head_cell(b)];
    batch_tail_ = tail_[b];
    tail_[b] = head_cell(b);  // the bucket is empty again (its head cell is rewritten by the next put)
    occupied_[b >> 6] &= ~(uint64_t{1} << (b & 63));
  }

  uint32_t ids_;
  uint64_t mask_;
  uint64_t base_ = 0;               // the window's first cycle; the cycle being handed out
  std::vector<uint32_t> tail_;      // per bucket: the cell whose link ends its list (its head cell when empty)
  std::vector<uint64_t> occupied_;  // bit per bucket: list not empty
  std::vector<uint32_t> link_;      // per id: the next id in its list; then one head cell per bucket
  uint32_t next_ = kNone;           // the next id of the cycle being handed out, or kNone
  uint32_t batch_tail_ = kNone;     // the last id of the cycle being handed out
  std::vector<Far> overflow_;       // a min-heap by (cycle, scheduling order)
  uint64_t far_order_ = 0;
  uint64_t pending_ = 0;
  static constexpr uint64_t kNoFence = ~uint64_t{0};
  const uint64_t* fence_ = &kNoFence;
};

}  // namespace vbsim::hw
