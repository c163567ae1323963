// FreeCycleRing: the free cycles of a pool of identical resources (a cache's
// MSHRs, the DRAM channel's request slots), kept sorted in a ring so that the
// one that frees first is the front: taking it is one load, and its new free
// cycle goes back in from the tail (resources are released nearly in order, so
// few places move). Which resource of the pool is used never matters, only
// when one is free. No allocation after construction.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vbsim::hw {

class FreeCycleRing {
 public:
  /// `size` >= 1 resources, every one free from cycle 0.
  explicit FreeCycleRing(uint32_t size) : size_(size) {
    uint32_t bits = 0;
    while ((uint64_t{1} << bits) < size) ++bits;
    ring_.assign(size_t{1} << bits, 0);
    mask_ = (uint32_t{1} << bits) - 1;
  }

  uint32_t size() const { return size_; }
  /// The earliest free cycle of any resource.
  uint64_t front() const { return ring_[head_]; }
  /// The resource at the front is taken until `cycle`: it leaves the front and
  /// comes back in at its sorted place.
  __attribute__((always_inline)) void take_front(uint64_t cycle) {
    head_ = (head_ + 1) & mask_;
    place_from(size_ - 1, cycle);
  }
  /// The resource at sorted position `k` (0: the front) frees at `cycle`
  /// instead, no later than before: it moves toward the front to its place.
  void lower(uint32_t k, uint64_t cycle) { place_from(k, cycle); }

 private:
  uint64_t& at(uint32_t k) { return ring_[(head_ + k) & mask_]; }
  __attribute__((always_inline)) void place_from(uint32_t k, uint64_t cycle) {
    for (; k > 0 && at(k - 1) > cycle; --k) at(k) = at(k - 1);
    at(k) = cycle;
  }

  std::vector<uint64_t> ring_;  // a power-of-two size >= size_; the ring is size_ places from head_
  uint32_t size_, head_ = 0, mask_;
};

}  // namespace vbsim::hw
