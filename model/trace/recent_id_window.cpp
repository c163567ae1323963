#include "trace/recent_id_window.h"

#include <stdexcept>

namespace vbsim {

RecentIdWindow::RecentIdWindow(std::size_t capacity) : capacity_(capacity) {
  if (capacity == 0) throw std::invalid_argument("RecentIdWindow: capacity must be at least 1");
}

std::size_t RecentIdWindow::slot_of(std::size_t k) const {
  const std::size_t oldest = (next_ + capacity_ - size_) % capacity_;
  return (oldest + k) % capacity_;
}

std::size_t RecentIdWindow::push(int64_t id) {
  if (ascending_ && size_ > 0 && id <= ids_[slot_of(size_ - 1)]) {
    // From now on lookup needs an index: build it from the ring once.
    ascending_ = false;
    index_.reserve(size_);
    for (std::size_t k = 0; k < size_; ++k) index_.emplace(ids_[slot_of(k)], slot_of(k));
  }
  const std::size_t slot = next_;
  if (size_ == capacity_) {
    if (!ascending_) index_.erase(ids_[slot]);
    ids_[slot] = id;
  } else {
    ids_.push_back(id);  // while filling, slot == size_: the ring grows with the rays
    ++size_;
  }
  if (!ascending_) index_[id] = slot;
  next_ = (next_ + 1) % capacity_;
  return slot;
}

int64_t RecentIdWindow::find(int64_t id) const {
  if (size_ == 0) return -1;
  if (!ascending_) {
    const auto it = index_.find(id);
    return it == index_.end() ? -1 : static_cast<int64_t>(it->second);
  }
  // Sorted ring. Dense ids (each one more than the last) put `id` exactly
  // newest - id positions back; try that before bisecting.
  const int64_t newest = ids_[slot_of(size_ - 1)];
  if (id > newest || id < ids_[slot_of(0)]) return -1;
  const int64_t back = newest - id;
  if (back < static_cast<int64_t>(size_)) {
    const std::size_t guess = slot_of(size_ - 1 - static_cast<std::size_t>(back));
    if (ids_[guess] == id) return static_cast<int64_t>(guess);
  }
  std::size_t lo = 0, hi = size_;  // the k with ids(k) == id lies in [lo, hi)
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    const int64_t v = ids_[slot_of(mid)];
    if (v == id) return static_cast<int64_t>(slot_of(mid));
    if (v < id) lo = mid + 1;
    else hi = mid;
  }
  return -1;
}

}  // namespace vbsim
