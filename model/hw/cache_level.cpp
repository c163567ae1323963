#include "hw/cache_level.h"

namespace vbsim::hw {

CacheLevel::CacheLevel(const CacheConfig& config)
    : tags_(config.size_bytes / (config.ways * config.line_bytes), config.ways),
      hit_latency_(config.hit_latency),
      mshrs_(config.mshrs),
      flight_line_(config.mshrs, LruCache::kNoLine),
      fill_(config.mshrs, 0),
      order_(config.mshrs, 0),
      pending_from_(config.mshrs),
      in_flight_per_set_(tags_.sets(), 0) {
  index_bits_ = 0;
  while ((uint64_t{1} << index_bits_) < config.mshrs) ++index_bits_;
  index_mask_ = (uint64_t{1} << index_bits_) - 1;
  ring_.assign(size_t{1} << index_bits_, 0);
  for (uint32_t i = 0; i < config.mshrs; ++i) ring_[i] = i;  // all free at cycle 0, in index order
  due_.reserve(config.mshrs);
}

void CacheLevel::retire_slow(uint64_t horizon) {
  // The due fills, from pending_from_ on, in (fill cycle, claim order) order:
  // the ring orders equal fills by index, so a run of them is re-sorted by claim.
  while (pending_from_ < mshrs_ && fill_of_key(ring_at(pending_from_)) <= horizon) {
    const uint64_t fill = fill_of_key(ring_at(pending_from_));
    uint32_t end = pending_from_ + 1;
    while (end < mshrs_ && fill_of_key(ring_at(end)) == fill) ++end;
    if (end == pending_from_ + 1) {
      install(static_cast<uint32_t>(ring_at(pending_from_) & index_mask_));
    } else {
      due_.clear();
      for (uint32_t k = pending_from_; k < end; ++k) {
        const uint32_t i = static_cast<uint32_t>(ring_at(k) & index_mask_);
        size_t at = due_.size();
        due_.push_back(i);
        for (; at > 0 && order_[due_[at - 1]] > order_[i]; --at) due_[at] = due_[at - 1];
        due_[at] = i;
      }
      for (const uint32_t i : due_) install(i);
    }
    pending_from_ = end;
  }
  next_fill_ = pending_from_ < mshrs_ ? fill_of_key(ring_at(pending_from_)) : ~uint64_t{0};
}

}  // namespace vbsim::hw
