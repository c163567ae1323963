// EventWheel: the cycle engine's pending events, handed out in the order of
// (cycle, id): by cycle, and within one cycle by increasing id. Each id has
// at most one pending event (a busy slot's current step, the ray source).
//
// A calendar queue: a ring of 2^k buckets, one per cycle of the window
// [base, base + 2^k), each an intrusive list of ids, with a bitmap of the
// non-empty buckets; events beyond the window wait in an overflow min-heap and
// move into the ring as the window advances. Taking the next cycle gathers its
// bucket into a batch sorted by id. An event scheduled for the cycle being
// handed out joins the batch in id order, so the order is exactly that of a
// min-heap of (cycle, id) keys. Nothing is allocated after construction.
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
      : mask_((uint64_t{1} << window_log2) - 1), head_(size_t{1} << window_log2, kNone),
        occupied_(((size_t{1} << window_log2) + 63) / 64, 0), link_(ids, kNone), batch_(ids) {
    overflow_.reserve(ids);
  }

  bool empty() const { return pending_ == 0; }

  /// Schedules `id` (not pending) at cycle `at`, which is not before the cycle
  /// last handed out.
  __attribute__((always_inline)) void schedule(uint64_t at, uint32_t id) {
    ++pending_;
    if (in_batch_ && at == base_) {
      // Joins the batch being handed out, in id order among those still to come.
      uint32_t i = batch_end_++;
      while (i > batch_next_ && batch_[i - 1] > id) {
        batch_[i] = batch_[i - 1];
        --i;
      }
      batch_[i] = id;
      return;
    }
    if (at - base_ > mask_) return schedule_far(at, id);
    put(at, id);
  }

  /// Cycle of the next event; the wheel is not empty.
  uint64_t next_cycle() const {
    if (in_batch_ && batch_next_ < batch_end_) return base_;
    const uint64_t ring = ring_count_ ? base_ + distance_to_next_bucket() : ~uint64_t{0};
    const uint64_t over = overflow_.empty() ? ~uint64_t{0} : overflow_.front() >> kIdBits;
    return ring < over ? ring : over;
  }

  /// Id of the event take() hands out next if it is in the cycle being handed
  /// out, else kNone (lets the caller prefetch its state).
  uint32_t peek_same_cycle() const { return batch_next_ < batch_end_ ? batch_[batch_next_] : kNone; }

  /// Takes the next event if its cycle is before `limit`: its id into `id`,
  /// its cycle into `at`. False (and nothing taken) otherwise.
  bool take(uint64_t limit, uint64_t& at, uint32_t& id) {
    if (!(in_batch_ && batch_next_ < batch_end_) && !open_next(limit)) return false;
    if (base_ >= limit) return false;
    at = base_;
    id = batch_[batch_next_++];
    --pending_;
    return true;
  }

 private:
  static constexpr int kIdBits = 24;

  /// The batch is used up: opens the next cycle's if it is before `limit`
  /// (kept out of line so that take(), called once per event, stays small).
  __attribute__((noinline)) bool open_next(uint64_t limit) {
    in_batch_ = false;
    if (pending_ == 0) return false;
    const uint64_t next = next_cycle();
    if (next >= limit) return false;
    open_batch(next);
    return true;
  }  // ids below 2^24; cycles below 2^40

  /// An event beyond the window waits in the overflow heap (kept out of line:
  /// schedule() is inlined into every caller).
  __attribute__((noinline)) void schedule_far(uint64_t at, uint32_t id) {
    overflow_.push_back((at << kIdBits) | id);
    std::push_heap(overflow_.begin(), overflow_.end(), std::greater<>());
  }

  void put(uint64_t at, uint32_t id) {
    const size_t b = static_cast<size_t>(at & mask_);
    link_[id] = head_[b];
    head_[b] = id;
    occupied_[b >> 6] |= uint64_t{1} << (b & 63);
    ++ring_count_;
  }

  /// Buckets from base's to the first non-empty one (the ring is not empty).
  uint64_t distance_to_next_bucket() const {
    const size_t n = head_.size(), start = static_cast<size_t>(base_ & mask_);
    size_t w = start >> 6;
    uint64_t bits = occupied_[w] & (~uint64_t{0} << (start & 63));
    for (size_t k = 0; bits == 0; ++k) {
      w = w + 1 == occupied_.size() ? 0 : w + 1;
      bits = occupied_[w];
      if (k > occupied_.size()) break;  // unreachable while ring_count_ > 0
    }
    const size_t b = (w << 6) + static_cast<size_t>(__builtin_ctzll(bits));
    return (b + n - start) & mask_;
  }

  /// Moves the window to start at `cycle` and gathers its events, sorted by id.
  void open_batch(uint64_t cycle) {
    base_ = cycle;
    while (!overflow_.empty() && (overflow_.front() >> kIdBits) - base_ <= mask_) {
      const uint64_t key = overflow_.front();
      std::pop_heap(overflow_.begin(), overflow_.end(), std::greater<>());
      overflow_.pop_back();
      put(key >> kIdBits, static_cast<uint32_t>(key & ((uint64_t{1} << kIdBits) - 1)));
    }
    const size_t b = static_cast<size_t>(cycle & mask_);
    batch_next_ = batch_end_ = 0;
    for (uint32_t id = head_[b]; id != kNone; id = link_[id]) {
      uint32_t i = batch_end_++;  // insertion sort: a bucket holds a few ids
      while (i > 0 && batch_[i - 1] > id) {
        batch_[i] = batch_[i - 1];
        --i;
      }
      batch_[i] = id;
    }
    ring_count_ -= batch_end_;
    head_[b] = kNone;
    occupied_[b >> 6] &= ~(uint64_t{1} << (b & 63));
    in_batch_ = true;
  }

  uint64_t mask_;
  uint64_t base_ = 0;                 // the window's first cycle; the batch's cycle
  std::vector<uint32_t> head_;        // per bucket: first id of its list
  std::vector<uint64_t> occupied_;    // bit per bucket: list not empty
  std::vector<uint32_t> link_;        // per id: next id in its bucket's list
  std::vector<uint32_t> batch_;       // the cycle being handed out, ids sorted
  uint32_t batch_next_ = 0, batch_end_ = 0;
  bool in_batch_ = false;
  std::vector<uint64_t> overflow_;    // (cycle << kIdBits | id), a min-heap
  uint64_t pending_ = 0, ring_count_ = 0;
};

}  // namespace vbsim::hw
