// TimedQueue: entries stamped with a cycle, taken out by cycle and, within a
// cycle, in the order they were put in: what a min-heap of (cycle, push order)
// gives, at a constant cost per entry. The memory modules keep their work for
// later cycles in it (the memory clock's cycles, the L2's requests to send and
// responses to apply, hw/memory/memory_clock.h and l2_cache.h).
//
// A calendar queue: a ring of 2^k buckets, one per cycle of the window
// [base, base + 2^k), each a FIFO list threaded through a pool of entries,
// with a bitmap of the non-empty buckets; an entry outside the window waits in
// an overflow min-heap of (cycle, push order). Taking compares the ring's
// earliest entry with the heap's, so the order never depends on where an
// entry waited. The window moves up as entries are taken (every entry left is
// at or after the one taken). Nothing is allocated once the pool and the heap
// have grown to the most entries waiting at once.
#pragma once
#include <algorithm>
#include <cstdint>
#include <functional>
#include <vector>

#include "hw/pending_cycle.h"

namespace vbsim::hw {

template <class Payload>
class TimedQueue {
 public:
  explicit TimedQueue(uint32_t window_log2 = 10)
      : mask_((uint64_t{1} << window_log2) - 1), head_(size_t{1} << window_log2, kNone),
        tail_(size_t{1} << window_log2, kNone), occupied_(((size_t{1} << window_log2) + 63) / 64, 0) {}

  bool empty() const { return size_ == 0; }
  size_t size() const { return size_; }
  /// The earliest entry's cycle, or kPendingCycle when empty.
  uint64_t earliest() const { return earliest_; }

  /// Puts `payload` in at `cycle` (any cycle, earlier ones too).
  void push(uint64_t cycle, const Payload& payload) {
    const uint32_t n = new_node(cycle, payload);
    ++size_;
    if (cycle < earliest_) earliest_ = cycle;
    if (cycle >= base_ && cycle - base_ <= mask_) {
      const size_t b = cycle & mask_;
      if (head_[b] == kNone) {
        head_[b] = n;
        occupied_[b >> 6] |= uint64_t{1} << (b & 63);
      } else {
        pool_[tail_[b]].next = n;
      }
      tail_[b] = n;
      if (cycle < ring_min_) ring_min_ = cycle;
      return;
    }
    far_.push_back({cycle, pool_[n].order, n});
    std::push_heap(far_.begin(), far_.end(), std::greater<>());
  }

  /// Takes the earliest entry (by cycle, then push order) when its cycle is at
  /// or before `now`: its cycle and payload into `cycle` and `payload`.
  bool pop_due(uint64_t now, uint64_t& cycle, Payload& payload) {
    if (earliest_ > now) return false;
    uint32_t n;
    if (ring_first()) {
      const size_t b = ring_min_ & mask_;
      n = head_[b];
      head_[b] = pool_[n].next;
      if (head_[b] == kNone) {
        tail_[b] = kNone;
        occupied_[b >> 6] &= ~(uint64_t{1} << (b & 63));
        base_ = ring_min_;  // every entry of the ring is at or after it
        ring_min_ = next_ring_cycle();
      }
    } else {
      n = far_.front().node;
      std::pop_heap(far_.begin(), far_.end(), std::greater<>());
      far_.pop_back();
    }
    cycle = pool_[n].cycle;
    payload = pool_[n].payload;
    pool_[n].next = free_;
    free_ = n;
    --size_;
    if (ring_min_ == kPendingCycle && cycle > base_) base_ = cycle;  // an empty ring follows the time taken
    earliest_ = std::min(ring_min_, far_.empty() ? kPendingCycle : far_.front().cycle);
    return true;
  }

 private:
  static constexpr uint32_t kNone = ~uint32_t{0};
  struct Node {
    uint64_t cycle, order;
    Payload payload;
    uint32_t next;
  };
  struct Far {
    uint64_t cycle, order;
    uint32_t node;
    bool operator>(const Far& o) const { return cycle != o.cycle ? cycle > o.cycle : order > o.order; }
  };

  /// The next entry is the ring's earliest (not the overflow heap's).
  bool ring_first() const {
    return ring_min_ != kPendingCycle &&
           (far_.empty() || far_.front().cycle > ring_min_ ||
            (far_.front().cycle == ring_min_ && far_.front().order > pool_[head_[ring_min_ & mask_]].order));
  }
  uint32_t new_node(uint64_t cycle, const Payload& payload) {
    const uint64_t order = order_++;
    if (free_ != kNone) {
      const uint32_t n = free_;
      free_ = pool_[n].next;
      pool_[n] = {cycle, order, payload, kNone};
      return n;
    }
    pool_.push_back({cycle, order, payload, kNone});
    return static_cast<uint32_t>(pool_.size() - 1);
  }
  /// The ring's earliest cycle (from base_ on), or kPendingCycle when the ring is empty.
  uint64_t next_ring_cycle() const {
    const size_t words = occupied_.size();
    const size_t start = base_ & mask_;
    size_t w = start >> 6;
    uint64_t bits = occupied_[w] & (~uint64_t{0} << (start & 63));
    for (size_t seen = 0; seen <= words; ++seen) {
      if (bits) {
        const size_t b = (w << 6) + static_cast<size_t>(__builtin_ctzll(bits));
        return base_ + ((b - start) & mask_);
      }
      w = (w + 1) % words;
      bits = occupied_[w];
      if (w == start >> 6) bits &= (start & 63) ? ~(~uint64_t{0} << (start & 63)) : ~uint64_t{0};
    }
    return kPendingCycle;
  }

  uint64_t mask_;
  std::vector<uint32_t> head_, tail_;  // per bucket: first and last entry, kNone when empty
  std::vector<uint64_t> occupied_;     // per bucket: one bit, set when it has entries
  std::vector<Node> pool_;
  std::vector<Far> far_;               // min-heap of the entries outside the window
  uint32_t free_ = kNone;
  uint64_t base_ = 0, order_ = 0, size_ = 0;
  uint64_t ring_min_ = kPendingCycle, earliest_ = kPendingCycle;
};

}  // namespace vbsim::hw
