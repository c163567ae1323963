// ReadyQueue: the trace positions of the rays ready for emission, taken
// smallest first (trace order among ready rays). Rays mostly become ready in
// trace order, so positions that come in increasing order go to a FIFO ring
// (constant time, no allocation); only one that comes after a larger one goes
// to a min-heap. At most `capacity` positions are queued at once.
#pragma once
#include <algorithm>
#include <cstdint>
#include <functional>
#include <vector>

namespace vbsim::hw {

class ReadyQueue {
 public:
  explicit ReadyQueue(uint32_t capacity) {
    size_t size = 16;
    while (size < capacity) size *= 2;
    ring_.assign(size, 0);
    mask_ = size - 1;
    heap_.reserve(64);
  }

  bool empty() const { return head_ == tail_ && heap_.empty(); }
  size_t size() const { return static_cast<size_t>(tail_ - head_) + heap_.size(); }
  void push(uint64_t pos) {
    if (head_ == tail_ || pos > ring_[(tail_ - 1) & mask_]) {
      ring_[tail_ & mask_] = pos;
      ++tail_;
    } else {
      heap_.push_back(pos);
      std::push_heap(heap_.begin(), heap_.end(), std::greater<uint64_t>());
    }
  }
  /// The smallest queued position (not empty).
  uint64_t top() const {
    if (heap_.empty()) return ring_[head_ & mask_];
    if (head_ == tail_) return heap_.front();
    return std::min(ring_[head_ & mask_], heap_.front());
  }
  void pop() {
    if (!heap_.empty() && (head_ == tail_ || heap_.front() < ring_[head_ & mask_])) {
      std::pop_heap(heap_.begin(), heap_.end(), std::greater<uint64_t>());
      heap_.pop_back();
    } else {
      ++head_;
    }
  }

 private:
  std::vector<uint64_t> ring_;  // increasing from head_ to tail_
  size_t mask_;
  uint64_t head_ = 0, tail_ = 0;
  std::vector<uint64_t> heap_;
};

}  // namespace vbsim::hw
